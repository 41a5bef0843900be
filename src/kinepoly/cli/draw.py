"""``kinepoly draw SCENE -o FILE|DIR/ [--steps DIR] [--paper A4]``: the drawing as SVG, DXF, PNG, PDF.

The format follows FILE's extension; ``-o DIR/`` writes all four as ``DIR/<scene name>.<ext>``.
``--steps DIR`` writes one SVG per construction step (``step-01.svg`` ...). Every file is
written to a temporary name and renamed (``cli.files.write_atomically``), so an interrupted run
never leaves half a file. A path that cannot be written is an ``OutputError`` (exit 2) with the reason.
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

__all__ = ["FORMATS", "add_arguments", "run"]

FORMATS = ("svg", "dxf", "png", "pdf")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", help="the scene file (TOML)")
    parser.add_argument("-o", "--output", metavar="FILE|DIR/",
                        help="the drawing: FILE.svg, .dxf, .png or .pdf; DIR/ (ending in /) writes all four")
    parser.add_argument("--steps", metavar="DIR", help="also write one SVG per construction step into DIR")
    parser.add_argument("--paper", default="A4", help="A0..A5, letter, legal, tabloid (landscape; add -portrait), "
                        "or WIDTHxHEIGHT in mm (default A4)")
    parser.add_argument("--dpi", type=int, default=150, help="resolution of PNG output (default 150)")


def _targets(output: str, stem: str, steps: str | None = None) -> list[tuple[Path, str]]:
    """The files of ``-o``; a file in the ``--steps`` folder is made with it, as the steps are."""
    path = output_path(output, "-o")
    if output.endswith(("/", "\\")) or path.is_dir():  # made once the drawing is (a failed run leaves none)
        _check_folder(path, "-o")
        return [(path / f"{stem}.{fmt}", fmt) for fmt in FORMATS]
    fmt = path.suffix.lower().lstrip(".")
    if fmt not in FORMATS:
        raise OutputError(f"-o {output}: unknown drawing format {path.suffix or '(no extension)'!r}; expected a file "
                          f"ending in .svg, .dxf, .png or .pdf, or a folder ending in /")
    if steps and path.parent.resolve() == Path(steps).resolve():
        _check_folder(path.parent, "-o")
    elif not path.parent.is_dir():
        raise OutputError(f"-o {output}: the folder {str(path.parent)!r} does not exist; create it or choose another")
    return [(path, fmt)]


def _check_folder(path: Path, option: str) -> None:
    """Refuse, before solving, a folder that could not be made: it or a parent of it is a file."""
    for part in (path, *path.parents):
        if part.exists():
            if not part.is_dir():
                raise OutputError(f"{option} {path}: cannot create the folder ({str(part)!r} is a file); choose "
                                  "another")
            return


def _make_folder(path: Path, option: str) -> None:
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise OutputError(f"{option} {path}: cannot create the folder ({error.strerror or error})") from error


def _writer(fmt: str, sheet: Any, dpi: int) -> tuple[Callable[[IO[Any]], None], bool]:
    if fmt == "svg":
        from kinepoly.render.svg import write_svg

        return (lambda stream: write_svg(sheet, stream)), False
    if fmt == "dxf":
        from kinepoly.render.dxf import write_dxf

        return (lambda stream: write_dxf(sheet, stream)), False
    if fmt == "png":
        from kinepoly.render.mpl import write_png

        return (lambda stream: write_png(sheet, stream, dpi)), True
    from kinepoly.render.mpl import write_pdf

    return (lambda stream: write_pdf(sheet, stream)), True


def _render(path: Path, fmt: str, sheet: Any, dpi: int) -> tuple[str | bytes, bool]:
    """The file's whole content, made in memory: a multi-file output is written only once every file is made."""
    write, binary = _writer(fmt, sheet, dpi)
    stream: io.BytesIO | io.StringIO = io.BytesIO() if binary else io.StringIO()
    try:
        write(stream)
    except OSError as error:
        raise OutputError(f"cannot write {path}: {error.strerror or error}") from error
    return stream.getvalue(), binary


