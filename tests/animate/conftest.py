"""Tests of the motion: frames against the sweep, GIF/MP4/HTML, kinepoly animate, the notebook API.

Shared support for every layer is at tests/ (scenes.py; chromium.py: Debian's chromium driven by playwright).
"""
