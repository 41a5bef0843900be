"""A sweep as frames: what every drawing of the motion shows, at scales fixed for the whole cycle. Pure.

``make_frames(result, prepared, parts)`` reads the sweep (its positions, its columns, each row's
status) and the engine's velocity and acceleration polygons over all rows
(``construct_velocity``, ``construct_acceleration`` on the sweep's own positions): it holds no
geometry of its own. A frame is a row the mechanism reaches; rows it cannot reach are skipped
and listed. Polygon tips are in paper mm, the pole at 0: ``tips = k * value`` with ``k`` (kv or
ka) one round number for every frame, the largest polygon of the cycle's ok rows fitting its
panel, so sizes compare from frame to frame. Singular rows (a dead or change point) keep the
mechanism and leave the polygons out (``valid`` False), as do near-singular rows whose polygons
run off the panel at that scale.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from msgspec import Struct

from kinepoly.engine.acceleration import AccelerationResult, construct_acceleration
from kinepoly.engine.centrode import frame_centrodes
from kinepoly.engine.polygon import Polygon
from kinepoly.engine.sliders import slider_motion
from kinepoly.engine.velocity import VelocityResult, construct_velocity, slide_direction
from kinepoly.errors import AssemblyError, SceneError
from kinepoly.geom.arrays import Bools, Points, Reals
from kinepoly.geom.tolerances import TINY_POSITIVE
from kinepoly.present.scales import nice_floor
from kinepoly.scene.link_point import LinkPoint, point_of
from kinepoly.scene.spec import LinkInput, Scene
from kinepoly.sweep.plots import robust_window
from kinepoly.sweep.result import CANNOT_ASSEMBLE, NEAR_SINGULAR, OK, SweepResult
from kinepoly.sweep.run import PreparedSweep
from kinepoly.sweep.shown import shown_values

__all__ = ["NO_POLYGON", "PANEL_MM", "PARTS", "Frames", "LinkFrames", "PolygonFrames", "SliderFrames", "Trace", "Value",
           "fitting_scale", "make_frames"]

PARTS = ("mechanism", "velocity", "acceleration", "centers", "paths", "functions")
"""What a frame can show: the mechanism, the two polygons, the instant centers with the frame, the
point paths traced so far, a cursor on the transmission functions."""
DEFAULT_PARTS = ("mechanism", "velocity", "acceleration", "paths")
PANEL_MM = 90.0
"""A polygon panel's side on paper: the largest polygon of the cycle fits a disc of this diameter
around the pole (less a margin for the labels)."""
NO_POLYGON = ("", "near-singular: beyond the cycle's scale", "singular: no polygon", "")
"""What a polygon panel says in place of a polygon it leaves out, by the row's status."""
_ROOM_MM = 0.5 * PANEL_MM - 6.0


def fitting_scale(radius: float, room_mm: float = _ROOM_MM) -> float:
    """The largest round scale (``present.scales.nice_floor``) that draws ``radius`` within ``room_mm``."""
    if not (radius > 0.0 and math.isfinite(radius)):
        return 1.0
    return nice_floor(room_mm / radius)


class PolygonFrames(Struct, frozen=True):
    """One polygon at every frame: ``tips[k, j]`` is tip ``labels[j]`` of frame k in paper mm (pole at 0).

    ``images`` are each link's image (tip indices, -1 the pole), ``vectors`` the arrows drawn
    (start, end, term) with -1 the pole; tips past ``len(labels)`` are construction points
    without a label (the end of a Coriolis term).
    """

    kind: str
    symbol: str
    scale: float
    unit: str
    labels: tuple[str, ...]
    tips: npt.NDArray[np.complex128]
    valid: Bools
    images: tuple[tuple[int, ...], ...]
    vectors: tuple[tuple[int, int, str], ...]
    center: complex = 0j
    """The middle of every frame's polygon (paper mm from the pole): the panel is centred there."""


class LinkFrames(Struct, frozen=True):
    """A link's points at every frame (the scene's length unit, the scene's frame); the frame link does not move."""

    name: str
    points: tuple[str, ...]
    xy: npt.NDArray[np.complex128]
    ground: bool


