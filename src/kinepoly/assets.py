"""The package's own files that its pages include (scripts and styles under a package's ``static/``), read
through importlib.resources, so that an installed package (a wheel, even one imported from its zip) reads them
as the source tree does. pyproject.toml's package-data ships them."""

from __future__ import annotations

from functools import cache
from importlib.resources import files

__all__ = ["static_text"]


@cache
def static_text(package: str, name: str) -> str:
    """The text of the file ``name`` in ``package``'s ``static/`` folder (``static_text("kinepoly.handout",
    "handout.js")``)."""
    return files(package).joinpath("static").joinpath(name).read_text(encoding="utf-8")
