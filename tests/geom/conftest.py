"""Tests of the geometry layer: the periodic cubic spline of a cam's ``points`` profile.

Shared support for every layer is at tests/ (scenes.py: the examples and random mechanisms).
"""
