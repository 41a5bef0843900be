"""``kinepoly bench``: error against run time, for one scene, against a 50-digit reference.

* ``reference``: the scene solved in mpmath (optional dependency: ``pip install 'kinepoly[bench]'``);
* ``motion``: link motions to the reported quantities, in any arithmetic;
* ``closed_forms``, ``series``: the standard mechanisms' closed forms, the course text's series;
* ``methods``: every method as a timed computation over an array of inputs;
* ``run``, ``sweep``: the bench at the scene's input, and at the rows of ``kinepoly.sweep`` (its range);
* ``plot``: the work-precision diagram and the sweep as image bytes (matplotlib, imported there only);
* ``cases``: the stability suite's scenes (scaled, translated, near dead points) and the texts the tests share;
* ``report``: what ``kinepoly bench`` prints, as tables or JSON (the command line: ``kinepoly.cli.bench``).

Nothing is imported here, so that ``kinepoly solve`` does not pay for the bench.
"""

__all__: list[str] = []
