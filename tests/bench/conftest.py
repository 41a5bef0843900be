"""Tests of kinepoly bench: closed forms, series, the methods and the 50-digit reference, the command.

Shared support for every layer is at tests/ (scenes.py: the examples and random mechanisms).
"""
