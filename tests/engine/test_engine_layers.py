"""The engine's import graph: no cycle, no import inside a function, the group kinds between the shared pieces
and the drivers, and one table that dispatches on the kinds (docs/architecture.md, "Modules of engine/")."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ENGINE = Path(__file__).resolve().parents[2] / "src" / "kinepoly" / "engine"
DRIVERS = {"plan", "position", "velocity", "acceleration", "assembly", "construct", "table"}
"""The table and the modules that loop over the plan's groups, and those above them in engine/."""
READERS = {"row", "sliders", "transmission", "centrode", "centers", "kennedy",
                 "center_values", "center_velocity", "circle_diagram", "finite_pole"}
"""The readers of what the drivers give (docs/architecture.md): they may import the drivers."""
GROUP_TYPES = {"Dyad", "CarriedDyad", "DriveGroup", "GearGroup", "CamGroup", "NewtonGroup", "PlanetGroup",
               "TriadGroup"}


def _module(path: Path) -> str:
    return ".".join(path.relative_to(ENGINE).with_suffix("").parts).removesuffix(".__init__") or "__init__"


def _engine_imports(tree: ast.Module) -> list[tuple[str, ast.stmt, bool]]:
    """(imported engine module, the statement, whether it is at the module's top level)."""
    top = set(map(id, tree.body))
    out: list[tuple[str, ast.stmt, bool]] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("kinepoly.engine"):
            base = node.module.removeprefix("kinepoly.engine").lstrip(".")
            for alias in node.names:
                name = f"{base}.{alias.name}" if base else alias.name
                known = (ENGINE / f"{name.replace('.', '/')}.py").exists()
                out.append((name if known else base, node, id(node) in top))
    return out


MODULES = {_module(p): ast.parse(p.read_text(encoding="utf-8")) for p in sorted(ENGINE.rglob("*.py"))}
GRAPH = {name: {target for target, _, _ in _engine_imports(tree) if target and target != name}
         for name, tree in MODULES.items()}


def _reaches(start: str, goal: str) -> bool:
    seen: set[str] = set()
    stack = [start]
    while stack:
        here = stack.pop()
        for there in GRAPH.get(here, ()):
            if there == goal:
                return True
            if there not in seen:
                seen.add(there)
                stack.append(there)
    return False


def test_the_graph_is_read() -> None:
    assert "kinds.dyad" in GRAPH and "lines" in GRAPH["kinds.dyad"] and "table" in GRAPH["plan"]


@pytest.mark.parametrize("module", sorted(MODULES))
def test_no_module_of_the_engine_reaches_itself_through_its_imports(module: str) -> None:
    assert not _reaches(module, module), f"engine.{module} is on an import cycle"


@pytest.mark.parametrize("module", sorted(MODULES))
def test_every_engine_import_is_at_the_top_of_its_module(module: str) -> None:
    inside = [target for target, _, at_top in _engine_imports(MODULES[module]) if not at_top]
    assert not inside, f"engine.{module} imports {inside} inside a function or a condition"


@pytest.mark.parametrize("module", sorted(m for m in MODULES if m.startswith("kinds.") or
                                          m not in DRIVERS | READERS and m not in ("kinds", "__init__")))
def test_kinds_and_shared_pieces_import_no_driver(module: str) -> None:
    up = sorted(GRAPH[module] & DRIVERS)
    assert not up, f"engine.{module} imports the driver(s) {up}"


@pytest.mark.parametrize("module", sorted(m for m in MODULES
                                          if not m.startswith("kinds") and m not in DRIVERS | READERS))
def test_shared_pieces_import_no_kind(module: str) -> None:
    up = sorted(t for t in GRAPH[module] if t.startswith("kinds"))
    assert not up, f"engine.{module} imports the kind(s) {up}"


def test_only_the_table_dispatches_on_the_group_types() -> None:
    found = []
    for name, tree in MODULES.items():
        for node in ast.walk(tree):
            if isinstance(node, ast.Call) and getattr(node.func, "id", "") == "isinstance" and len(node.args) == 2:
                types = {n.id for n in ast.walk(node.args[1]) if isinstance(n, ast.Name)}
                if types & GROUP_TYPES:
                    found.append((name, node.lineno))
    # rolling.mark_pitch_point takes a gear pair or its group (no dispatch); transmission asks which groups
    # are dyads, the only groups with a transmission angle
    assert sorted(m for m, _ in found) == ["rolling", "transmission"], found


def test_every_group_type_has_a_row_in_the_table() -> None:
    from kinepoly.engine import groups
    from kinepoly.engine.table import KINDS

    assert {t.__name__ for t in KINDS} == GROUP_TYPES
    assert all(getattr(groups, name) in KINDS for name in GROUP_TYPES)
    assert list(KINDS)[-1] is groups.NewtonGroup  # the Newton group takes what the others leave
