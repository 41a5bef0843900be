"""The package's import graph outside the engine has no cycle and no upward import (``tools/import_graph.py``):
a module imports only modules of its own package or of a layer below (errors < geom < scene < model < engine <
check < solution < present < render < applications < cli < the package's face), never its own package's face."""

from __future__ import annotations

from pathlib import Path

from tools.import_graph import LAYERS, cycles, import_graph, upward_imports

SOURCE = Path(__file__).resolve().parents[2] / "src"


def test_no_import_cycle_outside_the_engine() -> None:
    graph, _packages = import_graph(SOURCE)
    outside = [c for c in cycles(graph) if not all(m.startswith("kinepoly.engine.") for m in c)]
    assert outside == []


def test_no_upward_import() -> None:
    graph, packages = import_graph(SOURCE)
    assert upward_imports(graph, packages) == []


def test_every_top_level_module_and_package_has_a_layer() -> None:
    named = {name for layer in LAYERS for name in layer}
    found = {path.stem for path in (SOURCE / "kinepoly").glob("*.py") if path.stem != "__init__"}
    found |= {path.name for path in (SOURCE / "kinepoly").iterdir() if (path / "__init__.py").exists()}
    assert found | {"kinepoly"} == named


def test_the_graph_sees_a_lazy_import_and_the_cycle_it_makes(tmp_path: Path) -> None:
    package = tmp_path / "kinepoly"
    (package / "geom").mkdir(parents=True)
    (package / "__init__.py").write_text("")
    (package / "geom" / "__init__.py").write_text("")
    (package / "geom" / "a.py").write_text("def f():\n    from kinepoly.geom import b\n")
    (package / "geom" / "b.py").write_text("from kinepoly.geom.a import f\nfrom kinepoly.scene import spec\n")
    (package / "scene").mkdir()
    (package / "scene" / "__init__.py").write_text("")
    (package / "scene" / "spec.py").write_text("from . import __name__ as _n\n")
    graph, packages = import_graph(tmp_path)
    assert cycles(graph) == [["kinepoly.geom.a", "kinepoly.geom.b"]]
    assert upward_imports(graph, packages) == [("kinepoly.geom.b", "kinepoly.scene.spec"),
                                               ("kinepoly.scene.spec", "kinepoly.scene")]
