"""Problems found in a TOML file, each placed at the line of its key path, and their wording.

A :class:`ProblemReport` collects ``FILE:LINE: key.path: what is wrong; what is expected``
problems and raises them all at once as one :class:`~kinepoly.errors.SceneError`; the
helpers here write values as TOML would and suggest the name a user probably meant.
"""

from __future__ import annotations

import difflib
import json
import math
from collections.abc import Collection, Iterable
from dataclasses import dataclass, field

from kinepoly.errors import SceneError
from kinepoly.scene.lines import KeyPath, LineMap, dotted

__all__ = ["ProblemReport", "no_such", "quoted", "show_value", "suggest"]


@dataclass
class ProblemReport:
    """Collects problems, each placed at the line of its key path."""

    source: str
    lines: LineMap
    problems: list[tuple[int, str]] = field(default_factory=list)

    def add(self, path: KeyPath, message: str) -> None:
        line = self.lines.line_of(path)
        where = self.source if line is None else f"{self.source}:{line}"
        self.problems.append((line or 0, f"{where}: {dotted(path)}: {message}"))

    def line(self, path: KeyPath) -> int:
        return self.lines.line_of(path) or 0

    def raise_if_any(self) -> None:
        if self.problems:
            ordered = sorted(dict.fromkeys(self.problems), key=lambda item: item[0])
            raise SceneError([text for _, text in ordered])


def show_value(value: object, limit: int = 60) -> str:
    """A value as TOML would write it, cut short when long."""
    text = _toml_text(value)
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _toml_text(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
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
    close = difflib.get_close_matches(word, list(options), n=1)
    if close:
        return f'did you mean "{close[0]}"?'
    if not options:
        return "expected none here"
    return f"expected one of {quoted(sorted(options))}"


def no_such(kind: str, name: str, known: Collection[str]) -> str:
    return f'no {kind} "{name}"; {suggest(name, known)}'
