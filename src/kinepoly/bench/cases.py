"""Scenes of the standard mechanisms for the stability suite and the calibration of the estimates.

Each builder writes a scene as a user would (TOML through the loader) and can put it far from
the origin (``at``); the texts of the four-bar, the slider-crank and the slotted lever
(``*_text``) are the tests' random mechanisms too. ``scaled`` and ``translated`` change any
scene's lengths, speeds and place. ``random_case`` draws one case of every kind the estimates
were calibrated on: ordinary poses and inputs from 1e-1 to 1e-8 rad short of a dead point, for
four-bars (crank driven, and driven at the limit of a rocking input), slider-cranks (crank and
piston driven) and slotted levers (with the slide reversing).
"""

from __future__ import annotations

import math
import random

from msgspec import Struct
from msgspec.structs import replace

from kinepoly.scene.loader import loads_scene
from kinepoly.scene.spec import InputSpec, LinkInput, Scene, SliderInput

__all__ = ["Case", "four_bar", "four_bar_limit", "four_bar_text", "piston", "random_case", "scaled", "slider_crank",
           "slider_crank_text", "slotted_lever", "slotted_lever_reversal", "slotted_lever_text", "translated"]

FIND_ALL = """[find]
velocity = [{v}]
acceleration = [{a}]
omega = [{w}]
alpha = [{w}]
"""


def _find(velocity: list[str], acceleration: list[str], links: list[str], extra: str = "") -> str:
    quote = ", ".join
    return FIND_ALL.format(v=quote(f'"{p}"' for p in velocity), a=quote(f'"{p}"' for p in acceleration),
                           w=quote(f'"{k}"' for k in links)) + extra


def _xy(x: float, y: float, at: tuple[float, float]) -> str:
    if at == (0.0, 0.0):
        return f"[{x!r}, {y!r}]"  # as given: [0, 0] stays [0, 0]
    return f"[{x + at[0]!r}, {y + at[1]!r}]"


class Case(Struct, frozen=True):
    """A scene and what it is: its kind, and how far its input is from a dead point (rad; None: ordinary)."""

    kind: str
    scene: Scene
    distance: float | None = None


# --------------------------------------------------------------------------------------------
# The scene texts (the tests write their random mechanisms with these too)


def _text(title: str, links: tuple[str, ...], middle: str, guess: str, find: str, units: str = "") -> str:
    """A scene: links 1, 2, ... with these point tables, then ``middle`` (sliders, input), the guess, the find."""
    tables = "".join(f"{n} = {{ points = {{ {points} }} }}\n" for n, points in enumerate(links, 1))
    return f'\ntitle = "{title}"\n{units}[links]\n{tables}{middle}[guess]\n{guess}\n{find}\n'


def _crank_input(angle: float, omega: float, alpha: float) -> str:
    return f'[input]\nlink = "2"\nangle = {angle!r}\nomega = {omega!r}\nalpha = {alpha!r}\n'


def _slider(block: str, guide: str, point: str, through: str, angle: int) -> str:
    return (f'[[sliders]]\nblock = "{block}"\nguide = "{guide}"\npoint = "{point}"\n'
            f"line = {{ through = {through}, angle = {angle} }}\n")


def four_bar_text(a1: float, a2: float, a3: float, a4: float, angle: float, omega: float, alpha: float,
                  guess_b: tuple[float, float], *, coupler: tuple[float, float] = (60.0, 30.0),
                  title: str = "four-bar", angle_unit: str | None = None, at: tuple[float, float] = (0.0, 0.0),
                  find: str = "") -> str:
    """Frame A0 B0 = a1 on the x-axis, crank a2 at ``angle``, coupler a3 with C at ``coupler`` (polar), rocker a4."""
    links = (f"A0 = {_xy(0, 0, at)}, B0 = {_xy(a1, 0, at)}", f"A0 = [0, 0], A = [{a2!r}, 0]",
             f"A = [0, 0], B = [{a3!r}, 0], C = {{ polar = [{coupler[0]!r}, {coupler[1]!r}] }}",
             f"B0 = [0, 0], B = [{a4!r}, 0]")
    units = f'units = {{ angle = "{angle_unit}" }}\n' if angle_unit else ""
    return _text(title, links, _crank_input(angle, omega, alpha), f"B = {_xy(*guess_b, at)}", find, units)


