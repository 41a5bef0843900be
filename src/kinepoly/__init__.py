"""kinepoly: velocity and acceleration polygons of planar mechanisms, constructed and checked.

A notebook needs four names::

    import kinepoly
    scene = kinepoly.load_scene("examples/four-bar.toml")   # or kinepoly.loads_scene(text)
    solution = kinepoly.solve(scene)
    kinepoly.to_json(solution)["links"]["3"]["omega"]

``solution`` shows as its drawing in a notebook; ``kinepoly.draw(solution, part="velocity-polygon")``
is SVG text; ``kinepoly.animate(scene, "four-bar.gif")`` is ``kinepoly animate`` (docs/python.md).
"""

from typing import TYPE_CHECKING, Any

from kinepoly.errors import (
    AssemblyError,
    CatalogueError,
    HandoutError,
    KinepolyError,
    MobilityError,
    OutputError,
    SceneError,
    SingularityError,
)

if TYPE_CHECKING:
    from kinepoly.motion.api import animate, draw
    from kinepoly.present.report import steps_text, table_text, to_json
    from kinepoly.scene.loader import load_scene, loads_scene
    from kinepoly.scene.spec import Scene
    from kinepoly.solution import Solution, solve
    from kinepoly.sweep.family import sweep_family

_LAZY = {"animate": "kinepoly.motion.api", "draw": "kinepoly.motion.api", "steps_text": "kinepoly.present.report",
         "table_text": "kinepoly.present.report", "to_json": "kinepoly.present.report",
         "load_scene": "kinepoly.scene.loader", "loads_scene": "kinepoly.scene.loader", "Scene": "kinepoly.scene.spec",
         "Solution": "kinepoly.solution", "solve": "kinepoly.solution", "sweep_family": "kinepoly.sweep.family"}
"""Where each public name lives: loaded when first used, so that ``import kinepoly`` (and every command,
which imports only what it runs) starts fast."""

__all__ = [
    "AssemblyError",
    "CatalogueError",
    "HandoutError",
    "KinepolyError",
    "MobilityError",
    "OutputError",
    "Scene",
    "SceneError",
    "SingularityError",
    "Solution",
    "animate",
    "draw",
    "load_scene",
    "loads_scene",
    "solve",
    "steps_text",
    "sweep_family",
    "table_text",
    "to_json",
]


def _solution_svg(solution: "Solution") -> str:
    """A notebook shows a solution as its drawing (``Solution._repr_svg_``, set at the package's face when the
    solution's module is first loaded through it, so that the solution does not import the drawing code above it)."""
    from kinepoly.motion.api import draw

    return draw(solution)


def __getattr__(name: str) -> Any:
    """A public name's module is imported when the name is first used (``animate`` and ``draw`` load the
    drawing and animation code, matplotlib and the sweep); the name is then kept on the package."""
    where = _LAZY.get(name)
    if where is None:
        raise AttributeError(f"module 'kinepoly' has no attribute {name!r}")
    from importlib import import_module

    module = import_module(where)
    if where == "kinepoly.solution":
        setattr(module.Solution, "_repr_svg_", _solution_svg)  # noqa: B010 (a method the class does not declare)
    value = getattr(module, name)
    globals()[name] = value
    return value
