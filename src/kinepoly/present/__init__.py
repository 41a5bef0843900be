"""What a solution says to people and programs: reports, scales, and the words of the construction in any language.

* ``report``: the contract's JSON (``to_json``), the readable table and the steps of ``kinepoly solve``;
* ``centers``: the instant centers' part of those (JSON, table rows, Kennedy steps);
* ``scales``: the polygon scales kv and ka (the scene's ``[draw]``, else a round number);
* ``phrasing``: every step's sentence from its data, in the catalogue's language;
* ``catalogue``, ``messages/``: the message catalogues, one TOML file per language.

Pure functions: the command line (``kinepoly.cli``) prints and writes what they return.
"""