def slider_crank_text(a2: float, a3: float, offset: float, theta_deg: float, omega: float, alpha: float,
                      guess_b: tuple[float, float], *, title: str = "slider-crank",
                      at: tuple[float, float] = (0.0, 0.0), find: str = "") -> str:
    """Crank a2 about A0, rod a3 (with C) to the block B on the line y = offset."""
    links = (f"A0 = {_xy(0, 0, at)}", f"A0 = [0, 0], A = [{a2!r}, 0]",
             f"B = [0, 0], A = [{a3!r}, 0], C = {{ polar = [{0.4 * a3!r}, -30] }}", "B = [0, 0]")
    middle = _slider("4", "1", "B", _xy(0, offset, at), 0) + _crank_input(theta_deg, omega, alpha)
    return _text(title, links, middle, f"B = {_xy(*guess_b, at)}", find)


def slotted_lever_text(a1: float, a2: float, offset: float, theta_deg: float, omega: float, alpha: float,
                       guess_f: tuple[float, float], *, title: str = "slotted lever",
                       at: tuple[float, float] = (0.0, 0.0), find: str = "") -> str:
    """Crank a2 about A0 carries block A in the slot of lever 4 about B0 (A0 B0 = a1); ``find`` adds to its [find]."""
    links = (f"A0 = {_xy(0, 0, at)}, B0 = {_xy(a1, 0, at)}", f"A0 = [0, 0], A = [{a2!r}, 0]", "A = [0, 0]",
             f"B0 = [0, 0], F = [{offset!r}, 0]")
    middle = _slider("3", "4", "A", f"[{offset!r}, 0]", 90) + _crank_input(theta_deg, omega, alpha)
    asked = _find(["A", "A@4"], ["A", "A@4"], ["4"], 'sliders = ["43"]')
    return _text(title, links, middle, f"F = {_xy(*guess_f, at)}", f"{asked}\n{find}")


# --------------------------------------------------------------------------------------------
# The scenes


def four_bar(a1: float, a2: float, a3: float, a4: float, theta_deg: float, omega: float = 10.0, alpha: float = 5.0,
             *, upper: bool = True, at: tuple[float, float] = (0.0, 0.0), angle_unit: str = "deg",
             centers: str = "") -> Scene:
    """Frame A0 B0 = a1 on the x-axis, crank a2, coupler a3 (with C), rocker a4; B above or below A B0."""
    t = math.radians(theta_deg)
    ax, ay = a2 * math.cos(t), a2 * math.sin(t)
    dx, dy = a1 - ax, -ay
    d = math.hypot(dx, dy)
    along = (d * d + a3 * a3 - a4 * a4) / (2 * d) if d > 0 else 0.0
    h = math.sqrt(max(a3 * a3 - along * along, 0.0)) * (1.0 if upper else -1.0)
    guess = (ax + (along * dx - h * dy) / d, ay + (along * dy + h * dx) / d)
    extra = f"instant_centers = [{centers}]\n" if centers else ""
    return loads_scene(four_bar_text(a1, a2, a3, a4, theta_deg if angle_unit == "deg" else t, omega, alpha, guess,
                                     coupler=(0.5 * a3, 30.0), angle_unit=angle_unit, at=at,
                                     find=_find(["A", "B", "C"], ["A", "B", "C"], ["3", "4"], extra)))


def four_bar_limit(a1: float, a2: float, a3: float, a4: float, distance: float, **kw: object) -> Scene | None:
    """A four-bar whose input link rocks: ``distance`` rad short of the limit where coupler and rocker line up."""
    cos_limit = (a2 * a2 + a1 * a1 - (a3 + a4) ** 2) / (2 * a1 * a2)
    if not -1.0 < cos_limit < 1.0:
        return None
    return four_bar(a1, a2, a3, a4, math.degrees(math.acos(cos_limit) - distance), **kw)  # type: ignore[arg-type]


