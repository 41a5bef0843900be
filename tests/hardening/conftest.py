"""Hardening (issue 15): every input ends in a clear message and exit 2 or 3, or a correct result.

Regression tests of the fuzzing run's reproducers (each the four-bar ``BASE`` plus one change),
a bounded fuzz of mutated scenes through ``solve``, ``draw`` and ``handout`` in-process, and the
cost of long chains of four-bar loops (``kinepoly.bench.chain``).
"""
