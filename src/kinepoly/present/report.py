"""What ``kinepoly solve`` prints: the contract's JSON, a readable table, the steps. Pure functions.

The instant centers' part is ``present.centers``; the polygon scales ``present.scales``.
"""

from __future__ import annotations

import math
from typing import Any

from kinepoly.check.summary import QuantityError
from kinepoly.engine.steps import Step
from kinepoly.geom.tolerances import ANGLE_SAME_RAD, LOUD_ERROR, PARALLEL_SIN
from kinepoly.geom.vec import Vec, norm, unit
from kinepoly.present.clean import Noise, given_angle, noise_of
from kinepoly.present.phrasing import Context, canonical_terms, canonical_text, english, scale_note, step_sentence
from kinepoly.present.scales import PolygonScales, decide_scales
from kinepoly.scene.spec import GivenInput, LinkInput, Scene
from kinepoly.solution import Solution

__all__ = ["input_text", "named_line", "readable_json", "solved", "steps_text", "table_text", "to_json"]


def _pair(v: Vec) -> list[float]:
    return [float(v[0]) + 0.0, float(v[1]) + 0.0]  # + 0.0 turns -0.0 into 0.0


def _angle(solution: Solution, radians: float) -> float:
    return math.degrees(radians) if solution.scene.units.angle == "deg" else radians


def _link_angle(solution: Solution, link: str) -> float:
    """theta_1k in the scene's unit; a driven link's as the scene gives it (60, not 59.99999999999999)."""
    if solution.driven_link(link) is not None:
        return given_angle(solution.angle(link), solution.scene.units.angle)
    return _angle(solution, solution.angle(link))


def named_line(solution: Solution, link: str) -> tuple[str, float]:
    """The line of ``link`` a reader knows it by, and its angle to the frame (rad, in (-pi, pi]): the line from
    its first point to its second (``HD``), or, for a link of one point on a slide (a cylinder's barrel or rod),
    the slide's axis (``axis 34``); else its own x-axis (``theta_1j``)."""
    points = solution.scene.link(link).point_names
    if len(points) >= 2:
        a, b = solution.position(points[0]), solution.position(points[1])
        if a != b:
            return f"{points[0]}{points[1]}", math.atan2(b[1] - a[1], b[0] - a[0])
    for slider in sorted(solution.scene.sliders, key=lambda s: s.guide != link):
        if link in (slider.guide, slider.block) and slider.guide in solution.pose.links \
                and slider.block not in solution.scene.equivalent_links:
            angle = math.remainder(solution.angle(slider.guide) + slider.angle_rad, 2.0 * math.pi)
            return f"axis {slider.name}", angle
    return "x-axis", solution.angle(link)


def _shown_tips(solution: Solution, kind: str) -> dict[str, Vec]:
    polygon = solution.velocity if kind == "velocity" else solution.acceleration
    assert polygon is not None
    ground = solution.mechanism.ground
    ground_points = set(solution.mechanism.scene.link(ground).point_names) if ground else set()
    asked = {p for p in (solution.scene.find.velocity if kind == "velocity" else solution.scene.find.acceleration)}
    return {label: tip for label, tip in polygon.tips.items() if label not in ground_points or label in asked}


def _step_json(step: Step, k: float, context: Context) -> dict[str, Any]:
    return {
        "polygon": step.polygon,
        "kind": step.kind,
        "equation": step.equation,
        "text": step_sentence(step, english(), context),
        "result": step.result,
        "known": [{"term": t, "known": what} for t, what in step.known],
        "lines": [{"through": _pair((k * ln.through[0], k * ln.through[1])),
                   "direction": _pair(unit(ln.direction)) if norm(ln.direction) > 0 else [0.0, 0.0],
                   "label": ln.label} for ln in step.lines],
        "vectors": [{"label": v.label, "term": v.term, "from": _pair((k * v.start[0], k * v.start[1])),
                     "to": _pair((k * v.end[0], k * v.end[1]))} for v in step.vectors],
    }


