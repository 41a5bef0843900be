"""A polygon under construction: its tips, which link each tip belongs to, and the steps.

Points of an already-known link get their tips lazily, when a later step needs them:
- a point of the frame is the pole o;
- with two tips known on the link, by Mehmke's image: the triangle on the polygon similar
  to the link's triangle and of the same sense, built from the two angles at the known tips
  (flat triangles by proportional division of the known side);
- with one tip and the link's omega (and alpha) known, by laying the relative vector.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Literal

from kinepoly.engine.steps import Direction, DrawnVector, Step
from kinepoly.errors import SingularityError
from kinepoly.geom import Intersection, Line, ParallelLinesError, intersect
from kinepoly.geom.tolerances import COLLINEAR_SIN
from kinepoly.geom.vec import Vec, add, angle_of, cross, norm, perp, rotate, scale, sub
from kinepoly.model.mechanism import Mechanism, point_label
from kinepoly.notice import Notice
from kinepoly.scene.spec import SliderSpec
from kinepoly.model.pose import Pose

__all__ = ["Crossing", "PolygonBuilder", "sense"]

Kind = Literal["velocity", "acceleration"]
Crossing = Callable[[Line, Line], Intersection]
"""How two direction lines are crossed: ``kinepoly.geom.intersect`` (the bench swaps in others)."""


def sense(rate: float) -> str:
    return "ccw" if rate > 0 else ("cw" if rate < 0 else "zero")


class PolygonBuilder:
    """Mutable while one polygon is constructed; ``steps`` and ``tips`` are its output."""

    def __init__(self, mechanism: Mechanism, pose: Pose, kind: Kind, omega: dict[str, float] | None = None,
                 unit: str = "mm", crossing: Crossing = intersect) -> None:
        self.mechanism = mechanism
        self.crossing = crossing
        self.pose = pose
        self.kind = kind
        self.symbol = "v" if kind == "velocity" else "a"
        self.unit = f"{unit}/s" if kind == "velocity" else f"{unit}/s^2"
        self.omega = omega if omega is not None else {}
        self.rate: dict[str, float] = {}
        self.tips: dict[str, Vec] = {}
        self.members: dict[str, list[tuple[str, Vec]]] = {}
        self.steps: list[Step] = []
        self.notices: list[Notice] = []
        if mechanism.ground is not None:
            self.set_rate(mechanism.ground, 0.0)  # and every link that slides on it without turning
            for p in mechanism.scene.link(mechanism.ground).points:
                self._register(p.name, (0.0, 0.0), p.name, list(mechanism.links_of_point(p.name)))

    # -- where points are ---------------------------------------------------------------
    def world(self, point: str) -> Vec:
        owner = next(link for link in self.mechanism.links_of_point(point) if link in self.pose.links)
        return self.pose.links[owner].world(self.mechanism.local(owner, point))

    def label(self, link: str, point: str) -> str:
        return point if self.mechanism.has_point(link, point) else point_label(point, link)

    def tip_name(self, label: str) -> str:
        return label.lower()

    # -- rates (omega or alpha) ---------------------------------------------------------------
    def rate_of(self, link: str) -> float | None:
        return self.mechanism.class_rate(self.rate, link)

    def set_rate(self, link: str, value: float) -> None:
        for other in self.mechanism.turning_together(link):
            self.rate[other] = value

    # -- tips ---------------------------------------------------------------------------------
    def _register(self, label: str, value: Vec, point: str, links: list[str]) -> None:
        self.tips[label] = value
        at = self.world(point)
        for link in links:
            entries = self.members.setdefault(link, [])
            if all(name != label for name, _ in entries):
                entries.append((label, at))

    def add_tip(self, link: str, point: str, value: Vec) -> str:
        """Record the tip of ``point`` as a point of ``link`` (and of the pin's other link)."""
        label = self.label(link, point)
        links = [link]
        if label == point:
            links = [x for x in self.mechanism.links_of_point(point)]
        self._register(label, value, point, links)
        return label

    def tip(self, link: str, point: str) -> Vec:
        """The tip of ``point`` as a point of ``link``, constructing it when it is not known yet."""
        label = self.label(link, point)
        if label in self.tips:
            return self.tips[label]
        if link == self.mechanism.ground:
            self.add_tip(link, point, (0.0, 0.0))
            return (0.0, 0.0)
        members = self.members.get(link, [])
        if len(members) >= 2:
            value = self._image(link, point, label, members)
        elif len(members) == 1 and self.rate_of(link) is not None:
            value = self._relative(link, point, label, members[0])
        else:
            raise SingularityError(f"the {self.kind} of {label} cannot be constructed: link {link} has "
                                   f"{len(members)} known tip(s) and no known angular rate")
        self.add_tip(link, point, value)
        return value

    def _relative(self, link: str, point: str, label: str, member: tuple[str, Vec]) -> Vec:
        ref_label, ref_at = member
        r = sub(self.world(point), ref_at)
        start = self.tips[ref_label]
        name = f"{label}/{ref_label}"
        if self.kind == "velocity":
            w = self.rate_of(link) or 0.0
            rel = scale(w, perp(r))
            end = add(start, rel)
            text = (f"Lay v_{name} = omega{self._ground()}{link} x {ref_label}{label}: |v_{name}| = "
                    f"{abs(w):.6g} x {norm(r):.6g} = {norm(rel):.6g} {self.unit}, perpendicular to "
                    f"{ref_label}{label}, in the sense of omega ({sense(w)}), from the tip of v_{ref_label}.")
            vectors: tuple[DrawnVector, ...] = (DrawnVector(f"v_{name}", start, end, "relative"),)
            known: tuple[tuple[str, str], ...] = ((f"v_{ref_label}", "magnitude and direction"),
                                                  (f"v_{name}", "magnitude and direction"))
            rates: tuple[tuple[str, str | float], ...] = (("magnitude", norm(rel)), ("rate", abs(w)),
                                                          ("sense", sense(w)))
        else:
            w = self.omega_of(link)
            alpha = self.rate_of(link) or 0.0
            normal = scale(-w * w, r)
            tangential = scale(alpha, perp(r))
            mid = add(start, normal)
            end = add(mid, tangential)
            text = (f"Lay a^n_{name} = omega^2 |{ref_label}{label}| = {norm(normal):.6g} {self.unit} toward "
                    f"{ref_label}, then a^t_{name} = alpha |{ref_label}{label}| = {norm(tangential):.6g} "
                    f"{self.unit} perpendicular to {ref_label}{label} ({sense(alpha)}).")
            vectors = (DrawnVector(f"a^n_{name}", start, mid, "normal"),
                       DrawnVector(f"a^t_{name}", mid, end, "tangential"))
            known = ((f"a_{ref_label}", "magnitude and direction"), (f"a^n_{name}", "magnitude and direction"),
                     (f"a^t_{name}", "magnitude and direction"))
            rates = (("magnitude", norm(sub(end, start))), ("rate", abs(alpha)), ("sense", sense(alpha)),
                     ("omega", abs(w)), ("normal", norm(normal)), ("tangential", norm(tangential)))
        self.steps.append(Step(self.kind, "known", f"{self.symbol}_{label} = {self.symbol}_{ref_label} + "
                               f"{self.symbol}_{name}", text, self.tip_name(label), known, vectors,
                               value=end, topic="relative",
                               params=(("point", label), ("reference", ref_label), ("link", link),
                                       ("ground", self._ground()), ("length", norm(r)), *rates)))
        return end

    def omega_of(self, link: str) -> float:
        omega = self.mechanism.class_rate(self.omega, link)
        return 0.0 if omega is None else omega

    def _ground(self) -> str:
        return self.mechanism.ground or ""

    def _image(self, link: str, point: str, label: str, members: list[tuple[str, Vec]]) -> Vec:
        at = self.world(point)
        (la, wa), (lb, wb) = max(
            ((m, n) for k, m in enumerate(members) for n in members[k + 1:]),
            key=lambda pair: norm(sub(pair[1][1], pair[0][1])) + abs(cross(sub(pair[1][1], pair[0][1]),
                                                                         sub(at, pair[0][1]))),
        )
        a, b = self.tips[la], self.tips[lb]
        side = sub(wb, wa)
        if norm(side) == 0.0:
            raise SingularityError(f"image of {label}: the known points {la} and {lb} of link {link} coincide")
        equation = f"triangle {la.lower()}{lb.lower()}{label.lower()} ~ triangle {la}{lb}{label} (same sense)"
        angle_a = angle_of(sub(at, wa)) - angle_of(side)
        angle_b = angle_of(sub(at, wb)) - angle_of(scale(-1.0, side))
        polygon_side = sub(b, a)
        if norm(polygon_side) == 0.0:
            value = a
            text = (f"The tips {la.lower()} and {lb.lower()} coincide: link {link} translates at this "
                    f"instant, so {label.lower()} coincides with them.")
            self.steps.append(Step(self.kind, "image", equation, text, self.tip_name(label), value=value,
                                   topic="image-translating",
                                   params=(("link", link), ("point", label), ("first", la), ("second", lb))))
            return value
        line_a = Line(a, rotate(polygon_side, angle_a), f"from {la.lower()} at angle {lb}{la}{label}")
        line_b = Line(b, rotate(scale(-1.0, polygon_side), angle_b), f"from {lb.lower()} at angle {la}{lb}{label}")
        crossing = self.crossing(line_a, line_b)
        if abs(crossing.sin_angle) >= COLLINEAR_SIN:
            value = crossing.point
            text = (f"Image of {label} on link {link} (Mehmke): from {la.lower()} draw a line at "
                    f"{math.degrees(angle_a):.4g} deg to {la.lower()}{lb.lower()} and from {lb.lower()} one at "
                    f"{math.degrees(angle_b):.4g} deg to {lb.lower()}{la.lower()}, the angles of triangle "
                    f"{la}{lb}{label} at {la} and {lb}; they cross at {label.lower()}.")
            first_deg = math.degrees(math.remainder(angle_a, 2.0 * math.pi))
            second_deg = math.degrees(math.remainder(angle_b, 2.0 * math.pi))
            self.steps.append(Step(self.kind, "image", equation, text, self.tip_name(label),
                                   lines=(line_a, line_b), value=value, topic="image",
                                   params=(("link", link), ("point", label), ("first", la), ("second", lb),
                                           ("angle_first", first_deg), ("angle_second", second_deg)),
                                   directions=(Direction("", "at-angle", f"{la}{lb}".lower(), la.lower(),
                                                         angle_deg=first_deg),
                                               Direction("", "at-angle", f"{lb}{la}".lower(), lb.lower(),
                                                         angle_deg=second_deg))))
            return value
        ratio = ((at[0] - wa[0]) * side[0] + (at[1] - wa[1]) * side[1]) / (norm(side) ** 2)
        height = cross(side, sub(at, wa)) / (norm(side) ** 2)
        foot = add(a, scale(ratio, polygon_side))
        value = add(foot, scale(height, perp(polygon_side)))
        text = (f"Image of {label} on link {link} (Mehmke, flat triangle): divide {la.lower()}{lb.lower()} in the "
                f"ratio {ratio:.6g} as {label}'s foot divides {la}{lb}, and step off {height:.6g} times "
                f"|{la.lower()}{lb.lower()}| perpendicular to it, on the same side as {label}.")
        self.steps.append(Step(self.kind, "proportional", equation, text, self.tip_name(label),
                               lines=(Line(a, polygon_side, f"{la.lower()}{lb.lower()}"),), value=value,
                               topic="proportional",
                               params=(("link", link), ("point", label), ("first", la), ("second", lb),
                                       ("ratio", ratio), ("height", height)),
                               directions=(Direction("", "along", f"{la}{lb}".lower(), la.lower()),)))
        return value

    def lay_driven_slider(self, slider: SliderSpec, amount: float, direction: Vec) -> Vec:
        """The tip of a driven slider's point: ``amount`` (s_dot or s_ddot) along the slide, from o.

        Returns the block's motion relative to the guide (the guide or the block is the frame).
        """
        rel = scale(amount, direction)
        moving = slider.block if slider.guide == self.mechanism.ground else slider.guide
        value = rel if moving == slider.block else scale(-1.0, rel)
        label = self.add_tip(moving, slider.point, value)
        name = "s_dot" if self.kind == "velocity" else "s_ddot"
        self.steps.append(Step(self.kind, "known", f"{self.symbol}_{label} = {name}{slider.name} along the slide",
                               f"Lay {self.symbol}_{label}: |{name}{slider.name}| = {abs(amount):.6g} {self.unit} "
                               f"along slider {slider.name}'s line, from the pole o.", label.lower(),
                               ((f"{self.symbol}_{label}", "magnitude and direction"),),
                               (DrawnVector(f"{self.symbol}_{label}", (0.0, 0.0), value, "absolute"),), value=value,
                               topic="driven-slider", params=(("slider", slider.name), ("point", label),
                                                              ("amount", amount))))
        return rel

    # -- the intersection of two direction lines ----------------------------------------------------
    def cross_lines(self, first: Line, second: Line, what: str, where: str) -> Vec:
        """The crossing of two direction lines; parallel lines are a singular position (a named error).

        How near to parallel they may come is judged with the whole solution's error estimate
        (``kinepoly.accuracy``), which the steps' lines feed.
        """
        try:
            crossing = self.crossing(first, second)
        except ParallelLinesError as error:  # a line with no direction: two joints of a link coincide
            raise SingularityError(f"singular position {where}: at joint {what} the {self.kind} construction "
                                   f"fails because {error}; two joints of one link are at the same place") from None
        if not crossing.is_finite:
            raise SingularityError(
                f"singular position {where}: at joint {what} the {self.kind} direction lines ({first.label}; "
                f"{second.label}) are parallel: the links that meet there are in line, or square to a slide (a "
                f"dead centre or change point), so the {self.kind} of {what} is not determined by the input"
            )
        return crossing.point
