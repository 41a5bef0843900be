"""Tests of what kinepoly solve says: the table, the JSON of the contract, the steps, exit statuses.

Shared support for every layer is at tests/ (scenes.py: the examples and random mechanisms).
"""