class SliderFrames(Struct, frozen=True):
    """A slide: its guide line (from ``guide_a`` to ``guide_b``), the block's point and the slide's direction."""

    name: str
    guide_a: Points
    guide_b: Points
    block: Points
    direction: Points


class Trace(Struct, frozen=True):
    """A point (a path) or an instant center at every frame; ``valid`` False where it has none."""

    name: str
    xy: Points
    valid: Bools


class Value(Struct, frozen=True):
    """A quantity shown beside the drawing, at every row of the sweep (not only the frames)."""

    name: str
    unit: str
    values: Reals
    valid: Bools
    order: int


class Frames(Struct, frozen=True):
    """Everything a drawing of the motion needs; frame k is the sweep's row ``rows[k]``."""

    title: str
    input_name: str
    input_unit: str
    length_unit: str
    inputs: Reals
    status: npt.NDArray[np.int8]
    rows: npt.NDArray[np.intp]
    skipped: tuple[int, ...]
    links: tuple[LinkFrames, ...]
    sliders: tuple[SliderFrames, ...]
    paths: tuple[Trace, ...]
    centers: tuple[Trace, ...]
    velocity: PolygonFrames | None
    acceleration: PolygonFrames | None
    values: tuple[Value, ...]
    box: tuple[float, float, float, float]
    parts: tuple[str, ...]
    periodic: bool
    scene: Scene | None = None
    """The scene swept (its frames are drawn as its solutions at each row: ``motion.sheets``)."""

    @property
    def count(self) -> int:
        return len(self.rows)

    def value(self, name: str) -> Value:
        return next(v for v in self.values if v.name == name)

    def functions(self) -> tuple[tuple[Value, ...], tuple[float, float] | None]:
        """The transmission functions a ``functions`` panel draws (the omegas, else the first order, four at
        most) and its value window where flagged rows run off the ok ones (``sweep.plots.robust_window``)."""
        chosen = tuple([v for v in self.values if v.unit == "rad/s"] or [v for v in self.values if v.order == 1])[:4]
        ok = self.status == OK
        return chosen, robust_window([v.values[v.valid] for v in chosen], [v.values[v.valid & ok] for v in chosen])


def _polygon_frames(polygon: Polygon, idx: npt.NDArray[np.intp], valid: Bools, ok: Bools, unit: str,
                    extras: list[tuple[str, str, Points | None, str]]) -> PolygonFrames:
    """The polygon at every frame, at the round scale that fits the largest of the ``ok`` frames (of all
    ``valid`` ones where none is ok); a near-singular frame whose polygon leaves the panel at that scale
    is left out, as a singular one is."""
    mech = polygon.mechanism
    ground_points = set(mech.scene.link(mech.ground).point_names) if mech.ground else set()
    ground_points |= {label for label in polygon.tips if mech.ground and LinkPoint.parse(label).link == mech.ground}
    labels = [label for label in polygon.tips if label not in ground_points]
    index = {label: j for j, label in enumerate(labels)}
    index.update({g: -1 for g in ground_points})
    values = [np.asarray(polygon.tips[label])[idx] for label in labels]
    vectors: list[tuple[int, int, str]] = [(-1, index[label], "absolute") for label in labels]
    aux: list[Points] = []
    for start, end, through, term in extras:  # start -> start + through (term), then on to end
        if start in index and end in index:
            if through is None:
                vectors.append((index[start], index[end], term))
                continue
            j = len(labels) + len(aux)
            aux.append(np.asarray(polygon.tips[start])[idx] + np.asarray(through)[idx])
            vectors += [(index[start], j, term), (j, index[end], "sliding")]
    images = []
    for link, members in polygon.members.items():
        if link == mech.ground:
            continue
        image = tuple(dict.fromkeys(index[m.label] for m in members if m.label in index))
        if len(image) >= 2:
            images.append(image)
    raw = np.stack(values + aux, axis=1) if values or aux else np.zeros((len(idx), 0), np.complex128)
    finite = valid & np.isfinite(raw).all(axis=1)
    sized = finite & ok if (finite & ok).any() else finite
    every = np.append(raw[sized].ravel(), 0j)
    low, high = complex(every.real.min(), every.imag.min()), complex(every.real.max(), every.imag.max())
    scale = fitting_scale(0.5 * max(high.real - low.real, high.imag - low.imag))
    off = (raw - 0.5 * (low + high)) * scale  # from the panel's centre, in mm
    finite &= sized | (np.maximum(np.abs(off.real), np.abs(off.imag)).max(axis=1, initial=0.0) <= 0.5 * PANEL_MM)
    tips = np.where(finite[:, None], raw * scale, 0.0).astype(np.complex128)
    return PolygonFrames(polygon.kind, polygon.symbol, scale, unit, tuple(labels), tips, finite, tuple(images),
                         tuple(vectors), 0.5 * (low + high) * scale)


