"""Tests of the check: the independent analytic solution, the cross-check and the accuracy estimates.

Shared support for every layer is at tests/ (scenes.py: the examples and random mechanisms).
"""
