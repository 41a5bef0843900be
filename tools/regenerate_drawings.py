"""Regenerate ``drawings/`` from ``examples/``: ``python3 tools/regenerate_drawings.py`` (from the repo root).

Writes ``drawings/<example>.svg``, ``.dxf`` and ``.png`` for every ``examples/*.toml`` where the one there is
missing or differs (compared as ``--check`` compares: a DXF whose header alone moved is left as it is).
``--check`` writes nothing: it draws into a temporary folder and exits 1 naming every stale
or missing file (SVG and DXF compared canonically, PNG within a grey-level tolerance).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from collections.abc import Sequence
from pathlib import Path

if __package__ in (None, ""):  # run as a script: the repository's root on the path, for ``tools.compare_drawings``
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

__all__ = ["DRAWN_FORMATS", "draw_example", "main", "stale"]

DRAWN_FORMATS = ("svg", "dxf", "png")


def draw_example(scene_path: Path, out_dir: Path) -> list[Path]:
    """Draw one example as SVG, DXF and PNG into ``out_dir``; return the files written."""
    from kinepoly.cli.files import write_atomically
    from kinepoly.render.dxf import write_dxf
    from kinepoly.render.mpl import write_png
    from kinepoly.render.sheet import build_sheet
    from kinepoly.render.svg import write_svg
    from kinepoly.scene.loader import load_scene
    from kinepoly.solution import solve

    sheet = build_sheet(solve(load_scene(scene_path)))
    written = []
    for fmt, write, binary in (("svg", write_svg, False), ("dxf", write_dxf, False), ("png", write_png, True)):
        path = out_dir / f"{scene_path.stem}.{fmt}"
        write_atomically(path, lambda stream, w=write: w(sheet, stream), binary=binary)  # type: ignore[misc]
        written.append(path)
    return written


def _difference(fmt: str, committed: Path, fresh: Path) -> str:
    """Why ``committed`` is not the ``fresh`` drawing (empty when it is, compared canonically)."""
    from tools.compare_drawings import PNG_RMS_TOLERANCE, canonical_dxf, canonical_svg, png_rms

    if not committed.exists():
        return "missing"
    if fmt == "svg" and canonical_svg(committed.read_text()) != canonical_svg(fresh.read_text()):
        return "stale (the SVG differs)"
    if fmt == "dxf" and canonical_dxf(committed) != canonical_dxf(fresh):
        return "stale (the DXF differs)"
    if fmt == "png" and (rms := png_rms(committed, fresh)) > PNG_RMS_TOLERANCE:
        return f"stale (grey-level RMS difference {rms:.2f} > {PNG_RMS_TOLERANCE})"
    return ""


def stale(examples: Path, drawings: Path, replace: bool = False) -> list[str]:
    """What in ``drawings`` differs from a fresh drawing of ``examples`` (empty: all current); with ``replace``
    the differing files are replaced by the fresh ones, and only they (a DXF whose entities are the same but
    whose header moved is left as it is)."""
    import shutil

    problems = []
    with tempfile.TemporaryDirectory() as tmp:
        fresh = Path(tmp)
        for scene in sorted(examples.glob("*.toml")):
            draw_example(scene, fresh)
            svg_stale = False
            for fmt in DRAWN_FORMATS:  # svg first: a PNG of a changed drawing is stale however little it moved
                name = f"{scene.stem}.{fmt}"
                why = _difference(fmt, drawings / name, fresh / name)
                if fmt == "svg":
                    svg_stale = bool(why)
                elif fmt == "png" and svg_stale and not why:
                    why = "stale (its SVG differs)"
                if why:
                    problems.append(f"{drawings / name}: {why}")
                    if replace:
                        shutil.copyfile(fresh / name, drawings / name)
        known = {f"{s.stem}.{fmt}" for s in examples.glob("*.toml") for fmt in DRAWN_FORMATS}
        problems += [f"{p}: no example draws it" for p in sorted(drawings.glob("*.*")) if p.name not in known
                     and p.suffix.lstrip(".") in DRAWN_FORMATS]
    return problems


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python3 tools/regenerate_drawings.py",
                                     description="Draw every example into drawings/ (SVG, DXF, PNG).")
    parser.add_argument("--examples", default="examples", help="folder of example scenes (default examples)")
    parser.add_argument("--drawings", default="drawings", help="folder of the drawings (default drawings)")
    parser.add_argument("--check", action="store_true", help="write nothing; exit 1 when a drawing is stale")
    args = parser.parse_args(argv)
    examples, drawings = Path(args.examples), Path(args.drawings)
    scenes = sorted(examples.glob("*.toml"))
    if not scenes:
        print(f"regenerate: no *.toml in {examples}", file=sys.stderr)
        return 2
    if args.check:
        problems = stale(examples, drawings)
        for problem in problems:
            print(problem)
        print("drawings are current" if not problems else "run: python3 tools/regenerate_drawings.py")
        return 1 if problems else 0
    drawings.mkdir(parents=True, exist_ok=True)
    replaced = [problem for problem in stale(examples, drawings, replace=True) if "no example draws it" not in problem]
    for problem in replaced:
        print(f"wrote {problem.partition(':')[0]} (was {problem.partition(': ')[2]})")
    print(f"{len(replaced)} file(s) written; the others are current")
    return 0


if __name__ == "__main__":
    sys.exit(main())
