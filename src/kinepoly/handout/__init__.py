"""Teaching handouts: the problem, the construction step by step, the answers; PDF or one web page.

``kinepoly handout SCENE -o FILE.pdf`` and ``--html FILE.html`` (``cli.handout``). From Python::

    from kinepoly.handout import handout_html, handout_sheets, load_catalogue
    say = load_catalogue("tr")                       # or load_catalogue(messages="de.toml")
    handout, sheets = handout_sheets(solution, say)  # one render.primitives.Sheet per page
    handout, text = handout_html(solution, say)

The words come from a message catalogue per language (``present.catalogue``, ``present/messages/``); the
drawings from the render package's sheets; the step texts from the steps' data.
"""

from __future__ import annotations

from kinepoly.handout.build import handout_content, handout_sheets
from kinepoly.handout.content import Handout, Page
from kinepoly.handout.html import handout_html
from kinepoly.present.catalogue import Catalogue, load_catalogue, packaged_languages

__all__ = [
    "Catalogue",
    "Handout",
    "Page",
    "handout_content",
    "handout_html",
    "handout_sheets",
    "load_catalogue",
    "packaged_languages",
]
