"""Tests of the sweeps: the input over a turn, row by row against solve, kinepoly sweep.

Shared support for every layer is at tests/ (scenes.py; sweep_support.py: one row compared with solve).
"""
