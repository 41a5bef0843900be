"""Tests of the scene layer: the TOML loader, its units, and its messages (FILE:LINE: key.path: ...).

Shared support for every layer is at tests/ (scenes.py: the examples and random mechanisms).
"""
