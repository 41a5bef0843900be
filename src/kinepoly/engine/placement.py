"""What placing groups gives: the poses at every row, the rows that closed, the failures (``Placement``
while the executor works, ``Positions`` when it is done)."""

from __future__ import annotations

from collections.abc import Callable, Iterable

import numpy as np
from msgspec import Struct, field

from kinepoly.engine.gears import Rolled
from kinepoly.geom.arrays import Bools, Points, Reals
from kinepoly.model.array_pose import ArrayPose
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import LinkPose
from kinepoly.notice import Notice

__all__ = ["Failure", "Placement", "Positions"]


class Failure(Struct, frozen=True):
    """Rows where one group cannot be assembled (rows where an earlier group failed are not among them)."""

    group: str
    joint: str
    rows: Bools
    why: Callable[[int], str]


class Placement(Struct, frozen=True):
    """What placing some groups gave: poses, the rows that closed, failures, rough rows, warnings."""

    poses: dict[str, ArrayPose]
    ok: Bools
    failures: tuple[Failure, ...] = ()
    near: tuple[Failure, ...] = ()
    notices: tuple[Notice, ...] = ()
    values: tuple[Reals, ...] = ()
    """Each input's value at every row (``engine.carry.drive_values``)."""
    rolled: dict[str, Rolled] = field(default_factory=dict)
    """The gears placed by rolling, with how far each has rolled (``engine.gears``)."""
    marks: dict[str, Points] = field(default_factory=dict)
    """Points found while placing (a spline cam's contact and centre of curvature), by name."""
    contact_parameters: dict[str, Reals] = field(default_factory=dict)
    """Each spline cam's contact parameter on its profile at every row (``engine.cam_place``)."""

    def with_poses(self, poses: dict[str, ArrayPose]) -> Placement:
        """This placement with ``poses`` for its poses (``msgspec.structs.replace``, made directly)."""
        return Placement(poses, self.ok, self.failures, self.near, self.notices, self.values, self.rolled,
                         self.marks, self.contact_parameters)

    def row_poses(self, links: Iterable[str], row: int) -> dict[str, LinkPose]:
        """The poses of ``links`` at ``row`` as scalar values (for the one-row solvers)."""
        return {link: LinkPose(*self.poses[link].row(row)) for link in links}

    def row_values(self, row: int) -> dict[int, float]:
        """Each input's value at ``row``, by input index."""
        return {index: float(values[row]) for index, values in enumerate(self.values)}