def _values(result: SweepResult) -> tuple[Value, ...]:
    """The values shown beside the drawing, by the number rule (``sweep.shown``)."""
    unit = result.scene.units
    length, angle = unit.length, unit.angle
    shown = shown_values(result)
    out = [Value(result.input.name, angle if isinstance(result.scene.input, LinkInput) else length,
                 result.input.values, result.input.valid, 0)]
    names = {c.name for c in result.columns}
    units = {"angle": angle, "omega": "rad/s", "alpha": "rad/s^2", "slider": length, "slider-rate": f"{length}/s",
             "slider-acceleration": f"{length}/s^2", "transmission": angle}
    for col in result.columns:
        if col.kind in units:
            out.append(Value(col.name, units[col.kind], shown[col.name], col.valid, col.order))
        elif col.kind in ("velocity", "acceleration", "coriolis") and col.name.endswith("_x") \
                and col.name[:-2] + "_y" in names:
            other = result.column(col.name[:-2] + "_y")
            where = "/s" if col.kind == "velocity" else "/s^2"
            out.append(Value(f"|{col.name[:-2]}|", f"{length}{where}", np.hypot(shown[col.name], shown[other.name]),
                             col.valid & other.valid, col.order))
    return tuple(out)


def _links(result: SweepResult, idx: npt.NDArray[np.intp]) -> tuple[LinkFrames, ...]:
    positions = result.positions
    assert positions is not None
    mech = positions.mechanism
    out = []
    for name in mech.link_names:
        points = tuple(mech.scene.link(name).point_names)
        if name == mech.ground:
            xy = np.array([[complex(*mech.local(name, p)) for p in points]] * len(idx), np.complex128)
        elif name in positions.poses:
            xy = np.stack([positions.world(name, p)[idx] for p in points], axis=1) if points else \
                np.zeros((len(idx), 0), np.complex128)
        else:
            continue
        out.append(LinkFrames(name, points, xy.reshape(len(idx), len(points)), name == mech.ground))
    return tuple(out)


def _sliders(result: SweepResult, idx: npt.NDArray[np.intp], size: float) -> tuple[SliderFrames, ...]:
    positions = result.positions
    assert positions is not None
    out = []
    for spec in positions.mechanism.scene.sliders:
        if spec.guide not in positions.poses or spec.block not in positions.poses:
            continue
        e = np.asarray(slide_direction(positions, spec))[idx]
        through = np.asarray(positions.poses[spec.guide].world(spec.through))[idx]
        block = np.asarray(positions.world(spec.block, spec.point))[idx]
        s = np.asarray(slider_motion(positions, spec).s)[idx]
        # the slide's whole stroke, and the point it is set through (so that a slot meets its lever)
        low, high = min(float(s.min()), 0.0) - 0.15 * size, max(float(s.max()), 0.0) + 0.15 * size
        out.append(SliderFrames(spec.name, through + low * e, through + high * e, block, e))
    return tuple(out)


def _centers(velocity: VelocityResult, idx: npt.NDArray[np.intp], valid: Bools, size: float) -> tuple[Trace, ...]:
    """The instant center of each moving link with the frame (``engine.centrode``), where it is on the sheet:
    within a thousand times the mechanism's size."""
    polygon = velocity.polygon
    mech = polygon.mechanism
    out = []
    for link in mech.link_names:
        if link == mech.ground or link not in polygon.positions.poses or polygon.rate_of(link) is None:
            continue
        found = frame_centrodes(velocity, link)
        at = np.asarray(found.fixed)[idx]
        near = np.asarray(polygon.positions.point(mech.scene.link(link).points[0].name))[idx]
        shown = valid & np.asarray(found.finite)[idx] & (np.abs(at - near) <= 1e3 * size)
        out.append(Trace(f"I{mech.ground or ''}{link}", np.where(shown, at, 0.0), shown))
    return tuple(out)