def slider_crank(a2: float, a3: float, offset: float, theta_deg: float, omega: float = 10.0, alpha: float = 0.0,
                 *, ahead: bool = True, at: tuple[float, float] = (0.0, 0.0)) -> Scene:
    """Crank a2 about A0, rod a3 to the block B on the line y = offset (B ahead of or behind A)."""
    t = math.radians(theta_deg)
    ax, ay = a2 * math.cos(t), a2 * math.sin(t)
    run = math.sqrt(max(a3 * a3 - (offset - ay) ** 2, 0.0)) * (1.0 if ahead else -1.0)
    return loads_scene(slider_crank_text(a2, a3, offset, theta_deg, omega, alpha, (ax + run, offset), at=at,
                                         find=_find(["A", "B", "C"], ["A", "B", "C"], ["3"], 'sliders = ["14"]')))


def piston(a2: float, a3: float, distance: float, *, outer: bool = True, s_dot: float = -500.0,
           s_ddot: float = 100.0, upper: bool = True, at: tuple[float, float] = (0.0, 0.0)) -> Scene:
    """A slider-crank driven from the piston, the crank ``distance`` rad from a dead centre (outer: in line)."""
    phi = distance if outer else math.pi - distance
    s = a2 * math.cos(phi) + math.sqrt(a3 * a3 - (a2 * math.sin(phi)) ** 2)
    ay = a2 * math.sin(phi) * (1.0 if upper else -1.0)
    links = (f"A0 = {_xy(0, 0, at)}", f"A0 = [0, 0], A = [{a2!r}, 0]", f"B = [0, 0], A = [{a3!r}, 0]", "B = [0, 0]")
    middle = _slider("4", "1", "B", _xy(0, 0, at), 0) + f'[input]\nslider = "14"\ns = {s!r}\ns_dot = {s_dot!r}\n' \
        f"s_ddot = {s_ddot!r}\n"
    return loads_scene(_text("piston-driven slider-crank", links, middle, f"A = {_xy(a2 * math.cos(phi), ay, at)}",
                             _find(["A", "B"], ["A"], ["2", "3"])))


def slotted_lever(a1: float, a2: float, offset: float, theta_deg: float, omega: float = 10.0, alpha: float = 0.0,
                  *, at: tuple[float, float] = (0.0, 0.0)) -> Scene:
    """Crank a2 about A0 carries block A in the slot of lever 4 about B0 (A0 B0 = a1); slot offset ``offset``."""
    t = math.radians(theta_deg)
    ax, ay = a2 * math.cos(t), a2 * math.sin(t)
    rx, ry = ax - a1, ay
    rho = math.hypot(rx, ry)
    beta = math.atan2(ry, rx) + math.asin(max(-1.0, min(1.0, offset / rho)))  # the slot's direction, at A
    guess = (a1 + offset * math.cos(beta - math.pi / 2), offset * math.sin(beta - math.pi / 2))
    return loads_scene(slotted_lever_text(a1, a2, offset, theta_deg, omega, alpha, guess, at=at))


def slotted_lever_reversal(a1: float, a2: float, distance: float, **kw: object) -> Scene:
    """A slotted lever (slot through the pivot) ``distance`` rad from a slide reversal, where v_rel = 0.

    The block is nearest the lever's pivot when A0, A and B0 are in line (theta12 = 0): there it
    stops sliding and turns back, and the Coriolis term 2 omega x v_rel passes through zero.
    """
    return slotted_lever(a1, a2, 0.0, math.degrees(distance), **kw)  # type: ignore[arg-type]


def _log_uniform(rng: random.Random, low: float, high: float) -> float:
    return float(10.0 ** rng.uniform(math.log10(low), math.log10(high)))


