"""Driving the editor's page in chromium as a user does: drags with the mouse, between scene coordinates."""

from __future__ import annotations

from typing import Any

__all__ = ["drag", "screen", "settled", "wait_settled"]

_SCREEN = """([x, y]) => {
  const view = window.kinepolyEditor.good.view;
  const svg = document.querySelector('#sheet svg');
  const p = svg.createSVGPoint();
  p.x = view.origin[0] + view.scale * x;
  p.y = view.height - (view.origin[1] + view.scale * y);
  const q = p.matrixTransform(svg.getScreenCTM());
  return [q.x, q.y];
}"""


def screen(page: Any, at: tuple[float, float]) -> tuple[float, float]:
    """Where the scene's point ``at`` is on the screen, on the drawing shown now."""
    x, y = page.evaluate(_SCREEN, list(at))
    return float(x), float(y)


_SETTLED = "() => !window.kinepolyEditor.inFlight && window.kinepolyEditor.pending.length === 0"


def settled(page: Any) -> bool:
    return bool(page.evaluate(_SETTLED))


def wait_settled(page: Any) -> None:
    page.wait_for_function(_SETTLED)


def handle(page: Any, name: str) -> tuple[float, float]:
    """Where point ``name``'s handle is, in the scene."""
    at = page.evaluate("(name) => window.kinepolyEditor.good.handles.points[name].at", name)
    return float(at[0]), float(at[1])


def drag(page: Any, start: tuple[float, float], path: list[tuple[float, float]], *, shift: bool = False,
         wait: bool = True) -> None:
    """Press at the scene point ``start``, move through the scene points of ``path`` (each placed on the drawing
    shown when the mouse gets there, as the user sees it), release; with ``wait``, each move's redraw awaited."""
    page.mouse.move(*screen(page, start))
    if shift:
        page.keyboard.down("Shift")
    page.mouse.down()
    for at in path:
        page.mouse.move(*screen(page, at))
        if wait:
            wait_settled(page)
    page.mouse.up()
    if shift:
        page.keyboard.up("Shift")
    wait_settled(page)
