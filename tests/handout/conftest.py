"""Tests of the handouts: catalogues, the PDF's pages, the web page (in a real browser), kinepoly handout.

Shared support for every layer is at tests/ (scenes.py; chromium.py: Debian's chromium driven by playwright).
"""
