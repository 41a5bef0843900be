"""Sweeps: the position plan and the construction executed over an array of inputs at once.

``sweep(scene, steps=3600)`` returns a ``SweepResult``: one column per asked quantity over the
input's turn (or range), each row with its status; ``csv_text`` and ``plot_png`` present it.
``kinepoly.sweep.rows`` gives a row's link poses and a ``[guess]`` that pins a solve there to the
sweep's assembly.

The face of the package: ``from kinepoly.sweep import sweep, SweepResult`` (docs/python.md).
"""

from kinepoly.sweep.result import STATUS, Column, SweepResult
from kinepoly.sweep.run import PreparedSweep, cycle_turns, prepare_sweep, run_sweep, sweep

__all__ = ["STATUS", "Column", "PreparedSweep", "SweepResult", "cycle_turns", "prepare_sweep", "run_sweep", "sweep"]


def _result_png(result: SweepResult) -> bytes:
    """A notebook shows a sweep as its plots (``SweepResult._repr_png_``, set here, so that the result does not
    import the plotting code above it)."""
    from kinepoly.sweep.plots import plot_png

    return plot_png(result)


setattr(SweepResult, "_repr_png_", _result_png)  # noqa: B010 (a method the class does not declare)
