"""The loop method's derivation as text, in the texts' notation (θ_13, ω_13, ṡ_43, a^c), from a catalogue."""

from __future__ import annotations

import math

from kinepoly.geom.tolerances import ANGLE_SAME_RAD, ROUNDING_REL
from kinepoly.loops.contours import Loop, Term
from kinepoly.loops.rates import Block, LoopSolution
from kinepoly.present.catalogue import Catalogue
from kinepoly.present.phrasing import english
from kinepoly.scene.spec import LinkInput

__all__ = ["block_lines", "constant_line", "count_line", "derivation_lines", "loop_equation", "loop_lines",
           "loop_unknowns", "variable"]


def variable(loops: LoopSolution, key: str, order: int) -> str:
    """The name of an unknown: θ_13, ω_13, α_13 of a link's rotation; s_43, ṡ_43, s̈_43 of a slider."""
    ground = loops.mechanism.ground
    if key.startswith("s_"):
        return ("s_", "ṡ_", "s̈_")[order] + key[2:]
    return ("θ_", "ω_", "α_")[order] + f"{ground}{key}"


def _inputs(loops: LoopSolution) -> set[str]:
    out = set()
    for drive in loops.mechanism.drives:
        out.add(f"s_{drive.spec.slider}" if not isinstance(drive.spec, LinkInput) else loops.names[drive.moving])
    return out


def _keys(loops: LoopSolution, term: Term) -> list[str]:
    out = [] if loops.names[term.link] == loops.mechanism.ground else [loops.names[term.link]]
    return out + ([f"s_{term.slider}"] if term.slider is not None else [])


def loop_unknowns(loops: LoopSolution, loop: Loop) -> list[str]:
    """The loop's position variables that no input gives (θ_13, s_14)."""
    given = _inputs(loops)
    keys = dict.fromkeys(k for term in loop.terms for k in _keys(loops, term))
    return [variable(loops, k, 0) for k in keys if k not in given]


def _flipped(term: Term) -> bool:
    """A moving link's vector at theta_1k ± 180° is written as minus the vector at theta_1k."""
    return term.slider is None and abs(abs(term.offset) - math.pi) < ANGLE_SAME_RAD


def _sign(loops: LoopSolution, term: Term) -> int:
    return -term.sign if _flipped(term) and loops.names[term.link] != loops.mechanism.ground else term.sign


def _exp(loops: LoopSolution, term: Term, cat: Catalogue) -> str:
    if loops.names[term.link] == loops.mechanism.ground:
        angle = cat.angle(term.angle)
        return f"e^{{i({angle})}}" if angle.startswith("−") else f"e^{{i {angle}}}"
    theta = variable(loops, loops.names[term.link], 0)
    if abs(term.offset) < ROUNDING_REL or _flipped(term):
        return f"e^{{i {theta}}}"
    sign = "+" if term.offset > 0 else "−"
    return f"e^{{i({theta} {sign} {cat.number(abs(math.degrees(term.offset)))}°)}}"


def _join(parts: list[tuple[int, str]]) -> str:
    out = ""
    for sign, text in parts:
        if not out:
            out = text if sign > 0 else f"−{text}"
        else:
            out += (" + " if sign > 0 else " − ") + text
    return out or "0"


def loop_equation(loops: LoopSolution, loop: Loop, cat: Catalogue | None = None) -> str:
    """The position equation: the sum of the loop's vectors is zero, with the scene's lengths."""
    cat = cat or english()
    parts = []
    for term in loop.terms:
        size = variable(loops, f"s_{term.slider}", 0) if term.slider is not None else cat.number(term.length)
        parts.append((_sign(loops, term), f"{size} {_exp(loops, term, cat)}"))
    return _join(parts) + " = 0"


def _velocity_equation(loops: LoopSolution, loop: Loop, cat: Catalogue) -> str:
    parts = []
    for term in loop.terms:
        e = _exp(loops, term, cat)
        moving = loops.names[term.link] != loops.mechanism.ground
        w = variable(loops, loops.names[term.link], 1)
        if term.slider is not None:
            s, sd = variable(loops, f"s_{term.slider}", 0), variable(loops, f"s_{term.slider}", 1)
            parts.append((_sign(loops, term), f"{sd} {e}"))
            if moving:
                parts.append((_sign(loops, term), f"i {w} {s} {e}"))
        elif moving:
            parts.append((_sign(loops, term), f"i {w} {cat.number(term.length)} {e}"))
    return _join(parts) + " = 0"


def _acceleration_equation(loops: LoopSolution, loop: Loop, cat: Catalogue) -> str:
    parts = []
    for term in loop.terms:
        e = _exp(loops, term, cat)
        moving = loops.names[term.link] != loops.mechanism.ground
        w, a = variable(loops, loops.names[term.link], 1), variable(loops, loops.names[term.link], 2)
        if term.slider is not None:
            key = f"s_{term.slider}"
            s, sd, sdd = (variable(loops, key, k) for k in range(3))
            parts.append((_sign(loops, term), f"{sdd} {e}"))
            if moving:
                parts.append((_sign(loops, term), f"2 i {w} {sd} {e}"))
                parts.append((_sign(loops, term), f"(i {a} − {w}²) {s} {e}"))
        elif moving:
            parts.append((_sign(loops, term), f"(i {a} − {w}²) {cat.number(term.length)} {e}"))
    return _join(parts) + " = 0"


