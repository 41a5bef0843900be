"""Tests of the engine: the construction, gears and cams, Newton groups, the instant centers, the examples'
closed forms, stability.

Shared support for every layer is at tests/ (scenes.py: the examples and random mechanisms).
"""