def _write_all(files: list[tuple[Path, str | bytes, bool]]) -> None:
    """Write every file (each whole, by rename); when one cannot be written, remove those this run wrote."""
    done: list[Path] = []
    for path, content, binary in files:
        def write(stream: IO[Any], content: str | bytes = content) -> None:
            stream.write(content)

        try:
            write_atomically(path, write, binary=binary)
        except OSError as error:
            for written in done:
                with contextlib.suppress(OSError):
                    written.unlink()
            raise OutputError(f"cannot write {path}: {error.strerror or error}") from error
        done.append(path)


def run(args: argparse.Namespace) -> int:
    """Draw the scene as asked; print a line per file written."""
    for line in _draw(args):
        print(line)
    return 0


def _draw(args: argparse.Namespace) -> list[str]:
    """Draw the scene as asked; return the lines to print (one per file written)."""
    from kinepoly.render.layout import paper_name, paper_size
    from kinepoly.render.sheet import build_sheet, layout_sheet, step_count
    from kinepoly.scene.loader import load_scene
    from kinepoly.solution import solve

    if not args.output and not args.steps:
        raise OutputError("draw: nothing to write; give -o FILE (.svg, .dxf, .png, .pdf), -o DIR/ or --steps DIR")
    if not 10 <= args.dpi <= 2400:
        raise OutputError(f"--dpi {args.dpi}: expected a resolution between 10 and 2400")
    try:
        paper = paper_size(args.paper)
    except ValueError as error:
        raise OutputError(str(error)) from error
    targets = _targets(args.output, Path(args.scene).stem, args.steps) if args.output else []
    if args.steps:
        _check_folder(Path(args.steps), "--steps")
    t0 = time.perf_counter()
    solution = solve(load_scene(args.scene), load_s=0.0)
    layout = layout_sheet(solution, paper)
    for note in layout.notes:  # a larger paper or a polygon's scale reduced: said on the sheet and here
        print(f"kinepoly draw: {note}", file=sys.stderr)
    lines: list[str] = []
    files: list[tuple[Path, str | bytes, bool]] = []
    if targets:
        sheet = build_sheet(solution, paper, layout=layout)
        if layout.labels.crowded:  # said, not hidden: where points lie closer together than their names are long
            print(f"kinepoly draw: {len(layout.labels.crowded)} labels found no free place on "
                  f"{paper_name((layout.width, layout.height))} and touch what is drawn near them "
                  "(their points lie closer together than the labels are long)", file=sys.stderr)
        for path, fmt in targets:
            files.append((path, *_render(path, fmt, sheet, args.dpi)))
            lines.append(f"wrote {path}")
    total = step_count(solution) if args.steps else 0  # the Kennedy steps too, numbered as solve --steps numbers them
    for number in range(1, total + 1):
        path = Path(args.steps) / f"step-{number:0{max(2, len(str(total)))}d}.svg"
        files.append((path, *_render(path, "svg", build_sheet(solution, paper, step=number, layout=layout), args.dpi)))
    made: list[Path] = []
    try:
        for folder, option in sorted({(p.parent, "--steps" if args.steps and p.parent == Path(args.steps) else "-o")
                                      for p, _, _ in files}):
            if not folder.is_dir():
                _make_folder(folder, option)
                made.append(folder)
        _write_all(files)
    except OutputError:
        for folder in reversed(made):  # nothing left behind: the folders this run made, empty again
            with contextlib.suppress(OSError):
                folder.rmdir()
        raise
    if args.steps:
        lines.append(f"wrote {total} step drawings to {args.steps}")
    lines.append(f"drawn in {1e3 * (time.perf_counter() - t0):.0f} ms")
    return lines
