"""The loop equations differentiated once and twice, and solved for the unknown rates.

For a link's vector r e^{i theta} the first derivative is i omega r e^{i theta} and the second
(i alpha - omega^2) r e^{i theta}; for a slider's s e^{i theta} they are s_dot e^{i theta} + i omega s e^{i theta}
and s_ddot e^{i theta} + 2 i omega s_dot e^{i theta} (the Coriolis term) + (i alpha - omega^2) s e^{i theta}.
Each loop gives two real equations (its real and imaginary parts), linear in the unknown rates, with the
same coefficients for the velocities and the accelerations. They are solved block by block: an input's
equation gives its rate; a loop left with two unknowns by Cramer's rule; loops that share more unknowns
than any one of them can give (a triad's) as one coupled system.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping

import numpy as np
from msgspec import Struct

from kinepoly.errors import SingularityError
from kinepoly.geom.tolerances import LOOP_SINGULAR_DET
from kinepoly.loops.contours import Loop, Term, choose_loops, class_name, spanning_tree
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.model.pose import Pose
from kinepoly.scene.spec import LinkInput

__all__ = ["Block", "Equation", "LoopSolution", "solve_loops"]

_SINGULAR = LOOP_SINGULAR_DET


class Equation(Struct, frozen=True):
    """sum of coefficient * unknown = rhs: one real equation (a loop's real or imaginary part, or an input)."""

    source: str
    coefficients: dict[str, float]
    rhs: float


class Block(Struct, frozen=True):
    """Unknowns found together: ``kind`` is "input", "cramer" (one loop, 2x2) or "coupled" (several loops)."""

    kind: str
    loops: tuple[int, ...]
    unknowns: tuple[str, ...]
    matrix: tuple[tuple[float, ...], ...]
    rhs: tuple[float, ...]
    values: tuple[float, ...]
    inputs: int = 0
    """How many of its equations are inputs' (a motor between moving links: the difference of two rates)."""


class LoopSolution(Struct, frozen=True):
    """Every rate from the loop equations at one position: omega, alpha by link; s, s_dot, s_ddot by slider."""

    mechanism: Mechanism
    pose: Pose
    loops: tuple[Loop, ...]
    names: dict[str, str]
    """Each link's rotation class named by the link whose theta_1k the equations use."""
    omega: dict[str, float]
    alpha: dict[str, float] | None
    s: dict[str, float]
    s_dot: dict[str, float]
    s_ddot: dict[str, float] | None
    velocity_blocks: tuple[Block, ...]
    acceleration_blocks: tuple[Block, ...]
    velocity_constants: dict[int, complex]
    acceleration_constants: dict[int, complex]
    anchors: dict[str, tuple[complex, complex, complex]]
    """Each link's point with known motion: (where, velocity, acceleration)."""

    def coriolis(self, slider: str) -> complex:
        """2 i omega_guide s_dot e^{i theta}: the Coriolis term of the block on its guide."""
        spec = self.mechanism.slider(slider)
        unit = _unit(self.pose, spec.guide, spec.angle_rad)
        return 2j * self.omega[spec.guide] * self.s_dot[slider] * unit

    def velocity(self, link: str, at: complex) -> complex:
        where, v, _ = self.anchors[link]
        return v + 1j * self.omega[link] * (at - where)

    def acceleration(self, link: str, at: complex) -> complex:
        assert self.alpha is not None
        where, _, a = self.anchors[link]
        w, al = self.omega[link], self.alpha[link]
        return a + (1j * al - w * w) * (at - where)


def _unit(pose: Pose, guide: str, angle: float) -> complex:
    return complex(np.exp(1j * (pose.links[guide].theta + angle)))


def omega_name(name: str, ground: str) -> str:
    return f"omega_{ground}{name}"


def _jacobian(term: Term, names: Mapping[str, str], ground: str) -> dict[str, complex]:
    """The coefficient of each unknown rate in the term's derivative (the same for velocities and accelerations)."""
    out: dict[str, complex] = {}
    link = names[term.link]
    if term.slider is not None:
        out[f"s_{term.slider}"] = term.sign * term.unit
    if link != ground:
        out[link] = term.sign * 1j * term.length * term.unit
    return out


def _equations(loops: tuple[Loop, ...], names: Mapping[str, str], ground: str,
               constant: Mapping[int, complex]) -> list[Equation]:
    out = []
    for loop in loops:
        coeff: dict[str, complex] = {}
        for term in loop.terms:
            for key, c in _jacobian(term, names, ground).items():
                coeff[key] = coeff.get(key, 0j) + c
        c0 = constant.get(loop.number, 0j)
        out.append(Equation(f"{loop.number}.re", {k: v.real for k, v in coeff.items()}, -c0.real))
        out.append(Equation(f"{loop.number}.im", {k: v.imag for k, v in coeff.items()}, -c0.imag))
    return out


def _input_equations(mechanism: Mechanism, names: Mapping[str, str], order: int) -> list[Equation]:
    ground = mechanism.ground
    out = []
    for drive in mechanism.drives:
        if isinstance(drive.spec, LinkInput):
            coeff = {names[drive.moving]: 1.0}
            if names[drive.base] != ground:
                coeff[names[drive.base]] = coeff.get(names[drive.base], 0.0) - 1.0
        else:
            coeff = {f"s_{drive.spec.slider}": 1.0}
        out.append(Equation(f"input.{drive.index + 1}", {k: v for k, v in coeff.items() if k != ground},
                            drive.rate(order)))
    return out


def _solve_blocks(equations: list[Equation], unknowns: list[str]) -> tuple[dict[str, float], tuple[Block, ...]]:
    known: dict[str, float] = {}
    left = list(equations)
    blocks: list[Block] = []

    def open_of(eq: Equation) -> list[str]:
        return [k for k, c in eq.coefficients.items() if k not in known and c != 0.0]

    def take(kind: str, eqs: list[Equation], names: list[str]) -> None:
        a = np.array([[eq.coefficients.get(n, 0.0) for n in names] for eq in eqs])
        b = np.array([eq.rhs - sum(c * known[k] for k, c in eq.coefficients.items() if k in known) for eq in eqs])
        scale = float(np.max(np.abs(a))) if a.size else 0.0
        if a.shape[0] != a.shape[1] or scale == 0.0 or abs(np.linalg.det(a / scale)) < _SINGULAR:
            raise SingularityError(f"the loop equations for {', '.join(names)} are singular at this position "
                                   "(their determinant is zero): the mechanism is at a dead point")
        x = np.linalg.solve(a, b)
        known.update({n: float(v) for n, v in zip(names, x, strict=True)})
        loops = tuple(dict.fromkeys(int(eq.source.split(".")[0]) for eq in eqs if not eq.source.startswith("input")))
        blocks.append(Block(kind, loops, tuple(names), tuple(tuple(float(c) for c in row) for row in a),
                            tuple(float(v) for v in b), tuple(float(v) for v in x),
                            sum(1 for eq in eqs if eq.source.startswith("input"))))
        for eq in eqs:
            left.remove(eq)

    while left:
        inputs = [eq for eq in left if eq.source.startswith("input") and len(open_of(eq)) == 1]
        if inputs:
            take("input", [inputs[0]], open_of(inputs[0]))
            continue
        pairs = [(eq, other) for eq, other in itertools.pairwise(left)
                 if eq.source.endswith(".re") and other.source == eq.source.replace(".re", ".im")]
        ready = [(re, im) for re, im in pairs if len(set(open_of(re)) | set(open_of(im))) == 2]
        if ready:
            re, im = ready[0]
            take("cramer", [re, im], list(dict.fromkeys(open_of(re) + open_of(im))))
            continue
        settled = [eq for eq in left if not open_of(eq)]
        for eq in settled:
            left.remove(eq)
        if settled:
            continue
        rest = [u for u in unknowns if u not in known]
        take("coupled", list(left), rest)
    return known, tuple(blocks)


def _constants(loops: tuple[Loop, ...], names: Mapping[str, str], ground: str, omega: Mapping[str, float],
               s_dot: Mapping[str, float]) -> dict[int, complex]:
    """Each loop's second derivative without its unknown accelerations: the normal and Coriolis terms."""
    out = {}
    for loop in loops:
        total = 0j
        for term in loop.terms:
            w = 0.0 if names[term.link] == ground else omega[names[term.link]]
            total += term.sign * (-w * w) * term.length * term.unit
            if term.slider is not None:
                total += term.sign * 2j * w * s_dot[term.slider] * term.unit
        out[loop.number] = total
    return out


def solve_loops(mechanism: Mechanism, pose: Pose, *, with_acceleration: bool = True) -> LoopSolution:
    """Choose the loops at ``pose`` (every link placed), and solve their velocity and acceleration equations."""
    ground = mechanism.ground
    assert ground is not None
    loops = choose_loops(mechanism, pose)
    names = {link: class_name(mechanism, link) for link in mechanism.link_names}
    unknowns = list(dict.fromkeys(n for n in names.values() if n != ground))
    unknowns += [f"s_{s.name}" for s in mechanism.sliders]
    v_known, v_blocks = _solve_blocks(_equations(loops, names, ground, {}) + _input_equations(mechanism, names, 1),
                                      unknowns)
    omega = {link: (0.0 if names[link] == ground else v_known[names[link]]) for link in mechanism.link_names}
    s_dot = {s.name: v_known[f"s_{s.name}"] for s in mechanism.sliders}
    s = {t.slider: t.length for loop in loops for t in loop.terms if t.slider is not None}
    s.update({spec.name: _s_of(mechanism, pose, spec.name) for spec in mechanism.sliders if spec.name not in s})
    alpha = s_ddot = None
    a_blocks: tuple[Block, ...] = ()
    a_const: dict[int, complex] = {}
    if with_acceleration:
        a_const = _constants(loops, names, ground, {names[k]: w for k, w in omega.items()}, s_dot)
        a_known, a_blocks = _solve_blocks(_equations(loops, names, ground, a_const)
                                          + _input_equations(mechanism, names, 2), unknowns)
        alpha = {link: (0.0 if names[link] == ground else a_known[names[link]]) for link in mechanism.link_names}
        s_ddot = {spec.name: a_known[f"s_{spec.name}"] for spec in mechanism.sliders}
    anchors = _anchors(mechanism, pose, omega, alpha, s_dot, s_ddot)
    return LoopSolution(mechanism, pose, loops, names, omega, alpha, s, s_dot, s_ddot, v_blocks, a_blocks,
                        {loop.number: 0j for loop in loops}, a_const, anchors)


def _s_of(mechanism: Mechanism, pose: Pose, name: str) -> float:
    spec = mechanism.slider(name)
    unit = _unit(pose, spec.guide, spec.angle_rad)
    t = complex(*pose.world(spec.through, spec.guide))
    p = complex(*pose.world(mechanism.local(spec.block, spec.point), spec.block))
    return float(((p - t) * unit.conjugate()).real)


def _anchors(mechanism: Mechanism, pose: Pose, omega: Mapping[str, float], alpha: Mapping[str, float] | None,
             s_dot: Mapping[str, float],
             s_ddot: Mapping[str, float] | None) -> dict[str, tuple[complex, complex, complex]]:
    """Each link's point of known motion, down the spanning tree from the frame: the position loop's
    vectors from the frame to that point, differentiated."""
    parent, _ = spanning_tree(mechanism)
    ground = mechanism.ground
    assert ground is not None
    out: dict[str, tuple[complex, complex, complex]] = {ground: (0j, 0j, 0j)}

    def at(link: str, where: complex) -> tuple[complex, complex]:
        origin, v, a = out[link]
        w, al = omega[link], (alpha[link] if alpha is not None else 0.0)
        return v + 1j * w * (where - origin), a + (1j * al - w * w) * (where - origin)

    order = sorted((k for k in parent if k != ground), key=lambda k: _depth(parent, k))
    for link in order:
        up = parent[link]
        assert up is not None
        base, joint = up
        if isinstance(joint, Revolute):
            q = complex(*pose.world(mechanism.local(link, joint.point), link))
            v, a = at(base, q)
            out[link] = (q, v, a)
            continue
        p = complex(*pose.world(mechanism.local(joint.block, joint.point), joint.block))
        unit = _unit(pose, joint.guide, joint.angle_rad)
        v, a = at(base, p)
        sd, sdd = s_dot[joint.name], (s_ddot[joint.name] if s_ddot is not None else 0.0)
        rel_v, rel_a = sd * unit, sdd * unit + 2j * omega[joint.guide] * sd * unit
        sign = 1 if link == joint.block else -1
        out[link] = (p, v + sign * rel_v, a + sign * rel_a)
    return out


def _depth(parent: Mapping[str, tuple[str, object] | None], link: str) -> int:
    depth, up = 0, parent[link]
    while up is not None:
        depth, up = depth + 1, parent[up[0]]
    return depth