def random_case(rng: random.Random) -> Case:
    """One random case: a standard mechanism, ordinary or 1e-1 to 1e-8 rad from a dead point."""
    kind = rng.choice(["four-bar", "four-bar limit", "slider-crank", "piston", "slotted lever", "reversal"])
    scale = _log_uniform(rng, 1e-3, 1e3)
    near = _log_uniform(rng, 1e-8, 1e-1)
    omega = rng.choice([-1.0, 1.0]) * _log_uniform(rng, 1e-2, 1e2)
    alpha = rng.uniform(-1.0, 1.0) * omega * omega
    if kind == "four-bar":
        a1, a3, a4 = (scale * rng.uniform(0.8, 1.2) for _ in range(3))
        a2 = scale * rng.uniform(0.1, 0.35)  # Grashof crank-rocker: the crank turns fully
        return Case(kind, four_bar(a1, a2, a3, a4, rng.uniform(0, 360), omega, alpha, upper=rng.random() < 0.5))
    if kind == "four-bar limit":
        while True:
            a1, a2, a3, a4 = (scale * rng.uniform(0.4, 1.2) for _ in range(4))
            found = four_bar_limit(a1, a2, a3, a4, near, omega=omega, alpha=alpha, upper=rng.random() < 0.5)
            if found is not None:
                return Case(kind, found, near)
    if kind == "slider-crank":
        a2 = scale * rng.uniform(0.2, 0.45)
        return Case(kind, slider_crank(a2, scale, rng.uniform(-0.3, 0.3) * scale, rng.uniform(0, 360), omega, alpha,
                                       ahead=rng.random() < 0.7))
    if kind == "piston":
        a2 = scale * rng.uniform(0.2, 0.45)
        return Case(kind, piston(a2, scale, near, outer=rng.random() < 0.5, s_dot=omega * scale,
                                 s_ddot=alpha * scale, upper=rng.random() < 0.5), near)
    a1 = scale
    if kind == "slotted lever":
        a2 = scale * rng.uniform(0.2, 0.6)
        return Case(kind, slotted_lever(a1, a2, rng.uniform(-0.15, 0.15) * a2, rng.uniform(0, 360), omega, alpha))
    a2 = scale * rng.uniform(0.2, 0.6)
    return Case(kind, slotted_lever_reversal(a1, a2, rng.choice([-1.0, 1.0]) * near, omega=omega, alpha=alpha), near)


def scaled(scene: Scene, length: float = 1.0, speed: float = 1.0) -> Scene:
    """The same scene with every length times ``length`` and every rate of the input times ``speed``.

    Velocities then scale by length * speed, accelerations by length * speed^2, omega by speed,
    alpha by speed^2; angles do not change.
    """
    def v(p: tuple[float, float]) -> tuple[float, float]:
        return (p[0] * length, p[1] * length)

    links = tuple(replace(k, points=tuple(replace(p, local=v(p.local)) for p in k.points)) for k in scene.links)
    sliders = tuple(replace(s, through=v(s.through)) for s in scene.sliders)
    guess = tuple((name, v(at)) for name, at in scene.guess)
    inp = scene.input
    if isinstance(inp, LinkInput):
        new_input: InputSpec = replace(inp, omega=inp.omega * speed, alpha=inp.alpha * speed * speed)
    elif isinstance(inp, SliderInput):
        new_input = replace(inp, s=inp.s * length, s_dot=inp.s_dot * length * speed,
                            s_ddot=inp.s_ddot * length * speed * speed)
    else:
        new_input = replace(inp, points=tuple(
            replace(g, velocity=(g.velocity[0] * length * speed, g.velocity[1] * length * speed),
                    acceleration=None if g.acceleration is None else
                    (g.acceleration[0] * length * speed * speed, g.acceleration[1] * length * speed * speed))
            for g in inp.points))
    return replace(scene, links=links, sliders=sliders, guess=guess, input=new_input)


def translated(scene: Scene, offset: tuple[float, float]) -> Scene:
    """The same mechanism moved by ``offset`` in the frame (the frame link's points, its slider lines, the guess)."""
    frame = scene.ground if scene.ground is not None else scene.links[0].name

    def move(p: tuple[float, float]) -> tuple[float, float]:
        return (p[0] + offset[0], p[1] + offset[1])

    links = tuple(replace(k, points=tuple(replace(p, local=move(p.local)) for p in k.points)) if k.name == frame
                  else k for k in scene.links)
    sliders = tuple(replace(s, through=move(s.through)) if s.guide == frame else s for s in scene.sliders)
    guess = tuple((name, move(at)) for name, at in scene.guess)
    return replace(scene, links=links, sliders=sliders, guess=guess)
