"""``kinepoly bench``: error against run time, for one scene, against a 50-digit reference.

* ``reference``: the scene solved in mpmath (optional dependency: ``pip install 'kinepoly[bench]'``);
* ``motion``: link motions to the reported quantities, in any arithmetic;
* ``closed_forms``, ``series``: the standard mechanisms' closed forms, the course text's series;
* ``methods``: every method as a timed computation over an array of inputs;
* ``run``, ``sweep``: the bench at the scene's input, and over a full turn;
* ``plot``: the work-precision diagram and the sweep (matplotlib, imported there only);
* ``cases``: the stability suite's scenes (scaled, translated, near dead points);
* ``command``: the CLI's arguments and output.

Nothing is imported here, so that ``kinepoly solve`` does not pay for the bench.
"""

__all__: list[str] = []
