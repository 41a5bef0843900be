"""Tests of the command line: exit codes, messages, options, the JSON contract's shape, kinepoly draw and check.

Shared support for every layer is at tests/ (cli_support.py: a command run in-process; scenes.py: the examples).
"""
