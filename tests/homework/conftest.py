"""Tests of the homework: answers files, checking and diagnoses, variants, kinepoly check and variants.

Shared support for every layer is at tests/ (scenes.py: the examples and random mechanisms).
"""
