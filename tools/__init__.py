"""Developer tools, run from the repository's root; not part of the installed package.

* ``regenerate_drawings``: ``python3 tools/regenerate_drawings.py [--check]`` redraws ``drawings/``
  from ``examples/`` (``--check`` writes nothing and exits 1 when a drawing is stale);
* ``compare_drawings``: drawings compared as a reviewer would (SVG and DXF canonically, PNG
  within a grey-level tolerance); the drawings test uses it;
* ``fuzz``: ``python3 tools/fuzz.py --cases 3000 [--seed S] [--browser N]`` runs mutated examples
  through every command and prints the counts (exit statuses, problems, slow runs); the suite's
  ``tests/hardening/test_fuzz_v2.py`` runs a fixed few dozen of its cases.
* ``import_graph``: ``python3 tools/import_graph.py`` prints the package's import cycles and upward imports
  (a layer importing one above it); ``tests/hardening/test_import_layers.py`` holds them to none outside the engine.
"""
