"""Sweeps: the position plan and the construction executed over an array of inputs at once.

``sweep(scene, steps=3600)`` returns a ``SweepResult``: one column per asked quantity over the
input's turn (or range), each row with its status; ``csv_text`` and ``plot_png`` present it.
``sweep_family(scene, {"B@3": xy, ...}, steps=360)`` sweeps a family of the scene's mechanism whose
points differ between members, the plan run once for all (``FamilyResult``).
``kinepoly.sweep.rows`` gives a row's link poses and a ``[guess]`` that pins a solve there to the
sweep's assembly.

The face of the package: ``from kinepoly.sweep import sweep, SweepResult`` (docs/python.md).
"""

from kinepoly.sweep.family import FamilyColumn, FamilyResult, member_scene, sweep_family
from kinepoly.sweep.result import STATUS, Column, SweepResult
from kinepoly.sweep.run import PreparedSweep, cycle_turns, prepare_sweep, run_sweep, sweep

__all__ = ["STATUS", "Column", "FamilyColumn", "FamilyResult", "PreparedSweep", "SweepResult", "cycle_turns",
           "member_scene", "prepare_sweep", "run_sweep", "sweep", "sweep_family"]


def _result_png(result: SweepResult) -> bytes:
    """A notebook shows a sweep as its plots (``SweepResult._repr_png_``, set here, so that the result does not
    import the plotting code above it)."""
    from kinepoly.sweep.plots import plot_png

    return plot_png(result)


setattr(SweepResult, "_repr_png_", _result_png)  # noqa: B010 (a method the class does not declare)