class Positions(Struct):
    """Poses of every link of the plan at every row; ``ok`` where all of them could be placed."""

    mechanism: Mechanism
    poses: dict[str, ArrayPose]
    ok: Bools
    failures: tuple[Failure, ...] = ()
    near: tuple[Failure, ...] = ()
    notices: tuple[Notice, ...] = ()
    values: tuple[Reals, ...] = ()
    """Each input's value at every row: theta (rad) or s (length)."""
    marks: dict[str, Points] = field(default_factory=dict)
    """Points the construction found on the mechanism (a triad's Assur point), by name."""
    contact_parameters: dict[str, Reals] = field(default_factory=dict)
    """Each spline cam's contact parameter on its profile at every row."""
    _points: dict[str, Points] = field(default_factory=dict)
    _turned: dict[tuple[str, str], tuple[Points, Points]] = field(default_factory=dict)
    _chords: dict[int, tuple[str, str]] = field(default_factory=dict)
    """Each turned chord made (``chord``), by the array's identity (the chord is kept, so the identity is its own)."""
    _products: dict[tuple[tuple[str, str], tuple[str, str]], Points] = field(default_factory=dict)
    _sines: dict[tuple[int, float, float], Reals] = field(default_factory=dict)
    """Each sine made (``chord_sine``), by its product's identity (the product is kept) and the chords' lengths."""
    _zeros: tuple[Points, Reals] | None = None
    """0 at every row as points and as rates (``zeros``), None until asked."""
    _origin: Points | bool | None = None
    """The frame's point at its origin (``_frame_origin``), None until looked for."""
    _every: bool | None = None
    """Whether every row closed (``every_ok``), None until asked."""

    @property
    def n(self) -> int:
        return len(self.ok)

    def every_ok(self) -> bool:
        """Whether every row closed (``ok`` at every row; ``ok`` is not changed once placed): found once."""
        every = self._every
        if every is None:
            every = self._every = bool(np.logical_and.reduce(self.ok))  # ok.all() without its Python wrapper
        return every

    def zeros(self) -> tuple[Points, Reals]:
        """0 at every row, as points and as rates: made once for the polygons built on these positions (the pole, the
        tip of every point of the frame; the frame's rate). Do not change them in place."""
        zeros = self._zeros
        if zeros is None:
            n = len(self.ok)
            zeros = self._zeros = (np.zeros(n, np.complex128), np.zeros(n))
        return zeros

    def point(self, name: str) -> Points:
        """World position of a named point (through the first solved link that has it)."""
        points = self._points
        if name in points:
            return points[name]
        poses = self.poses
        for link, at in self.mechanism.places_of(name):  # the first solved link that has it
            if link in poses:
                found = points[name] = poses[link].world_at(at)
                return found
        raise KeyError(f"no solved link holds point {name}")

    def chord(self, start: str, end: str) -> tuple[Points, Points]:
        """The vector from point ``start`` to point ``end`` at every row, and that vector turned a quarter
        counter-clockwise: the direction of the relative velocity of ``end`` about ``start`` on their link.
        Made once, for the velocity and acceleration polygons alike (do not change them in place)."""
        key = (start, end)
        turned = self._turned
        if key in turned:
            return turned[key]
        r, at = self.point(end), self.point(start)
        origin = self._origin
        if origin is None:
            origin = self._origin = self._frame_origin()
        if at is not origin:  # from the frame's origin, +0 at every row, r is the end itself: r - 0 is r
            r = r - at
        found = turned[key] = (r, 1j * r)
        self._chords[id(found[1])] = key
        return found

    def _frame_origin(self) -> Points | bool:
        """The frame's point at its origin, where one was made (+0 at every row: ``ArrayPose.world_at``), else False
        (it is looked for once: where made later, a chord from it is taken as from any point)."""
        ground = self.mechanism.ground
        frame = self.poses.get(ground) if ground is not None else None
        found = frame.made(0j) if frame is not None and frame.still else None
        return False if found is None else found

    def chord_product(self, first: Points, second: Points) -> Points | None:
        """conj(first) * second where both are turned chords made here (``chord``): its imaginary part their cross
        product, its real part their dot product; made once, for the velocity and acceleration polygons' crossing
        of the same two lines and the transmission angle between them alike (None for other directions)."""
        chords = self._chords
        a, b = chords.get(id(first)), chords.get(id(second))
        if a is None or b is None:
            return None
        key = (a, b)
        products = self._products
        if key in products:
            return products[key]
        found = products[key] = first.conjugate() * second
        return found

    def chord_sine(self, product: Points | None, length1: float | None, length2: float | None) -> Reals | None:
        """The sine of the angle between two turned chords whose product is ``product`` (``chord_product``) and whose
        lengths are the constants ``length1`` and ``length2``: their cross product over the lengths, as
        ``geom.arrays.cross_lines`` makes it; made once for the velocity and acceleration polygons' crossing of the
        same two lines (None where there is no product, or a length is measured or differs by row: a family's)."""
        if product is None or not isinstance(length1, float) or not isinstance(length2, float):
            return None
        key = (id(product), length1, length2)
        sines = self._sines
        if key in sines:
            return sines[key]
        found = sines[key] = np.asarray(product.imag) / (length1 * length2)
        return found

    def world(self, link: str, point: str) -> Points:
        return self.poses[link].world_at(self.mechanism.local_at(link, point))

    def add_point(self, name: str, at: Points) -> None:
        """A point the construction finds on the mechanism (a triad's Assur point), by name."""
        self._points[name] = at
        self.marks[name] = at

    def row(self, k: int) -> dict[str, LinkPose]:
        """The poses of row k as scalar values."""
        return {link: LinkPose(*pose.row(k)) for link, pose in self.poses.items()}
