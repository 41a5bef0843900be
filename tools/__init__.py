"""Developer tools, run from the repository's root; not part of the installed package.

* ``regenerate_drawings``: ``python3 tools/regenerate_drawings.py [--check]`` redraws ``drawings/``
  from ``examples/`` (``--check`` writes nothing and exits 1 when a drawing is stale);
* ``compare_drawings``: drawings compared as a reviewer would (SVG and DXF canonically, PNG
  within a grey-level tolerance); the drawings test uses it.
"""