def to_json(solution: Solution, scales: PolygonScales | None = None) -> dict[str, Any]:
    """The result object of the contract (``kinepoly solve --json``).

    ``scales`` are the polygon scales of the drawing (``present.scales.decide_scales``; A4 when None):
    the polygons' ``scale``, their tips on the paper and the steps' lengths on the paper use them; a
    scale the paper reduced is a ``scale-reduced`` warning, and its polygon has ``wanted`` too.
    """
    scene, asked = solution.scene, solution.asked
    out: dict[str, Any] = {"title": scene.title, "units": {"length": scene.units.length, "angle": scene.units.angle}}
    links: dict[str, dict[str, float]] = {}
    for name in dict.fromkeys((*asked.omega, *asked.alpha)):
        line, at = named_line(solution, name)
        link_entry = links.setdefault(name, {"angle": _link_angle(solution, name)})
        if abs(math.remainder(at - solution.angle(name), 2.0 * math.pi)) > ANGLE_SAME_RAD:  # theta_1j is not its line's
            link_entry["line"] = {"name": line, "angle": _angle(solution, at)}  # type: ignore[assignment]
        driven = solution.driven_link(name)  # its omega and alpha given, not recomputed
        if name in asked.omega and solution.velocity is not None:
            link_entry["omega"] = driven.omega if driven is not None else solution.velocity.omega[name]
        if name in asked.alpha and solution.acceleration is not None:
            link_entry["alpha"] = driven.alpha if driven is not None else solution.acceleration.alpha[name]
    if links:
        out["links"] = links
    points: dict[str, dict[str, list[float]]] = {}
    for label in dict.fromkeys((*scene.find.velocity, *scene.find.acceleration)):
        points[label] = {"position": _pair(solution.position(label))}
    for label in scene.find.velocity:
        assert solution.velocity is not None
        points[label]["velocity"] = _pair(solution.velocity.tips[label])
    for label in scene.find.acceleration:
        assert solution.acceleration is not None
        points[label]["acceleration"] = _pair(solution.acceleration.tips[label])
    if points:
        out["points"] = points
    if asked.sliders:
        sliders: dict[str, dict[str, Any]] = {}
        for name in asked.sliders:
            values = solution.slider(name)
            entry: dict[str, Any] = {"s": values.s}
            if values.s_dot is not None:
                entry["s_dot"] = values.s_dot
            if values.s_ddot is not None and values.coriolis is not None:
                entry["s_ddot"] = values.s_ddot
                entry["coriolis"] = _pair(values.coriolis)
            sliders[name] = entry
        out["sliders"] = sliders
    if solution.contacts:
        out["contacts"] = {name: {"point": _pair(c.point), "normal": _pair(c.normal),
                                  **({"sliding_velocity": _pair(c.sliding_velocity)}
                                     if c.sliding_velocity is not None else {})}
                           for name, c in solution.contacts.items()}
    decided = scales if scales is not None else decide_scales(solution)
    polygons: dict[str, Any] = {}
    for scale in decided.polygons:
        k = scale.value
        tips: dict[str, list[float]] = {"o": [0.0, 0.0]}
        tips.update({label.lower(): _pair((k * v[0], k * v[1]))
                     for label, v in _shown_tips(solution, scale.kind).items()})
        polygons[scale.kind] = {"scale": k, "points": tips}
        if scale.reduced:
            polygons[scale.kind]["wanted"] = scale.wanted
    if polygons:
        out["polygons"] = polygons
    if solution.centers is not None:
        from kinepoly.present.centers import centers_json  # loaded only for a solution with instant centers

        out["instant_centers"] = centers_json(solution.centers)
    context = Context(solution, decided.as_dict())
    out["steps"] = [_step_json(s, decided.get(s.polygon) or 1.0, context) for s in solution.steps]
    if solution.centers is not None:
        from kinepoly.present.centers import kennedy_steps_json

        out["steps"] += kennedy_steps_json(solution.centers, context)
    check = solution.check
    out["check"] = {
        "reference": "analytic",
        "max_rel_error": check.max_rel_error,
        "relative": dict(check.relative),
        "condition_number": check.condition_number,
        "differences": {q.key: q.difference for q in check.quantities},
    }
    if solution.accuracy is not None:
        out["check"].update(_accuracy_json(solution))
    out["plan"] = solution.plan.describe()
    out["timing"] = dict(solution.timing)
    out["warnings"] = [{"code": n.code, "message": n.message} for n in solution.notices]
    out["warnings"] += [{"code": "scale-reduced", "message": scale_note(scale, decided.paper, english())}
                        for scale in decided.reduced]
    return out


