"""Sweeps: the position plan and the construction executed over an array of inputs at once.

``sweep(scene, steps=3600)`` returns a ``SweepResult``: one column per asked quantity over the
input's turn (or range), each row with its status; ``csv_text`` and ``plot_png`` present it.
``kinepoly.sweep.rows`` gives a row's link poses and a ``[guess]`` that pins a solve there to the
sweep's assembly.
"""

from kinepoly.sweep.run import STATUS, Column, PreparedSweep, SweepResult, cycle_turns, prepare_sweep, run_sweep, sweep

__all__ = ["STATUS", "Column", "PreparedSweep", "SweepResult", "cycle_turns", "prepare_sweep", "run_sweep", "sweep"]
