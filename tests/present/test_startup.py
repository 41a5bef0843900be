"""Start-up: ``import kinepoly`` loads none of the solve (its public names are imported when first used),
``kinepoly --version`` reads the package's metadata only when it is given, and ``kinepoly solve`` loads the
instant centers' modules only for a scene that asks for centers, no drawing library at all, and no other command."""

from __future__ import annotations

import ast
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import kinepoly

ROOT = Path(__file__).resolve().parents[2]
SRC = str(ROOT / "src")
FOUR_BAR = str(ROOT / "examples" / "four-bar.toml")  # no [find] instant_centers
CENTERS_SIX_BAR = str(ROOT / "examples" / "centers-six-bar.toml")  # instant_centers = "all"

CENTER_MODULES = {"kinepoly.engine.centers", "kinepoly.engine.kennedy", "kinepoly.engine.center_values",
                  "kinepoly.engine.center_velocity", "kinepoly.engine.circle_diagram", "kinepoly.present.centers"}
"""Aronhold-Kennedy's construction and its report: needed only where a scene asks for instant centers."""
DRAWING_LIBRARIES = {"matplotlib", "shapely", "svgwrite", "ezdxf"}
OTHER_COMMANDS = {f"kinepoly.cli.{name}" for name in ("draw", "check", "variants", "bench", "sweep", "handout",
                                                      "animate", "edit")} | {"kinepoly.editor"}
"""What the other commands import when they are run: a solve loads none of it."""
OTHER_KINDS = {f"kinepoly.engine.kinds.{kind}" for kind in ("gear", "cam", "planet", "triad", "newton")} | {
    "kinepoly.engine.triad", "kinepoly.engine.planet", "kinepoly.engine.cam_place", "kinepoly.engine.newton_assembly"}
"""The group kinds a four-bar has none of, and their constructions: loaded for a mechanism that has such a group."""
MESSAGE_ONLY = {"difflib"}
"""Loaded for a message about a bad scene (a did-you-mean), not for a good one."""


def _modules(code: str, **environment: str) -> set[str]:
    env = {**os.environ, "PYTHONPATH": SRC, **environment}
    out = subprocess.run([sys.executable, "-c", code + "\nimport json, sys; print(json.dumps(sorted(sys.modules)))"],
                         env=env, capture_output=True, text=True, check=True).stdout
    return set(json.loads(out.splitlines()[-1]))


def test_import_kinepoly_loads_no_solve() -> None:
    loaded = _modules("import kinepoly")
    assert not {"numpy", "kinepoly.solution", "kinepoly.present.report", "kinepoly.scene.loader"} & loaded


def test_the_command_line_reads_no_metadata_unless_asked() -> None:
    assert "importlib.metadata" not in _modules("import kinepoly.cli; kinepoly.cli.parser()")


def test_building_the_command_line_loads_no_command() -> None:
    loaded = _modules("import kinepoly.cli; kinepoly.cli.parser()")
    assert not {"numpy", "kinepoly.present.scales", "kinepoly.scene.loader", "tempfile", "socket"} & loaded


def test_every_public_name_is_there() -> None:
    for name in kinepoly.__all__:
        assert getattr(kinepoly, name) is not None
    assert kinepoly.solve.__module__ == "kinepoly.solution"
    assert kinepoly.Scene.__name__ == "Scene"


def _solve_modules(scene: str, *options: str, **environment: str) -> set[str]:
    """The modules loaded by ``kinepoly solve scene options`` run in a fresh process through the command line."""
    argv = ["solve", scene, *options]
    return _modules(f"import contextlib, io, kinepoly.cli\nwith contextlib.redirect_stdout(io.StringIO()):\n"
                    f"    assert kinepoly.cli.main({argv!r}) == 0", **environment)


def test_solve_without_centers_loads_neither_their_modules_nor_a_drawing_library() -> None:
    for options in ((), ("--json",), ("--steps",)):
        loaded = _solve_modules(FOUR_BAR, *options)
        assert "kinepoly.solution" in loaded and "kinepoly.present.report" in loaded  # it did solve
        assert not (CENTER_MODULES | DRAWING_LIBRARIES) & loaded, options


def test_solve_loads_no_other_command() -> None:
    for options in ((), ("--json",), ("--steps",)):
        loaded = _solve_modules(FOUR_BAR, *options)
        assert "kinepoly.cli.solve" in loaded and "kinepoly.present.report" in loaded  # it did solve
        assert not (OTHER_COMMANDS | MESSAGE_ONLY) & loaded, options
        assert "kinepoly.engine.kinds.dyad" in loaded and not OTHER_KINDS & loaded, options


@pytest.mark.parametrize(("example", "kinds"), [("planetary-free-arm", {"gear", "planet"}),
                                               ("triad", {"triad", "newton"}), ("metu-cam", {"cam"})])
def test_solve_loads_the_kinds_its_mechanism_has(example: str, kinds: set[str]) -> None:
    loaded = _solve_modules(str(ROOT / "examples" / f"{example}.toml"))
    assert {f"kinepoly.engine.kinds.{kind}" for kind in kinds} <= loaded


def test_solve_with_centers_loads_their_modules() -> None:
    loaded = _solve_modules(CENTERS_SIX_BAR, "--json")
    assert CENTER_MODULES <= loaded
    assert not DRAWING_LIBRARIES & loaded


def test_a_later_solve_reads_the_catalogue_from_the_cache(tmp_path: Path) -> None:
    first = _solve_modules(FOUR_BAR, "--json", XDG_CACHE_HOME=str(tmp_path))
    assert "importlib.resources" in first  # the shipped TOML read, checked, and kept
    assert (tmp_path / "kinepoly" / "catalogue-en.marshal").is_file()
    later = _solve_modules(FOUR_BAR, "--json", XDG_CACHE_HOME=str(tmp_path))
    assert not {"importlib.resources", "tempfile"} & later


def test_the_value_types_are_structs() -> None:
    """No module of the package declares a dataclass (docs/architecture.md, "Value types"): making one compiles its
    generated methods at import, which was the largest share of a solve's start."""
    declaring = []
    for path in sorted((ROOT / "src" / "kinepoly").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import | ast.ImportFrom):
                names = [node.module or ""] if isinstance(node, ast.ImportFrom) else [a.name for a in node.names]
                if "dataclasses" in names:
                    declaring.append(str(path.relative_to(ROOT)))
    assert not declaring
    assert "dataclasses" not in _solve_modules(FOUR_BAR, "--json")