def readable_json(solution: Solution, noise: Noise | None = None,
                  scales: PolygonScales | None = None) -> dict[str, Any]:
    """``to_json`` with every printed value below its error estimate set to 0 (``present.clean``).

    For the text meant for people (the table, the title block); the JSON keeps the computed floats.
    """
    noise = noise if noise is not None else noise_of(solution)
    data = to_json(solution, scales)
    degrees = solution.scene.units.angle == "deg"
    for entry in data.get("links", {}).values():
        entry["angle"] = noise.degrees(entry["angle"]) if degrees else noise.value(entry["angle"], "angle")
        if "line" in entry:
            at = entry["line"]["angle"]
            entry["line"]["angle"] = noise.degrees(at) if degrees else noise.value(at, "angle")
        for key in ("omega", "alpha"):
            if key in entry:
                entry[key] = noise.value(entry[key], key)
    for entry in data.get("points", {}).values():
        for key in ("position", "velocity", "acceleration"):
            if key in entry:
                entry[key] = list(noise.pair(entry[key], key))
    for entry in data.get("sliders", {}).values():
        for key, kind in (("s", "position"), ("s_dot", "velocity"), ("s_ddot", "acceleration")):
            if key in entry:
                entry[key] = noise.value(entry[key], kind)
        if "coriolis" in entry:
            entry["coriolis"] = list(noise.pair(entry["coriolis"], "acceleration"))
    for entry in data.get("contacts", {}).values():
        entry["point"] = list(noise.pair(entry["point"], "position"))
        entry["normal"] = [0.0 if abs(x) < PARALLEL_SIN else x for x in entry["normal"]]  # a unit vector
        if "sliding_velocity" in entry:
            entry["sliding_velocity"] = list(noise.pair(entry["sliding_velocity"], "velocity"))
    return data


def _value_json(value: float | tuple[float, float]) -> float | list[float]:
    return _pair(value) if isinstance(value, tuple) else float(value)


def _accuracy_json(solution: Solution) -> dict[str, Any]:
    """Per kind: normwise, componentwise and estimated relative errors; per quantity: both values and more."""
    accuracy = solution.accuracy
    assert accuracy is not None
    return {
        "estimate": accuracy.estimated,
        "normwise": dict(accuracy.normwise),
        "componentwise": dict(accuracy.componentwise),
        "quantities": {q.key: {"kind": q.kind, "construction": _value_json(q.construction),
                               "analytic": _value_json(q.analytic), "difference": q.difference,
                               "estimate": q.estimate, "normwise": q.normwise, "componentwise": q.componentwise}
                       for q in accuracy.quantities},
    }


def _accuracy_rows(solution: Solution) -> list[str]:
    accuracy = solution.accuracy
    if accuracy is None or not accuracy.normwise:
        return []
    rows = [[kind, f"{accuracy.normwise[kind]:.2g}", _componentwise_text(accuracy.quantities, kind),
             f"{accuracy.estimated.get(kind, 0.0):.2g}"] for kind in accuracy.normwise]
    return _rows(["quantity", "normwise error", "componentwise error", "error estimate"], rows) + [""]


def _components(value: float | tuple[float, float]) -> tuple[float, ...]:
    return tuple(value) if isinstance(value, tuple) else (float(value),)


