"""Tests of the drawings: the sheet, its SVG, DXF, PNG and PDF files, gears and cams on it, and drawings/ kept current.

Shared support for every layer is at tests/ (scenes.py: the examples and random mechanisms); the drawings are
compared with tools/compare_drawings.py.
"""
