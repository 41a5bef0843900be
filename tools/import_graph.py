"""The package's import graph, read from the source (``ast``, every import, lazy and type-only ones too).

``python3 tools/import_graph.py [SRC]`` prints the cycles (strongly connected components of more than one
module) inside and outside ``kinepoly.engine``, and the upward imports: a module importing one of a layer
above its own (``LAYERS``, lowest first; a package's modules are one layer) or the face (``__init__``) of
its own package. ``tests/hardening/test_import_layers.py`` holds the package outside the engine to none.
"""

from __future__ import annotations

import ast
import sys
from collections import defaultdict
from pathlib import Path

__all__ = ["LAYERS", "cycles", "import_graph", "main", "upward_imports"]

LAYERS: tuple[tuple[str, ...], ...] = (
    ("errors", "notice"),
    ("atomic", "assets"),
    ("geom",),
    ("scene",),
    ("model",),
    ("engine",),
    ("check",),
    ("solution",),
    ("present",),
    ("render",),
    ("loops",),
    ("sweep",),
    ("bench",),
    ("handout",),
    ("homework", "motion"),
    ("editor",),
    ("cli",),
    ("kinepoly",),
    ("__main__",),
)
"""kinepoly's top-level modules and packages, lowest first; ``kinepoly`` is the package's face."""

_RANK = {name: rank for rank, names in enumerate(LAYERS) for name in names}

Graph = dict[str, set[str]]


def _modules(source: Path) -> dict[str, tuple[Path, bool]]:
    """Each module's dotted name: its file and whether it is a package's ``__init__``."""
    out = {}
    for path in sorted((source / "kinepoly").rglob("*.py")):
        parts = list(path.relative_to(source).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        out[".".join(parts[:-1] if is_package else parts)] = (path, is_package)
    return out


def import_graph(source: Path) -> tuple[Graph, dict[str, bool]]:
    """Module -> the kinepoly modules it imports (an imported name that is a module counts as that module)."""
    modules = _modules(source)

    def resolve(name: str) -> str | None:
        while name and name not in modules:
            name = name.rpartition(".")[0]
        return name or None

    graph: Graph = defaultdict(set)
    for module, (path, is_package) in modules.items():
        package = module if is_package else module.rpartition(".")[0]
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                targets = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    parts = package.split(".")
                    base = ".".join(parts[: len(parts) - node.level + 1] + ([node.module] if node.module else []))
                named = [f"{base}.{alias.name}" for alias in node.names if f"{base}.{alias.name}" in modules]
                targets = named or [base]
            else:
                continue
            for target in targets:
                found = resolve(target) if target.startswith("kinepoly") else None
                if found is not None and found != module:
                    graph[module].add(found)
    return dict(graph), {name: is_package for name, (_path, is_package) in modules.items()}


def cycles(graph: Graph) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan's algorithm, iteratively)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []
    nodes = sorted(set(graph) | {t for targets in graph.values() for t in targets})
    for root in nodes:
        if root in index:
            continue
        work = [(root, iter(sorted(graph.get(root, ()))))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph.get(child, ())))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    out.append(sorted(component))
    return out


def _top(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "kinepoly"


def upward_imports(graph: Graph, packages: dict[str, bool]) -> list[tuple[str, str]]:
    """Imports of a higher layer, of another package of the same layer, or of the importer's own package's face."""
    out = []
    for module, targets in graph.items():
        for target in sorted(targets):
            here, there = _top(module), _top(target)
            above = here != there and _RANK[there] >= _RANK[here]
            own_face = packages[target] and module.startswith(target + ".")
            if above or own_face:
                out.append((module, target))
    return sorted(out)


def main(argv: list[str]) -> int:
    source = Path(argv[0] if argv else "src")
    graph, packages = import_graph(source)
    found = cycles(graph)
    print(f"{len(packages)} modules, {sum(map(len, graph.values()))} imports")
    for where, inside in (("outside the engine", False), ("inside the engine", True)):
        chosen = [c for c in found if all(m.startswith("kinepoly.engine") for m in c) == inside]
        print(f"cycles {where}: {len(chosen)}, holding {sum(map(len, chosen))} modules")
        for component in chosen:
            print("   ", " ".join(component))
    upward = upward_imports(graph, packages)
    print(f"upward imports: {len(upward)}")
    for module, target in upward:
        print(f"    {module} -> {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
