"""The README's table of command-line options, generated from kinepoly's parser.

``python tools/cli_options.py`` rewrites the table between ``<!-- options: begin -->`` and
``<!-- options: end -->`` in README.md; ``--check`` only says whether it is up to date (exit 1
if not). ``tests/cli/test_cli_options.py`` keeps the two equal.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

from kinepoly.cli import parser

README = Path(__file__).resolve().parent.parent / "README.md"
BEGIN, END = "<!-- options: begin -->", "<!-- options: end -->"

__all__ = ["options_table", "rewrite"]


def _commands(root: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    sub = next(a for a in root._actions if isinstance(a, argparse._SubParsersAction))
    return dict(sub.choices)


def _cell(text: str) -> str:
    return re.sub(r"\s+", " ", text).replace("|", "\\|").strip()


def options_table() -> str:
    """One row per option of every command: the command, the option, what it does, its default."""
    rows = ["| command | option | what it does | default |", "| --- | --- | --- | --- |"]
    for name, command in _commands(parser()).items():
        for action in command._actions:
            if (not action.option_strings or action.help == argparse.SUPPRESS
                    or isinstance(action, argparse._HelpAction)):
                continue
            flags = ", ".join(action.option_strings)
            if action.metavar is not None or action.nargs != 0:
                flags += f" {action.metavar or action.dest.upper()}"
            default = action.default
            shown = "" if default is None or default is False else " ".join(map(str, default)) \
                if isinstance(default, (list, tuple)) else str(default)
            rows.append(f"| `{name}` | `{_cell(flags)}` | "
                        f"{_cell((action.help or '').replace('%%', '%'))} | {_cell(shown)} |")
    return "\n".join(rows)


def rewrite(text: str) -> str:
    """``text`` (the README) with the table between the markers replaced by the parser's."""
    start, stop = text.index(BEGIN) + len(BEGIN), text.index(END)
    return text[:start] + "\n" + options_table() + "\n" + text[stop:]


def main(argv: list[str]) -> int:
    text = README.read_text(encoding="utf-8")
    new = rewrite(text)
    if "--check" in argv:
        return 0 if new == text else 1
    README.write_text(new, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
