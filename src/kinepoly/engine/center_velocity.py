"""Angular velocities from instant centers: omega_1j = omega_1i (I_1i I_ij)/(I_1j I_ij), with its sense.

I_ij is a point of link i and of link j with one velocity v. As a point of link i it moves with
i's known motion; as a point of link j, which turns about I_1j, it moves at omega_1j x (I_ij - I_1j).
So omega_1j = ((I_ij - I_1j) x v) / |I_ij - I_1j|^2. When link i turns about I_1i this is the
textbook ratio of signed distances along the Kennedy line of links 1, i and j (the three centers
lie on it), and its sign is the sense: the same as omega_1i when I_1i and I_1j lie on the same
side of I_ij.

Centers at infinity: I_1j at infinity means link j translates (omega_1j = 0) with the velocity v;
I_ij at infinity means links i and j turn alike (omega_1j = omega_1i). Starting from the input
link, every link whose centers I_1j and I_ij (for a link i already known) were found gets its
omega. Nothing here reads the polygons: it is a third, independent check of them. Only inputs on
the frame start the chain: a motor or a cylinder between moving links gives a relative motion alone.
"""

from __future__ import annotations

from kinepoly.engine.center_values import CenterOmega, How, InstantCenter, Motion
from kinepoly.engine.circle_diagram import Edge, edge, pair_name
from kinepoly.geom.tolerances import COINCIDENT_SIN
from kinepoly.geom.vec import Vec, cross, dot, norm, rotate, scale, sub, unit
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import Pose
from kinepoly.scene.spec import LinkInput

__all__ = ["CenterOmega", "Motion", "omegas_from_centers"]


def _input_motions(mechanism: Mechanism, pose: Pose) -> list[tuple[str, Motion]]:
    """The motion each input on the frame gives its link (an input between two moving links gives only a
    relative motion: the chain of ratios cannot start there)."""
    ground = mechanism.ground
    assert ground is not None
    out = []
    for drive in mechanism.drives:
        inp = drive.spec
        if not drive.on_frame:
            continue
        if isinstance(inp, LinkInput):
            at = pose.links[ground].world(mechanism.local(ground, mechanism.input_pivot(inp).point))
            out.append((inp.link, Motion(inp.omega, at, (0.0, 0.0), pair_name((ground, inp.link)))))
        else:
            slider = mechanism.slider(inp.slider)
            e = rotate((1.0, 0.0), pose.links[slider.guide].theta + slider.angle_rad)
            moving = slider.block if slider.guide == ground else slider.guide
            v = scale(inp.s_dot if moving == slider.block else -inp.s_dot, e)
            out.append((moving, Motion(0.0, (0.0, 0.0), v)))
    return out


class _Omegas:
    def __init__(self, mechanism: Mechanism, centers: dict[Edge, InstantCenter], size: float) -> None:
        self.mechanism, self.centers, self.size = mechanism, centers, size
        self.links = mechanism.link_names
        self.ground = mechanism.ground or ""

    def omega_name(self, link: str) -> str:
        return f"omega{pair_name((self.ground, link))}"

    def center(self, a: str, b: str) -> InstantCenter | None:
        return self.centers.get(edge(a, b, self.links))

    def option(self, j: str, i: str, motion: Motion) -> tuple[tuple[int, float], CenterOmega] | None:
        b, c = self.center(self.ground, j), self.center(i, j)
        if b is None or c is None:
            return None
        wj, wi = self.omega_name(j), self.omega_name(i)
        names = (b.name, c.name)
        if c.position is None:
            if b.position is None:
                return None
            new = Motion(motion.omega, b.position, (0.0, 0.0), b.name)
            return (0, 0.0), CenterOmega(j, wj, motion.omega, i, names, f"{wj} = {wi} ({c.label} at infinity)",
                                         "same", (("given", motion.omega),), new)
        v = motion.velocity_of(c.position)
        if b.position is None:
            new = Motion(0.0, c.position, v)
            return (0, 0.0), CenterOmega(j, wj, 0.0, i, names, f"{wj} = 0 ({b.label} at infinity)", "translating",
                                         (("vx", v[0]), ("vy", v[1])), new)
        r = sub(c.position, b.position)
        length = norm(r)
        if length <= COINCIDENT_SIN * self.size:
            return None
        omega = cross(r, v) / (length * length)
        new = Motion(omega, b.position, (0.0, 0.0), b.name)
        return (1, self.size / length), CenterOmega(j, wj, omega, i, names, *self.how(j, i, motion, b, c, v), new)

    def how(self, j: str, i: str, motion: Motion, b: InstantCenter, c: InstantCenter,
            v: Vec) -> tuple[str, How, tuple[tuple[str, float], ...]]:
        """The equation, the way and the numbers of omega_1j when I_1j and I_ij are both finite."""
        wj, wi = self.omega_name(j), self.omega_name(i)
        assert b.position is not None and c.position is not None
        a = self.center(self.ground, i)
        r = sub(c.position, b.position)
        if motion.about is not None and a is not None and a.position is not None and motion.about == a.name:
            u = unit(r)
            near, far = dot(sub(c.position, a.position), u), norm(r)
            return (f"{wj} = {wi} ({a.label} {c.label})/({b.label} {c.label})", "ratio",
                    (("given", motion.omega), ("near", near), ("far", far)))
        return (f"{wj} = ({b.label}{c.label} x v_{c.label}) / |{b.label}{c.label}|^2", "velocity",
                (("vx", v[0]), ("vy", v[1]), ("rx", r[0]), ("ry", r[1]), ("cross", cross(r, v)), ("distance", norm(r))))


def omegas_from_centers(mechanism: Mechanism, pose: Pose, centers: dict[Edge, InstantCenter],
                        size: float) -> tuple[CenterOmega, ...]:
    """omega_1j of every link the centers reach from the input, in the order they are reached.

    ``size`` is the mechanism's size (lengths): two centers closer than COINCIDENT_SIN times it
    are one point and give no ratio.
    """
    if mechanism.ground is None:
        return ()
    starts = _input_motions(mechanism, pose)
    if not starts:
        return ()
    finder = _Omegas(mechanism, centers, size)
    motions: dict[str, Motion] = dict(starts)
    out: list[CenterOmega] = []
    while True:
        found: list[CenterOmega] = []
        for j in mechanism.link_names:
            if j == mechanism.ground or j in motions:
                continue
            options = [option for i, m in motions.items() if (option := finder.option(j, i, m)) is not None]
            if options:
                found.append(min(options, key=lambda o: o[0])[1])
        if not found:
            return tuple(out)
        for result in found:
            motions[result.link] = result.motion
            out.append(result)
