"""The finite-rotation pole drawn on the mechanism (``kinepoly sweep --pole A B --pole-plot FILE.png``).

The mechanism at both inputs (the first solid, the second dashed), the chosen link's two points in
both places (A1, A2, B1, B2), the perpendicular bisectors of A1A2 and B1B2 and their crossing P12,
and the link's instant center at the first input, which P12 approaches as the two inputs close.
"""

from __future__ import annotations

import io

import numpy as np

from kinepoly.geom.tolerances import SIZE_FLOOR
from kinepoly.model.pose import LinkPose
from kinepoly.scene.spec import Scene
from kinepoly.sweep.pole import PoleBetween

__all__ = ["pole_png"]

_FIRST, _SECOND, _LINK, _POLE = "#555555", "#999999", "#1f5fa8", "#b0262b"


def _outline(scene: Scene, link: str, pose: LinkPose) -> np.ndarray:
    """The link's points in the frame, in turn round their centre (a binary link: its bar)."""
    points = np.array([complex(*pose.world(p.local)) for p in scene.link(link).points])
    if len(points) > 2:
        points = points[np.argsort(np.angle(points - points.mean()))]
        points = np.append(points, points[0])
    return points


def pole_png(scene: Scene, found: PoleBetween, input_name: str, unit: str, dpi: int = 110) -> bytes:
    """The drawing as PNG bytes."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pole = found.found
    fig, ax = plt.subplots(figsize=(8.0, 6.5))
    try:
        every: list[complex] = []
        for poses, colour, style in ((found.first, _FIRST, "-"), (found.second, _SECOND, "--")):
            for link, pose in poses.items():
                if link == scene.ground:
                    continue
                outline = _outline(scene, link, pose)
                every += list(outline)
                chosen = link == pole.link
                ax.plot(outline.real, outline.imag, style, color=_LINK if chosen else colour,
                        lw=2.2 if chosen else 1.2, marker="o", ms=3)
        named = ((f"{pole.a}1", pole.a1), (f"{pole.a}2", pole.a2), (f"{pole.b}1", pole.b1), (f"{pole.b}2", pole.b2))
        for label, z in named:
            ax.annotate(label, (z.real, z.imag), xytext=(4, 4), textcoords="offset points", fontsize=9, color=_LINK)
        marks = [pole.a1, pole.a2, pole.b1, pole.b2]
        if pole.pole is not None:
            marks.append(pole.pole)
        if found.instant_center is not None:
            marks.append(found.instant_center)
        every += marks
        span = max(np.ptp([z.real for z in every]), np.ptp([z.imag for z in every]), SIZE_FLOOR)
        for p1, p2 in ((pole.a1, pole.a2), (pole.b1, pole.b2)):
            ax.plot([p1.real, p2.real], [p1.imag, p2.imag], ":", color=_POLE, lw=1.0)
            if abs(p2 - p1) > 0.0:
                mid, normal = (p1 + p2) / 2, 1j * (p2 - p1) / abs(p2 - p1)
                ends = [mid + normal * 2 * span, mid - normal * 2 * span]
                ax.plot([e.real for e in ends], [e.imag for e in ends], "-.", color=_POLE, lw=0.8)
        if pole.pole is not None:
            ax.plot(pole.pole.real, pole.pole.imag, "o", color=_POLE, ms=7)
            ax.annotate(f"P12 of link {pole.link}", (pole.pole.real, pole.pole.imag), xytext=(6, -12),
                        textcoords="offset points", fontsize=10, color=_POLE)
        if found.instant_center is not None:
            ic = found.instant_center
            ax.plot(ic.real, ic.imag, "x", color="#000000", ms=8)
            ax.annotate(f"instant center at {input_name} = {found.start:g}", (ic.real, ic.imag), xytext=(6, 6),
                        textcoords="offset points", fontsize=8)
        xs, ys = [z.real for z in every], [z.imag for z in every]
        pad = 0.08 * span
        ax.set_xlim(min(xs) - pad, max(xs) + pad)
        ax.set_ylim(min(ys) - pad, max(ys) + pad)
        ax.set_aspect("equal")
        ax.grid(True, lw=0.3)
        turned = np.degrees(pole.turn)
        ax.set_title(f"{scene.title}\nfinite-rotation pole of link {pole.link} from {input_name} = {found.start:g} "
                     f"(solid) to {found.stop:g} (dashed)\nthe link turns {turned:.4g} deg", fontsize=9)
        ax.set_xlabel(f"x ({unit})")
        ax.set_ylabel(f"y ({unit})")
        fig.tight_layout()
        buffer = io.BytesIO()
        fig.savefig(buffer, format="png", dpi=dpi)
        return buffer.getvalue()
    finally:
        plt.close(fig)
