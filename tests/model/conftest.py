"""Tests of the model layer: link poses (one row and arrays of rows) and the mechanism a scene builds.

Shared support for every layer is at tests/ (scenes.py: the examples and random mechanisms).
"""