def _componentwise_text(quantities: tuple[QuantityError, ...], kind: str) -> str:
    """The worst componentwise error of ``kind`` over the components that mean something: those whose
    analytic value is above its quantity's error estimate (a component that is 0, or rounding noise
    around 0, has no relative error to speak of). "-" where no component is left."""
    worst: float | None = None
    for q in quantities:
        if q.kind != kind:
            continue
        for got, ref in zip(_components(q.construction), _components(q.analytic), strict=True):
            if abs(ref) > q.estimate and math.isfinite(ref):
                worst = max(worst or 0.0, abs(got - ref) / abs(ref))
    return "-" if worst is None else f"{worst:.2g}"


def _fmt(x: float) -> str:
    return f"{x:.6g}"


def input_text(solution: Solution) -> str:
    """Every input as a textbook writes it, ``theta12 = ...`` or ``s14 = ...``, separated by semicolons."""
    inp = solution.scene.input
    if isinstance(inp, GivenInput):
        return "given motion of " + ", ".join(p.name for p in inp.points)
    out = []
    for drive in solution.mechanism.drives:
        spec, pair = drive.spec, f"{drive.base}{drive.moving}"
        if isinstance(spec, LinkInput):
            out.append(f"theta{pair} = {_fmt(given_angle(spec.angle_rad, solution.scene.units.angle))} "
                       f"{solution.scene.units.angle}, "
                       f"omega{pair} = {_fmt(spec.omega)} rad/s, alpha{pair} = {_fmt(spec.alpha)} rad/s^2")
        else:
            u = solution.scene.units.length
            out.append(f"s{spec.slider} = {_fmt(spec.s)} {u}, s_dot = {_fmt(spec.s_dot)} {u}/s, "
                       f"s_ddot = {_fmt(spec.s_ddot)} {u}/s^2")
    return "; ".join(out)


def _rows(header: list[str], rows: list[list[str]]) -> list[str]:
    widths = [max(len(r[c]) for r in [header, *rows]) for c in range(len(header))]

    def line(row: list[str]) -> str:
        return "  ".join(v.rjust(w) if k else v.ljust(w) for k, (v, w) in enumerate(zip(row, widths, strict=True)))

    return [line(header), "  ".join("-" * w for w in widths), *(line(r) for r in rows)]


def _link_name(name: str, entry: dict[str, Any]) -> str:
    """A link's row label: its name and the line its angle is of (``2 (HD)``)."""
    return f"{name} ({entry['line']['name']})" if "line" in entry else name


def _line_angle(entry: dict[str, Any]) -> float:
    return float(entry["line"]["angle"] if "line" in entry else entry["angle"])


