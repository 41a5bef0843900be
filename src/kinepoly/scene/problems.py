"""Problems found in a TOML file, each placed at the line of its key path, and their wording.

A :class:`ProblemReport` collects ``FILE:LINE: key.path: what is wrong; what is expected``
problems and raises them all at once as one :class:`~kinepoly.errors.SceneError`; the
helpers here write values as TOML would and suggest the name a user probably meant.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Collection, Iterable

from msgspec import Struct, field

from kinepoly.errors import SceneError
from kinepoly.scene.lines import KeyPath, LineMap, dotted

__all__ = ["SHOWN", "ProblemReport", "no_such", "quoted", "show_value", "suggest", "unknown_key"]

SHOWN = 20
"""The most problems one report words. Beyond, problems are only counted ("and 9980 more problems"), and a
message given as a function (a did-you-mean each, a search of every name) is not made: refusing a file of
10,000 unknown names costs what refusing 20 does."""


class ProblemReport(Struct):
    """Collects problems, each placed at the line of its key path."""

    source: str
    lines: LineMap
    problems: list[tuple[int, str]] = field(default_factory=list)
    more: int = 0
    """Problems found beyond the first ``SHOWN``: counted, not worded."""

    def add(self, path: KeyPath, message: str | Callable[[], str]) -> None:
        """Place the problem at its line; ``message`` may be a function, called only for the first ``SHOWN``."""
        if len(self.problems) >= SHOWN:
            self.more += 1
            return
        line = self.lines.line_of(path)
        where = self.source if line is None else f"{self.source}:{line}"
        text = message if isinstance(message, str) else message()
        self.problems.append((line or 0, f"{where}: {dotted(path)}: {text}"))

    def line(self, path: KeyPath) -> int:
        return self.lines.line_of(path) or 0

    def raise_if_any(self) -> None:
        if self.problems:
            ordered = sorted(dict.fromkeys(self.problems), key=lambda item: item[0])
            more = [f"{self.source}: (file): and {self.more} more problems, not shown; expected these fixed first"]
            raise SceneError([text for _, text in ordered] + (more if self.more else []))


def show_value(value: object, limit: int = 60) -> str:
    """A value as TOML would write it, cut short when long."""
    text = _toml_text(value)
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _toml_text(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        import json  # loaded for a message only, not on every start

        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, float) and not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, list):
        return "[" + ", ".join(_toml_text(item) for item in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{key} = {_toml_text(item)}" for key, item in value.items()) + " }"
    return str(value)


def quoted(names: Iterable[str], limit: int = 12) -> str:
    names = list(names)
    shown = ", ".join(f'"{name}"' for name in names[:limit])
    return shown + (", …" if len(names) > limit else "")


def suggest(word: str, options: Collection[str]) -> str:
    import difflib  # loaded for a message only, not on every start

    close = difflib.get_close_matches(word, list(options), n=1)
    if close:
        return f'did you mean "{close[0]}"?'
    if not options:
        return "expected none here"
    return f"expected one of {quoted(sorted(options))}"


def no_such(kind: str, name: str, known: Collection[str]) -> str:
    return f'no {kind} "{name}"; {suggest(name, known)}'


def unknown_key(key: str, allowed: Collection[str]) -> str:
    return f"unknown key; {suggest(key, allowed)}"