def _box(links: tuple[LinkFrames, ...], sliders: tuple[SliderFrames, ...]) -> tuple[float, float, float, float]:
    parts = [link.xy.ravel() for link in links] + [s.guide_a for s in sliders] + [s.guide_b for s in sliders]
    every = np.concatenate(parts) if parts else np.zeros(1, np.complex128)
    return (float(every.real.min()), float(every.imag.min()), float(every.real.max()), float(every.imag.max()))


def make_frames(result: SweepResult, prepared: PreparedSweep, parts: tuple[str, ...] = DEFAULT_PARTS) -> Frames:
    """The frames of ``result`` (made from ``prepared``): rows the mechanism reaches, the polygons at fixed scales."""
    unknown = [p for p in parts if p not in PARTS]
    if unknown:
        raise SceneError(f"--parts: expected some of {', '.join(PARTS)}, got {', '.join(unknown)}")
    positions, shown = result.positions, result.shown
    if positions is None or shown is None:
        raise ValueError("this sweep result keeps no poses (it was not made by kinepoly.sweep.run_sweep)")
    computed = np.flatnonzero(shown)
    reach = result.status != CANNOT_ASSEMBLE
    rows = np.flatnonzero(reach).astype(np.intp)
    if not len(rows):
        raise AssemblyError(f"{result.scene.title}: the mechanism cannot be assembled at any of the {result.rows} "
                            "positions asked")
    idx = computed[rows]
    valid = result.status[rows] <= NEAR_SINGULAR
    ok = result.status[rows] == OK
    asked = prepared.asked
    length = result.scene.units.length
    velocity: VelocityResult | None = None
    acceleration: AccelerationResult | None = None
    with np.errstate(all="ignore"):
        if asked.needs_velocity or "centers" in parts:
            velocity = construct_velocity(positions, prepared.plan, asked.velocity)
            if asked.needs_acceleration:
                acceleration = construct_acceleration(velocity, prepared.plan, asked.acceleration)
        links = _links(result, idx)
        size = max(TINY_POSITIVE, max(float(np.abs(link.xy - link.xy[:, :1]).max()) if link.xy.size else 0.0
                                for link in links))
        sliders = _sliders(result, idx, size)
        v_frames = a_frames = None
        mech = positions.mechanism
        if velocity is not None and "velocity" in parts:
            extras: list[tuple[str, str, Points | None, str]] = [
                (LinkPoint(s.point, s.guide).text, velocity.polygon.label(s.block, s.point), None, "sliding")
                      for s in mech.scene.sliders if s.guide != mech.ground]
            v_frames = _polygon_frames(velocity.polygon, idx, valid, ok, f"{length}/s", extras)
        if acceleration is not None and "acceleration" in parts:
            extras = [(LinkPoint(s.point, s.guide).text, acceleration.polygon.label(s.block, s.point),
                       acceleration.coriolis[s.name], "coriolis")  # a_P(guide) + coriolis + sliding = a_P(block)
                      for s in mech.scene.sliders if s.name in acceleration.coriolis and s.guide != mech.ground]
            a_frames = _polygon_frames(acceleration.polygon, idx, valid, ok, f"{length}/s^2", extras)
        paths: tuple[Trace, ...] = ()
        if "paths" in parts:
            labels = dict.fromkeys(point_of(label) for label in (*result.scene.find.velocity,
                                                                         *result.scene.find.acceleration))
            paths = tuple(Trace(p, np.asarray(positions.point(p))[idx], np.ones(len(idx), np.bool_))
                          for p in labels)
        centers = _centers(velocity, idx, valid, size) if velocity is not None and "centers" in parts else ()
    unit = result.scene.units
    return Frames(result.scene.title, result.input.name,
                  unit.angle if isinstance(result.scene.input, LinkInput) else unit.length, length,
                  result.input.values, result.status, rows, tuple(int(r) for r in np.flatnonzero(~reach)), links,
                  sliders, paths, centers, v_frames, a_frames, _values(result), _box(links, sliders),
                  tuple(p for p in PARTS if p in parts), result.periodic, result.scene)