def _knowns(loops: LoopSolution, loop: Loop, cat: Catalogue) -> str:
    seen: dict[str, str] = {}
    for term in loop.terms:
        for key in _keys(loops, term):
            if key.startswith("s_"):
                seen.setdefault(variable(loops, key, 0), cat.number(loops.s[key[2:]]))
            else:
                seen.setdefault(variable(loops, key, 0), cat.angle(loops.pose.links[key].theta))
    return ", ".join(f"{name} = {value}" for name, value in seen.items())


def _complex(cat: Catalogue, z: complex) -> str:
    sign = "+" if z.imag >= 0 else "−"
    return f"{cat.number(z.real)} {sign} {cat.number(abs(z.imag))} i"


def _block_lines(loops: LoopSolution, block: Block, order: int, cat: Catalogue) -> list[str]:
    names = [variable(loops, key, order) for key in block.unknowns]
    values = ", ".join(f"{n} = {cat.number(v)}" for n, v in zip(names, block.values, strict=True))
    if block.kind == "input":
        return [cat.say("loops.input", unknown=names[0], value=cat.number(block.values[0]))]
    scale = max((abs(c) for row in block.matrix for c in row), default=0.0)
    matrix = tuple(tuple(0.0 if abs(c) <= ROUNDING_REL * scale else c for c in row) for row in block.matrix)
    rows = []
    for row, rhs in zip(matrix, block.rhs, strict=True):
        left = " ".join(f"{'+' if c >= 0 else '−'} {cat.number(abs(c))} {n}" for c, n in zip(row, names, strict=True))
        left = left.removeprefix("+ ") if left.startswith("+") else "−" + left.removeprefix("− ")
        rows.append(f"    {left} = {cat.number(rhs)}")
    if block.kind == "coupled":
        key = "loops.coupled_input" if block.inputs and len(block.loops) == 1 else "loops.coupled"
        head = cat.say(key, loops=", ".join(str(k) for k in block.loops) or "-",
                       size=str(len(names)), unknowns=", ".join(names))
        return [head, *rows, "    " + values]
    (a11, a12), (a21, a22) = matrix
    b1, b2 = block.rhs
    det = a11 * a22 - a12 * a21
    def times(x: float, y: float) -> str:
        return "·".join(f"({cat.number(v)})" if v < 0 and cat.number(v) != "0" else cat.number(v) for v in (x, y))

    delta = cat.say("loops.determinant", expression=f"{times(a11, a22)} − {times(a12, a21)}", value=cat.number(det))
    first = cat.say("loops.cramer", unknown=names[0], numerator=f"({times(b1, a22)} − {times(a12, b2)})",
                    determinant=cat.number(det), value=cat.number(block.values[0]))
    second = cat.say("loops.cramer", unknown=names[1], numerator=f"({times(a11, b2)} − {times(b1, a21)})",
                     determinant=cat.number(det), value=cat.number(block.values[1]))
    return [cat.say("loops.parts", loop=str(block.loops[0]), unknowns=", ".join(names)), *rows,
            "    " + delta, "    " + first, "    " + second]


def count_line(loops: LoopSolution, cat: Catalogue) -> str:
    """N = j - n + 1 and why the loops chosen are independent."""
    mech = loops.mechanism
    return cat.say("loops.count", j=str(len(mech.joints)), n=str(len(mech.link_names)), count=str(len(loops.loops)),
                   joints=", ".join(loop.closing for loop in loops.loops))


def loop_lines(loops: LoopSolution, loop: Loop, cat: Catalogue) -> list[str]:
    """One loop: its links, its position equation and values, its first and second derivatives."""
    out = [cat.say("loops.loop", number=str(loop.number), members=" → ".join(loop.members), joint=loop.closing),
           cat.say("loops.position", equation=loop_equation(loops, loop, cat)),
           cat.say("loops.known", values=_knowns(loops, loop, cat), closure=_complex(cat, loop.closure())),
           cat.say("loops.velocity", equation=_velocity_equation(loops, loop, cat))]
    if loops.alpha is not None:
        out.append(cat.say("loops.acceleration", equation=_acceleration_equation(loops, loop, cat)))
        if any(t.slider is not None and loops.names[t.link] != loops.mechanism.ground for t in loop.terms):
            out.append(cat.say("loops.coriolis"))
    return out


def block_lines(loops: LoopSolution, block: Block, order: int, cat: Catalogue) -> list[str]:
    """One block of unknowns: the input's value, a loop's 2x2 system and Cramer's rule, or a coupled system."""
    return _block_lines(loops, block, order, cat)


def constant_line(loops: LoopSolution, number: int, cat: Catalogue) -> str:
    return cat.say("loops.constant", loop=str(number), value=_complex(cat, loops.acceleration_constants[number]))


def derivation_lines(loops: LoopSolution, cat: Catalogue | None = None) -> list[str]:
    """The whole derivation: the loops counted and chosen, each one's equations, the systems and their solutions."""
    cat = cat or english()
    out = [cat.say("loops.title"), "", count_line(loops, cat)]
    for loop in loops.loops:
        head, *rest = loop_lines(loops, loop, cat)
        out += ["", head, *("    " + line for line in rest)]
    out += ["", cat.say("loops.velocities")]
    for block in loops.velocity_blocks:
        out += _block_lines(loops, block, 1, cat)
    if loops.alpha is not None:
        out += ["", cat.say("loops.accelerations")]
        for number in loops.acceleration_constants:
            out.append("    " + constant_line(loops, number, cat))
        for block in loops.acceleration_blocks:
            out += _block_lines(loops, block, 2, cat)
    return out