def table_text(solution: Solution, scales: PolygonScales | None = None) -> str:
    """A readable summary: links, points, sliders, scales (``to_json``'s), warnings, and the cross-check footer."""
    noise = noise_of(solution)
    data = readable_json(solution, noise, scales)
    u, au = solution.scene.units.length, solution.scene.units.angle
    out = [solution.scene.title, f"input: {input_text(solution)}", ""]
    if "links" in data:
        rows = [[_link_name(name, v), _fmt(_line_angle(v)), _fmt(v["omega"]) if "omega" in v else "",
                 _fmt(v["alpha"]) if "alpha" in v else ""] for name, v in data["links"].items()]
        out += _rows(["link", f"angle ({au})", "omega (rad/s)", "alpha (rad/s^2)"], rows) + [""]
    if "points" in data:
        rows = []
        for label, v in data["points"].items():
            vel, acc = v.get("velocity"), v.get("acceleration")
            rows.append([label, f"({_fmt(v['position'][0])}, {_fmt(v['position'][1])})",
                         f"({_fmt(vel[0])}, {_fmt(vel[1])})" if vel else "", _fmt(math.hypot(*vel)) if vel else "",
                         f"({_fmt(acc[0])}, {_fmt(acc[1])})" if acc else "", _fmt(math.hypot(*acc)) if acc else ""])
        out += _rows(["point", f"position ({u})", f"velocity ({u}/s)", "|v|", f"acceleration ({u}/s^2)", "|a|"],
                     rows) + [""]
    if "sliders" in data:
        rows = [[name, _fmt(v["s"]), _fmt(v["s_dot"]) if "s_dot" in v else "",
                 _fmt(v["s_ddot"]) if "s_ddot" in v else "",
                 f"({_fmt(v['coriolis'][0])}, {_fmt(v['coriolis'][1])})" if "coriolis" in v else ""]
                for name, v in data["sliders"].items()]
        out += _rows(["slider", f"s ({u})", f"s_dot ({u}/s)", f"s_ddot ({u}/s^2)", "coriolis"], rows) + [""]
    if "contacts" in data:
        rows = [[name, f"({_fmt(v['point'][0])}, {_fmt(v['point'][1])})",
                 f"({_fmt(v['normal'][0])}, {_fmt(v['normal'][1])})",
                 f"({_fmt(v['sliding_velocity'][0])}, {_fmt(v['sliding_velocity'][1])})" if "sliding_velocity" in v
                 else ""] for name, v in data["contacts"].items()]
        out += _rows(["contact", f"point ({u})", "normal", f"sliding velocity ({u}/s)"], rows) + [""]
    if solution.centers is not None:
        from kinepoly.present.centers import centers_table

        out += centers_table(solution.centers, u, data["check"]["relative"].get("instant_center"), noise) + [""]
    for kind, poly in data.get("polygons", {}).items():
        per = f"{u}/s" if kind == "velocity" else f"{u}/s^2"
        symbol = "kv" if kind == "velocity" else "ka"
        out.append(f"{kind} polygon: {symbol} = {poly['scale']:g} mm of paper per {per}")
    for w in data["warnings"]:
        out.append(f"warning [{w['code']}]: {w['message']}")
    out += _accuracy_rows(solution)
    err = data["check"]["max_rel_error"]
    verdict = "ok" if err <= LOUD_ERROR else "DISAGREES"
    t = data["timing"]
    out.append(f"cross-check against the analytic solution: max relative error {err:.2g} ({verdict}); "
               f"run time {1e3 * t['total_s']:.3g} ms (load {1e3 * t['load_s']:.2g}, position "
               f"{1e3 * t['position_s']:.2g}, construction {1e3 * t['construction_s']:.2g}, check "
               f"{1e3 * t['check_s']:.2g})")
    return "\n".join(out)


def steps_text(solution: Solution, scales: PolygonScales | None = None) -> str:
    """The construction, one numbered step after another (the sentences from ``present.phrasing``, in English).

    The lengths on the paper are at ``scales`` (``present.scales.decide_scales``; A4 when None).
    """
    decided = scales if scales is not None else decide_scales(solution)
    context = Context(solution, decided.as_dict())
    out = [f"{solution.scene.title}: the construction, step by step", ""]
    out += [f"position: {line}" for line in solution.plan.describe()] + [""]
    terms = canonical_terms(solution)
    for symbol, scale in (("kv", decided.get("velocity")), ("ka", decided.get("acceleration"))):
        if scale is not None:
            per = f"{solution.scene.units.length}/s" + ("" if symbol == "kv" else "^2")
            out.append(f"scale: {symbol} = {scale:g} mm of paper per {per}")
    out += [""] if decided.polygons else []
    for n, step in enumerate(solution.steps, 1):
        out.append(f"{n:>2}. [{step.polygon}, {step.kind}] {canonical_text(step.equation, terms)}")
        out.append(f"    {step_sentence(step, english(), context)}")
        if step.known:
            out.append("    known: " + "; ".join(f"{canonical_text(t, terms)} ({what})" for t, what in step.known))
    if solution.centers is not None:
        from kinepoly.present.centers import centers_steps_text

        out += centers_steps_text(solution.centers, len(solution.steps) + 1, context)
    return "\n".join(out)


def solved(scene: Scene, paper: tuple[float, float], load_s: float = 0.0) -> tuple[Solution, dict[str, Any]]:
    """The solution of ``scene`` and the object ``kinepoly solve --json`` prints for it on ``paper`` (``kinepoly
    edit`` answers it too)."""
    from kinepoly.solution import solve  # looked up at the call, as the command line always did

    solution = solve(scene, load_s=load_s)
    return solution, to_json(solution, decide_scales(solution, paper))
