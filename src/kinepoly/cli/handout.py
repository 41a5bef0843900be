"""``kinepoly handout SCENE -o FILE.pdf | --html FILE.html [--lang en|tr|ro] [--messages FILE] [--paper A4]``.

The catalogue and the paths are checked before the scene is solved; every file is written to a
temporary name beside it and renamed (``cli.files.write_atomically``), so a failed run
leaves no half file. Bad options are an ``OutputError`` (exit 2) with what to change.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any

from kinepoly.cli.files import output_path, write_atomically
from kinepoly.errors import OutputError

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", help="the scene file (TOML)")
    parser.add_argument("-o", "--output", metavar="FILE.pdf", help="the handout as a PDF: the problem, a page per "
                        "construction step, the answers")
    parser.add_argument("--html", metavar="FILE.html", help="the handout as one web page that steps through the "
                        "construction (buttons, slider, arrow keys); self-contained")
    parser.add_argument("--lang", default="en", help="the language of the text: en, tr or ro (default en)")
    parser.add_argument("--messages", metavar="FILE.toml", help="a message catalogue of your own (another language, "
                        "or your wording; see 'Handouts' in the README); overrides --lang")
    parser.add_argument("--paper", default="A4", help="A0..A5, letter, legal, tabloid (landscape; add -portrait), "
                        "or WIDTHxHEIGHT in mm (default A4)")
    parser.add_argument("--loops", action="store_true",
                        help="add to the PDF and the web page a page per loop of the loop-closure "
                        "method (each loop's equation in complex numbers, its derivatives, Cramer's rule); gears and "
                        "cams are not covered: exit 2")


def _target(option: str, value: str, suffixes: tuple[str, ...]) -> Path:
    path = output_path(value, option)
    if path.suffix.lower() not in suffixes:
        other = "; for the web page use --html FILE.html" if option == "-o" else "; for the PDF use -o FILE.pdf"
        raise OutputError(f"{option} {value}: expected a file ending in {' or '.join(suffixes)}{other}")
    if not path.parent.is_dir():
        raise OutputError(f"{option} {value}: the folder {str(path.parent)!r} does not exist; create it or choose "
                          "another")
    if path.is_dir():
        raise OutputError(f"{option} {value}: is a folder; give a file name")
    return path


def _write(path: Path, write: Callable[[IO[Any]], None], binary: bool) -> None:
    try:
        write_atomically(path, write, binary=binary)
    except OSError as error:
        raise OutputError(f"cannot write {path}: {error.strerror or error}") from error


def run(args: argparse.Namespace) -> int:
    """Make the handout as asked; print a line per file written."""
    for line in _handout(args):
        print(line)
    return 0


def _handout(args: argparse.Namespace) -> list[str]:
    """Make the handout as asked; return the lines to print."""
    from kinepoly.present.catalogue import load_catalogue
    from kinepoly.render.layout import paper_size
    from kinepoly.scene.loader import load_scene
    from kinepoly.solution import solve

    if not args.output and not args.html:
        raise OutputError("handout: nothing to write; give -o FILE.pdf, --html FILE.html, or both")
    pdf = _target("-o", args.output, (".pdf",)) if args.output else None
    page = _target("--html", args.html, (".html", ".htm")) if args.html else None
    try:
        paper = paper_size(args.paper)
    except ValueError as error:
        raise OutputError(str(error)) from error
    say = load_catalogue(args.lang, args.messages)
    t0 = time.perf_counter()
    solution = solve(load_scene(args.scene))
    loops = None
    if args.loops:
        from kinepoly.loops import loop_method_solution

        loops = loop_method_solution(solution)[1]
    lines = []
    files: list[tuple[Path, bytes | str, bool]] = []  # made in memory first: both files or neither
    if pdf is not None:
        from kinepoly.handout.build import handout_sheets
        from kinepoly.render.mpl import write_pdf_pages

        handout, sheets = handout_sheets(solution, say, args.paper, loops)
        for note in handout.notes:  # a larger paper than asked: said on the pages and here
            print(f"kinepoly handout: {note}", file=sys.stderr)
        buffer = io.BytesIO()
        try:
            write_pdf_pages(sheets, buffer, handout.title)
        except OSError as error:
            raise OutputError(f"cannot write {pdf}: {error.strerror or error}") from error
        files.append((pdf, buffer.getvalue(), True))
        lines.append(f"wrote {pdf} ({len(sheets)} pages, {say.language})")
    if page is not None:
        from kinepoly.handout.html import handout_html

        handout, text = handout_html(solution, say, paper, loops)
        files.append((page, text, False))
        lines.append(f"wrote {page} ({len(handout.pages)} pages, {say.language})")
    written: list[Path] = []
    for path, content, binary in files:
        def write(stream: IO[Any], content: bytes | str = content) -> None:
            stream.write(content)

        try:
            _write(path, write, binary)
        except OutputError:
            for done in written:
                with contextlib.suppress(OSError):
                    done.unlink()
            raise
        written.append(path)
    lines.append(f"made in {1e3 * (time.perf_counter() - t0):.0f} ms")
    return lines
