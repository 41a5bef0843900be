"""The loop-closure method (METU 4.2, RO 2.2.1): a second, analytic way to the velocities and accelerations.

The mechanism's independent loops (``contours``), each written as a sum of vectors in complex form and
differentiated; the unknown rates found loop by loop by Cramer's rule, or as one coupled system where
the loops share more unknowns than one loop can give (``rates``); the derivation as text (``text``).
It uses the engine's positions only, never its polygons.
"""

from kinepoly.loops.contours import Loop, LoopMethodError, Term, choose_loops, loop_count
from kinepoly.loops.rates import Block, LoopSolution, solve_loops
from kinepoly.loops.result import loop_method_solution, loops_json

__all__ = ["Block", "Loop", "LoopMethodError", "LoopSolution", "Term", "choose_loops", "loop_count",
           "loop_method_solution", "loops_json", "solve_loops"]
