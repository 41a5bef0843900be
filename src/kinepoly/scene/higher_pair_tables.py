"""The higher pairs of a scene: ``[[gears]]`` (pitch curves rolling without slip) and ``[[cams]]``.

A gear's pitch is ``{ center = "O2", radius = 48 }`` (a point of the gear's own link) or, for a rack,
``{ line = { through = [x, y], angle = a } }`` in the rack's frame; ``phase`` places the reference mesh (a
circle's in the scene's angle unit, a line's a length; see docs/scene-format.md, "Higher pairs").
A cam's profile is ``{ circle = { center = [x, y], radius = R } }`` in the cam's frame; its follower
touches it by a ``roller``, a ``flat`` face, a ``knife`` edge or a circular profile of its own
(``follower_profile = { circle = { center = "C", radius = r } }``, read as a roller on C: two circles in
contact keep their centres R + r apart). Pairs are numbered from 1 in key
paths (``gears.1.pitch.2.radius``) and named like sliders (``"23"``).
"""

from __future__ import annotations

from msgspec.structs import replace

from kinepoly.scene.lines import KeyPath
from kinepoly.scene.problems import no_such, show_value, suggest
from kinepoly.scene.profile_points import read_profile_points
from kinepoly.scene.reader_state import ReaderState
from kinepoly.scene.source import Table
from kinepoly.scene.spec import CamSpec, GearSpec, PitchCircle, PitchLine, Vector
from kinepoly.scene.units import quantity, quantity_pair
from kinepoly.scene.values import check_keys, pair_name, read_name, read_table, require

__all__ = ["HigherPairTables"]

_GEAR_KEYS = ("links", "pitch", "internal", "phase", "name")
_PITCH_KEYS = ("center", "radius", "line")
_LINE_KEYS = ("through", "angle")
_CAM_KEYS = ("cam", "follower", "profile", "roller", "flat", "knife", "follower_profile", "contact", "name")
_FOLLOWERS = ("roller", "flat", "knife", "follower_profile")
_PROFILE_KEYS = ("circle", "points")
_CIRCLE_KEYS = ("center", "radius")
_ROLLER_KEYS = ("center", "radius")


class HigherPairTables(ReaderState):
    """Reads ``[[gears]]`` and ``[[cams]]`` against the links already read."""

    # -- shared

    def _array_of_tables(self, key: str, value: object) -> list[Table]:
        if value is None:
            return []
        if not isinstance(value, list) or not all(isinstance(item, dict) for item in value):
            self.report.add((key,), f"expected [[{key}]] tables, got {show_value(value)}")
            return []
        return value

    def _link(self, path: KeyPath, value: object, role: str) -> str | None:
        name = read_name(self.report, path, value, "a link name", "2")
        if name is not None and not self.has_link(name):
            self.report.add(path, lambda: no_such("link", name, self.links or {}))
            return None
        return name

    def _positive(self, path: KeyPath, value: object) -> float | None:
        number = quantity(self.report, path, value, self.kinds.length)
        if number is not None and not number > 0.0:
            self.report.add(path, f"{show_value(value)} is not positive; expected a radius > 0")
            return None
        return number

    def _line(self, path: KeyPath, value: object) -> tuple[Vector, float] | None:
        table = read_table(self.report, path, value, "{ through = [x, y], angle = a }")
        if table is None:
            return None
        check_keys(self.report, path, table, _LINE_KEYS)
        through_value = require(self.report, path, table, "through", "through = [x, y], a point of the line")
        angle_value = require(self.report, path, table, "angle", "angle = a, the line's direction")
        if through_value is None or angle_value is None:
            return None
        through = quantity_pair(self.report, path + ("through",), through_value, self.kinds.length)
        angle = quantity(self.report, path + ("angle",), angle_value, self.kinds.angle)
        return None if through is None or angle is None else (through, angle)

    # -- gears

    def read_gears(self, value: object) -> list[GearSpec]:
        gears = [self.read_gear(("gears", str(i)), item)
                 for i, item in enumerate(self._array_of_tables("gears", value), start=1)]
        return [gear for gear in gears if gear is not None]

    def read_gear(self, path: KeyPath, table: Table) -> GearSpec | None:
        check_keys(self.report, path, table, _GEAR_KEYS)
        links_value = require(self.report, path, table, "links", 'links = ["2", "3"], the two gears\' links')
        pitch_value = require(self.report, path, table, "pitch",
                              'pitch = [{ center = "O2", radius = 48 }, { center = "O3", radius = 72 }]')
        if links_value is None or pitch_value is None:
            return None
        if not isinstance(links_value, list) or len(links_value) != 2:
            self.report.add(path + ("links",), 'expected two link names like ["2", "3"], got '
                                               f'{show_value(links_value)}')
            return None
        links = [self._link(path + ("links", str(k)), v, "gear") for k, v in enumerate(links_value, start=1)]
        if not isinstance(pitch_value, list) or len(pitch_value) != 2:
            self.report.add(path + ("pitch",), "expected two pitch curves, one per link, got "
                                               f"{show_value(pitch_value)}")
            return None
        pitch = [self.read_pitch(path + ("pitch", str(k)), v, links[k - 1]) for k, v in enumerate(pitch_value, start=1)]
        internal = table.get("internal", False)
        if not isinstance(internal, bool):
            self.report.add(path + ("internal",), f"expected true or false, got {show_value(internal)}")
            internal = False
        phase = self.read_phase(path + ("phase",), table.get("phase"), pitch)
        first, second = links
        if first is not None and first == second:
            self.report.add(path + ("links",), f'both gears are link "{first}"; expected two different links')
            return None
        if first is None or second is None or pitch[0] is None or pitch[1] is None or phase is None:
            return None
        one, two = pitch[0], pitch[1]
        if isinstance(one, PitchLine) and isinstance(two, PitchLine):
            self.report.add(path + ("pitch",), "two pitch lines cannot roll on each other; "
                                               "expected a circle and a line")
            return None
        if internal and not (isinstance(one, PitchCircle) and isinstance(two, PitchCircle)):
            self.report.add(path + ("internal",), "a rack has no inside; expected internal only for two circles")
            return None
        if internal and isinstance(one, PitchCircle) and isinstance(two, PitchCircle) and one.radius == two.radius:
            self.report.add(path + ("pitch",), "an internal pair needs two different radii (their centres are "
                            "|r2 - r3| apart); expected a ring larger than its pinion")
            return None
        name_value = table.get("name")
        name = (read_name(self.report, path + ("name",), name_value, "a pair name", "23") if name_value is not None
                else pair_name(first, second))
        if name is None:
            return None
        return GearSpec(name, (first, second), (one, two), internal, phase, self.report.line(path))

    def read_pitch(self, path: KeyPath, value: object, link: str | None) -> PitchCircle | PitchLine | None:
        table = read_table(self.report, path, value,
                           '{ center = "O2", radius = r } or { line = { through = [x, y], angle = a } }')
        if table is None:
            return None
        check_keys(self.report, path, table, _PITCH_KEYS)
        if "line" in table:
            if "center" in table or "radius" in table:
                self.report.add(path, "a pitch curve is a circle or a line; expected center and radius, or line")
                return None
            found = self._line(path + ("line",), table["line"])
            return None if found is None else PitchLine(found[0], found[1])
        center = require(self.report, path, table, "center", 'center = "O2", a point of the gear\'s link')
        radius = require(self.report, path, table, "radius", "radius = r, the pitch radius")
        if center is None or radius is None:
            return None
        name = read_name(self.report, path + ("center",), center, "a point name", "O2")
        r = self._positive(path + ("radius",), radius)
        if name is not None and link is not None and self.links is not None and link in self.links:
            known = self.links[link].point_names
            if name not in known:
                self.report.add(path + ("center",), f'no point "{name}" in link "{link}"; {suggest(name, known)}')
                return None
        return None if name is None or r is None else PitchCircle(name, r)

    def read_phase(self, path: KeyPath, value: object,
                   pitch: list[PitchCircle | PitchLine | None]) -> tuple[float, float] | None:
        if value is None:
            return (0.0, 0.0)
        if not isinstance(value, list) or len(value) != 2:
            self.report.add(path, f"expected [phase2, phase3], one per gear, got {show_value(value)}")
            return None
        out = []
        for k, (entry, curve) in enumerate(zip(value, pitch, strict=True), start=1):
            kind = self.kinds.length if isinstance(curve, PitchLine) else self.kinds.angle
            number = quantity(self.report, path + (str(k),), entry, kind)
            if number is None:
                return None
            out.append(number)
        return (out[0], out[1])

    # -- cams

    def read_cams(self, value: object) -> list[CamSpec]:
        cams = [self.read_cam(("cams", str(i)), item)
                for i, item in enumerate(self._array_of_tables("cams", value), start=1)]
        return [cam for cam in cams if cam is not None]

    def read_cam(self, path: KeyPath, table: Table) -> CamSpec | None:
        check_keys(self.report, path, table, _CAM_KEYS)
        cam_value = require(self.report, path, table, "cam", 'cam = "2", the link that carries the profile')
        follower_value = require(self.report, path, table, "follower", 'follower = "3", the link it touches')
        profile_value = require(self.report, path, table, "profile",
                                "profile = { circle = { center = [x, y], radius = R } }")
        cam = None if cam_value is None else self._link(path + ("cam",), cam_value, "cam")
        follower = None if follower_value is None else self._link(path + ("follower",), follower_value, "follower")
        if cam is not None and cam == follower:
            self.report.add(path + ("follower",), f'cam and follower are both link "{cam}"; expected two links')
            return None
        circle = None if profile_value is None else self.read_profile(path + ("profile",), profile_value)
        contact = table.get("contact", "outside")
        if contact not in ("outside", "inside"):
            self.report.add(path + ("contact",), f'expected "outside" or "inside", got {show_value(contact)}')
            return None
        kinds = [key for key in _FOLLOWERS if key in table]
        if len(kinds) != 1:
            self.report.add(path, f"{'no follower' if not kinds else 'more than one follower: ' + ', '.join(kinds)}; "
                            'expected one of roller = { center = "W", radius = r }, flat = { through = [x, y], '
                            'angle = a }, knife = "W", follower_profile = { circle = { center = "C", radius = r } } '
                            'or follower_profile = { points = [[x, y], ...] }')
            return None
        if cam is None or follower is None or circle is None:
            return None
        name_value = table.get("name")
        name = (read_name(self.report, path + ("name",), name_value, "a pair name", "23") if name_value is not None
                else pair_name(cam, follower))
        if name is None:
            return None
        base = CamSpec(name, cam, follower, circle[0], circle[1], "knife", inside=contact == "inside",
                       line=self.report.line(path), profile_points=circle[2])
        kind = kinds[0]
        key = path + (kind,)
        if kind == "knife":
            point = self._follower_point(key, table["knife"], follower)
            return None if point is None else _with(base, kind="knife", point=point)
        own_table = table[kind] if kind == "follower_profile" else None
        if isinstance(own_table, dict) and "points" in own_table and "circle" not in own_table:
            check_keys(self.report, key, own_table, ("circle", "points"))
            return self._follower_points(key, own_table["points"], base)
        if kind in ("roller", "follower_profile"):
            own = kind == "follower_profile"
            circle_table = self._follower_circle(key, table[kind]) if own else table[kind]
            if circle_table is None:
                return None
            key = key + ("circle",) if own else key
            what = "the follower's circle" if own else "roller"
            roller = read_table(self.report, key, circle_table, '{ center = "W", radius = r }')
            if roller is None:
                return None
            check_keys(self.report, key, roller, _ROLLER_KEYS)
            center = require(self.report, key, roller, "center",
                             'center = "C", the point of the follower at its circle\'s centre' if own
                             else 'center = "W", the roller\'s pin on the follower')
            radius = require(self.report, key, roller, "radius",
                             "radius = r, the follower's circle's radius" if own else "radius = r, the roller's radius")
            if center is None or radius is None:
                return None
            point = self._follower_point(key + ("center",), center, follower)
            r = self._positive(key + ("radius",), radius)
            if point is None or r is None:
                return None
            if base.inside and not base.is_spline and not r < base.radius:
                self.report.add(key + ("radius",), f"{'a circle' if own else 'a roller'} of radius {r:g} inside a "
                                f"groove of radius {base.radius:g}; expected {what} smaller than the profile")
                return None
            return _with(base, kind="roller", point=point, roller_radius=r, follower_profile=own)
        if base.inside:
            self.report.add(path + ("contact",), 'a flat face cannot touch a disc from inside; expected "outside"')
            return None
        found = self._line(key, table["flat"])
        return None if found is None else _with(base, kind="flat", flat=found)

    def _follower_circle(self, path: KeyPath, value: object) -> object | None:
        """The ``circle`` table of a ``follower_profile`` (None for a ``points`` one, read apart)."""
        table = read_table(self.report, path, value,
                           '{ circle = { center = "C", radius = r } } or { points = [[x, y], ...] }')
        if table is None:
            return None
        check_keys(self.report, path, table, ("circle", "points"))
        if "points" in table and "circle" in table:
            self.report.add(path, "a follower profile is a circle or points; expected one of them")
            return None
        return require(self.report, path, table, "circle",
                       'circle = { center = "C", radius = r }, C a point of the follower')

    def _follower_points(self, path: KeyPath, value: object, base: CamSpec) -> CamSpec | None:
        """A ``follower_profile = { points = [...] }``: a closed spline in the follower's frame, touching a
        ``points`` cam from outside."""
        points = read_profile_points(self.report, path + ("points",), value, self.kinds.length)
        if points is None:
            return None
        if not base.is_spline:
            self.report.add(path + ("points",), "a follower profile of points touches a cam profile of points; "
                            'expected profile = { points = [...] } on the cam, or follower_profile = { circle = '
                            '{ center = "C", radius = r } } for a circle cam')
            return None
        if base.inside:
            self.report.add(path[:-1] + ("contact",), 'two profiles of points touch from outside only; expected '
                            'contact = "outside"')
            return None
        return _with(base, kind="knife", point=None, follower_points=points)

    def read_profile(self, path: KeyPath, value: object) -> tuple[Vector, float, tuple[Vector, ...]] | None:
        """A circle's (centre, radius, ()), or a ``points`` profile's ((0, 0), 0, points)."""
        table = read_table(self.report, path, value, "{ circle = { center = [x, y], radius = R } }")
        if table is None:
            return None
        check_keys(self.report, path, table, _PROFILE_KEYS)
        if "points" in table:
            if "circle" in table:
                self.report.add(path, "a profile is a circle or points; expected one of them")
                return None
            points = read_profile_points(self.report, path + ("points",), table["points"], self.kinds.length)
            if points is None:
                return None
            return ((0.0, 0.0), 0.0, points)
        circle_value = require(self.report, path, table, "circle", "circle = { center = [x, y], radius = R }")
        circle = None if circle_value is None else read_table(self.report, path + ("circle",), circle_value,
                                                                "{ center = [x, y], radius = R }")
        if circle is None:
            return None
        check_keys(self.report, path + ("circle",), circle, _CIRCLE_KEYS)
        center_value = require(self.report, path + ("circle",), circle, "center",
                               "center = [x, y] or { polar = [r, angle] }, in the cam's frame")
        radius_value = require(self.report, path + ("circle",), circle, "radius", "radius = R")
        if center_value is None or radius_value is None:
            return None
        center, _ = self.read_point_value(path + ("circle", "center"), center_value)
        radius = self._positive(path + ("circle", "radius"), radius_value)
        return None if center is None or radius is None else (center, radius, ())

    def _follower_point(self, path: KeyPath, value: object, follower: str) -> str | None:
        name = read_name(self.report, path, value, "a point name", "W")
        if name is not None and self.links is not None and follower in self.links:
            known = self.links[follower].point_names
            if name not in known:
                self.report.add(path, lambda: f'no point "{name}" in link "{follower}" (the follower); '
                                              f'{suggest(name, known)}')
                return None
        return name


def _with(base: CamSpec, **changes: object) -> CamSpec:
    return replace(base, **changes)
