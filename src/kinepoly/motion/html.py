"""The motion as one self-contained web page: the frames as data, a small script drawing them as SVG.

Nothing is fetched: the data (every frame's link points, polygon tips in paper mm, the values at
every row) and the script are in the page. Controls: play/pause, a slider over the positions
reached, the arrow keys; the table shows the asked quantities at the position shown. Hooks for
tests: ``#position`` (the slider, frame index), ``#where`` (the position's label), each value's
cell ``td[data-name=NAME]`` with its exact number in ``data-value`` (empty where it has none),
``document.body.dataset.row`` (the sweep's row shown).
"""

from __future__ import annotations

import html
import math
from typing import Any

import numpy as np

from kinepoly.motion.frames import NO_POLYGON, PANEL_MM, Frames, PolygonFrames
from kinepoly.present.script_json import script_json
from kinepoly.sweep.run import STATUS

__all__ = ["html_page"]

_DIGITS = 3


def _xy(points: Any) -> list[float]:
    """Complex points as a flat [x0, y0, x1, y1, ...] rounded to the micrometre."""
    z = np.asarray(points, np.complex128).ravel()
    out = np.empty(2 * len(z))
    out[0::2], out[1::2] = z.real, z.imag
    return [round(float(v), _DIGITS) for v in out]


def _number(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


def _polygon(poly: PolygonFrames) -> dict[str, Any]:
    return {"kind": poly.kind, "symbol": poly.symbol, "scale": poly.scale, "unit": poly.unit,
            "labels": [label.partition("@")[0].lower() + label.partition("@")[2] for label in poly.labels],
            "tips": [_xy(row) for row in poly.tips], "valid": [bool(v) for v in poly.valid],
            "images": [list(i) for i in poly.images], "vectors": [list(v) for v in poly.vectors],
            "center": [poly.center.real, poly.center.imag], "half": 0.5 * PANEL_MM}


def frames_data(frames: Frames) -> dict[str, Any]:
    """The page's data: JSON-ready."""
    rows = [int(r) for r in frames.rows]
    chosen, window = frames.functions()
    return {
        "title": frames.title, "input": {"name": frames.input_name, "unit": frames.input_unit},
        "length": frames.length_unit, "rows": rows, "count": len(frames.inputs), "skipped": list(frames.skipped),
        "inputs": [float(x) for x in frames.inputs],
        "status": [STATUS[int(s)] for s in frames.status],
        "noPolygon": dict(zip(STATUS, NO_POLYGON)),
        "functions": {"names": [v.name for v in chosen], "window": window},
        "box": list(frames.box), "parts": list(frames.parts),
        "links": [{"name": link.name, "ground": link.ground, "points": list(link.points),
                   "xy": [_xy(row) for row in link.xy]} for link in frames.links],
        "sliders": [{"name": s.name, "a": _xy(s.guide_a), "b": _xy(s.guide_b), "block": _xy(s.block),
                     "dir": _xy(s.direction)} for s in frames.sliders],
        "paths": [{"name": t.name, "xy": _xy(t.xy)} for t in frames.paths],
        "centers": [{"name": t.name, "xy": _xy(t.xy), "valid": [bool(v) for v in t.valid]} for t in frames.centers],
        "polygons": [_polygon(p) for p in (frames.velocity, frames.acceleration) if p is not None],
        "values": [{"name": v.name, "unit": v.unit, "order": v.order,
                    "values": [_number(float(x)) if ok else None for x, ok in zip(v.values, v.valid)]}
                   for v in frames.values],
    }


_STYLE = """
body { font-family: DejaVu Sans, Verdana, Arial, sans-serif; margin: 16px; color: #111; }
h1 { font-size: 18px; margin: 0 0 8px 0; }
#panels { display: flex; gap: 8px; flex-wrap: wrap; }
.panel { border: 1px solid #999; background: #fff; }
.panel h2 { font-size: 12px; font-weight: normal; text-align: center; margin: 2px; }
#controls { margin: 10px 0; display: flex; gap: 12px; align-items: center; }
#position { width: 420px; }
table { border-collapse: collapse; font-size: 13px; }
td, th { padding: 2px 10px; border-bottom: 1px solid #ddd; text-align: left; }
td.number { text-align: right; font-variant-numeric: tabular-nums; }
#skipped { color: #a33; font-size: 13px; }
"""

_SCRIPT = r"""
"use strict";
const D = JSON.parse(document.getElementById("frames").textContent);
const NS = "http://www.w3.org/2000/svg";
const COLORS = {velocity: "#1f5fbf", acceleration: "#c0392b", sliding: "#d98200", coriolis: "#1e8c3a"};
const LINKS = ["#333333", "#1f5fbf", "#c0392b", "#1e8c3a", "#8e44ad", "#d98200", "#16a085"];
function el(parent, name, attrs) {
  const e = document.createElementNS(NS, name);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  parent.appendChild(e);
  return e;
}
function panel(title, box, width) {
  const div = document.createElement("div");
  div.className = "panel";
  const h = document.createElement("h2");
  h.textContent = title;
  div.appendChild(h);
  const [x0, y0, x1, y1] = box;
  const height = width * (y1 - y0) / (x1 - x0);
  const svg = el(div, "svg", {width: width, height: height, viewBox: `${x0} ${-y1} ${x1 - x0} ${y1 - y0}`});
  const defs = el(svg, "defs", {});
  for (const name in COLORS) {
    const m = el(defs, "marker", {id: `arrow-${name}`, viewBox: "0 0 10 10", refX: 10, refY: 5,
                                  markerWidth: 6, markerHeight: 6, orient: "auto-start-reverse"});
    el(m, "path", {d: "M0,0 L10,5 L0,10 z", fill: COLORS[name]});
  }
  document.getElementById("panels").appendChild(div);
  return svg;
}
const B = D.box, size = Math.max(B[2] - B[0], B[3] - B[1]), margin = 0.12 * size;
const mbox = [B[0] - margin, B[1] - margin, B[2] + margin, B[3] + margin];
const unit = size / 60;
const mech = panel(`Mechanism (${D.length})`, mbox, 460);
const drawn = {paths: [], links: [], labels: [], sliders: [], centers: []};
for (const p of D.paths)
  drawn.paths.push(el(mech, "polyline", {fill: "none", stroke: "#999", "stroke-width": unit * 0.3}));
D.links.forEach((link, j) => {
  if (link.ground) {
    for (let i = 0; i < link.points.length; i++) {
      const x = link.xy[0][2 * i], y = -link.xy[0][2 * i + 1];
      el(mech, "path", {d: `M${x},${y} l${-unit},${1.7 * unit} h${2 * unit} z`, fill: "#fff", stroke: "#333",
                        "stroke-width": unit * 0.25});
    }
    return;
  }
  drawn.links.push([link, el(mech, "polyline", {fill: "none", stroke: LINKS[j % LINKS.length],
                                                 "stroke-width": unit * 0.7, "stroke-linejoin": "round"})]);
});
const seen = new Set();
for (const link of D.links) link.points.forEach((name, i) => {
  if (seen.has(name)) return;
  seen.add(name);
  drawn.labels.push([link, i, el(mech, "text", {"font-size": unit * 2.4})]);
  drawn.labels[drawn.labels.length - 1][2].textContent = name;
});
for (const s of D.sliders)
  drawn.sliders.push([el(mech, "line", {stroke: "#555", "stroke-width": unit * 0.25}),
                      el(mech, "polygon", {fill: "none", stroke: "#333", "stroke-width": unit * 0.4})]);
for (const c of D.centers) {
  const t = el(mech, "text", {"font-size": unit * 2, fill: "#8e44ad"});
  t.textContent = "\u00d7" + c.name;
  drawn.centers.push(t);
}
const polys = D.polygons.map(p => {
  const h = p.half, c = p.center;
  const name = p.kind === "velocity" ? "Velocity polygon, kv" : "Acceleration polygon, ka";
  const svg = panel(`${name} = ${p.scale} mm per ${p.unit}`, [c[0] - h, c[1] - h, c[0] + h, c[1] + h], 300);
  el(svg, "circle", {cx: 0, cy: 0, r: 0.6, fill: "#000"});
  const o = el(svg, "text", {x: -3, y: 3, "font-size": 3.2});
  o.textContent = "o";
  const images = p.images.map(() => el(svg, "polyline", {fill: "none", stroke: COLORS[p.kind], "stroke-opacity": 0.5,
                                                           "stroke-width": 0.3}));
  const arrows = p.vectors.map(v => {
    const term = v[2] in COLORS ? v[2] : p.kind;
    return el(svg, "line", {stroke: COLORS[term], "stroke-width": 0.45, "marker-end": `url(#arrow-${term})`});
  });
  const labels = p.labels.map(l => { const t = el(svg, "text", {"font-size": 3.2, fill: COLORS[p.kind]});
                                     t.textContent = l; return t; });
  const singular = el(svg, "text", {x: c[0], y: -c[1] + 0.8 * h, "font-size": 3.5, "text-anchor": "middle", fill: "#888"});
  singular.textContent = "";
  return {p, svg, images, arrows, labels, singular};
});
let cursor = null;
if (D.parts.includes("functions")) {
  // the transmission functions of order 1 over the sweep, and a cursor at the position shown
  const chosen = D.values.filter(v => D.functions.names.includes(v.name));
  const xs = D.inputs, ys = chosen.flatMap(v => v.values.filter(x => x !== null));
  const x0 = Math.min(...xs), x1 = Math.max(...xs);
  const [y0, y1] = D.functions.window || [Math.min(0, ...ys), Math.max(0, ...ys)];  // a window: the rest cut off
  const w = 200, h = 60, sx = w / (x1 - x0 || 1), sy = h / (y1 - y0 || 1);
  const svg = panel(`${chosen.map(v => v.name).join(", ")} (${chosen.length ? chosen[0].unit : ""}) ` +
                    `against ${D.input.name}`, [-5, -5, w + 5, h + 5], 600);
  const X = x => (x - x0) * sx, Y = y => -(y - y0) * sy;
  el(svg, "line", {x1: 0, x2: w, y1: Y(0), y2: Y(0), stroke: "#bbb", "stroke-width": 0.3});
  chosen.forEach((v, j) => {
    let d = "", pen = false;
    v.values.forEach((y, i) => {
      if (y === null) { pen = false; return; }
      d += `${pen ? "L" : "M"}${X(xs[i]).toFixed(2)},${Y(y).toFixed(2)} `; pen = true;
    });
    el(svg, "path", {d, fill: "none", stroke: LINKS[(j + 1) % LINKS.length], "stroke-width": 0.6});
  });
  cursor = el(svg, "line", {y1: 5, y2: -h - 5, stroke: "#000", "stroke-width": 0.4});
  cursor.move = x => { cursor.setAttribute("x1", X(x)); cursor.setAttribute("x2", X(x)); };
}
const table = document.getElementById("values");
const cells = D.values.map(v => {
  const tr = document.createElement("tr");
  const name = document.createElement("td"), value = document.createElement("td"), u = document.createElement("td");
  name.textContent = v.name; value.className = "number"; value.dataset.name = v.name; u.textContent = v.unit;
  tr.append(name, value, u);
  table.appendChild(tr);
  return value;
});
const biggest = D.values.map(v => Math.max(0, ...v.values.filter(x => x !== null).map(Math.abs)));
const slider = document.getElementById("position");
slider.max = D.rows.length - 1;
let frame = 0, timer = null;
function at(xy, i) { return [xy[2 * i], -xy[2 * i + 1]]; }
function show(k) {
  frame = Math.max(0, Math.min(D.rows.length - 1, k));
  const row = D.rows[frame];
  slider.value = frame;
  document.body.dataset.row = row;
  document.body.dataset.frame = frame;
  for (const [link, line] of drawn.links) {
    const pts = [];
    for (let i = 0; i < link.points.length; i++) pts.push(at(link.xy[frame], i).join(","));
    if (pts.length >= 3) pts.push(pts[0]);
    line.setAttribute("points", pts.join(" "));
  }
  for (const [link, i, t] of drawn.labels) {
    const [x, y] = at(link.xy[frame], i);
    t.setAttribute("x", x + unit * 0.8); t.setAttribute("y", y - unit * 0.8);
  }
  D.paths.forEach((p, j) => {
    const pts = [];
    for (let i = 0; i <= frame; i++) pts.push(at(p.xy, i).join(","));
    drawn.paths[j].setAttribute("points", pts.join(" "));
  });
  D.sliders.forEach((s, j) => {
    const [line, block] = drawn.sliders[j];
    const a = at(s.a, frame), b = at(s.b, frame), c = at(s.block, frame), e = at(s.dir, frame);
    line.setAttribute("x1", a[0]); line.setAttribute("y1", a[1]);
    line.setAttribute("x2", b[0]); line.setAttribute("y2", b[1]);
    const h = 3 * unit, corners = [[-1, -1], [1, -1], [1, 1], [-1, 1]].map(([u, v]) =>
      [c[0] + h * (u * e[0] - 0.6 * v * e[1]), c[1] + h * (u * e[1] + 0.6 * v * e[0])].join(","));
    block.setAttribute("points", corners.join(" "));
  });
  D.centers.forEach((c, j) => {
    const [x, y] = at(c.xy, frame), t = drawn.centers[j];
    const inside = c.valid[frame] && x >= mbox[0] && x <= mbox[2] && -y >= mbox[1] && -y <= mbox[3];
    t.setAttribute("x", x); t.setAttribute("y", y); t.style.display = inside ? "" : "none";
  });
  for (const q of polys) {
    const tips = q.p.tips[frame], valid = q.p.valid[frame];
    const tip = i => i < 0 ? [0, 0] : at(tips, i);
    q.images.forEach((line, j) => line.setAttribute("points", q.p.images[j].map(i => tip(i).join(",")).join(" ")));
    q.arrows.forEach((line, j) => {
      const [s, e] = q.p.vectors[j], a = tip(s), b = tip(e);
      line.setAttribute("x1", a[0]); line.setAttribute("y1", a[1]);
      line.setAttribute("x2", b[0]); line.setAttribute("y2", b[1]);
      line.style.display = valid && Math.hypot(b[0] - a[0], b[1] - a[1]) > 0.3 ? "" : "none";
    });
    q.labels.forEach((t, i) => { const [x, y] = tip(i); t.setAttribute("x", x + 1); t.setAttribute("y", y - 1);
                                 t.style.display = valid ? "" : "none"; });
    q.images.forEach(line => { line.style.display = valid ? "" : "none"; });
    q.singular.style.display = valid ? "none" : "";
    q.singular.textContent = D.noPolygon[D.status[row]];
  }
  D.values.forEach((v, j) => {
    const x = v.values[row];
    cells[j].dataset.value = x === null ? "" : String(x);
    const tiny = x !== null && Math.abs(x) < 1e-9 * biggest[j];  // rounding noise of a rate through zero
    cells[j].textContent = x === null ? "\u2014" : tiny ? "0" : Number(x.toPrecision(6)).toString();
  });
  if (cursor !== null) cursor.move(D.inputs[row]);
  const status = D.status[row] === "ok" ? "" : ` (${D.status[row]})`;
  document.getElementById("where").textContent =
    `position ${row + 1} of ${D.count}: ${D.input.name} = ${Number(D.inputs[row].toPrecision(6))} ${D.input.unit}${status}`;
}
function play() {
  if (timer !== null) { clearInterval(timer); timer = null; }
  else timer = setInterval(() => show((frame + 1) % D.rows.length), 1000 / Number(document.body.dataset.fps));
  document.getElementById("play").textContent = timer === null ? "Play" : "Pause";
  document.body.dataset.playing = timer === null ? "no" : "yes";
}
document.getElementById("play").addEventListener("click", play);
slider.addEventListener("input", () => show(Number(slider.value)));
document.addEventListener("keydown", e => {
  if (e.target === slider) return;
  if (e.key === "ArrowRight") show(frame + 1);
  else if (e.key === "ArrowLeft") show(frame - 1);
  else if (e.key === " ") { play(); e.preventDefault(); }
});
if (D.skipped.length) document.getElementById("skipped").textContent =
  `${D.skipped.length} of ${D.count} positions cannot be reached and are skipped: ` +
  D.skipped.map(r => `${Number(D.inputs[r].toPrecision(6))}`).join(", ") + ` ${D.input.unit}`;
window.kinepoly = {show, play, data: D};
show(0);
"""


def html_page(frames: Frames, fps: float = 24.0) -> str:
    """The page: data, style and script inline; it draws frame 0 on load."""
    data = script_json(frames_data(frames))
    title = html.escape(frames.title)
    return (f'<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n<title>{title}: motion</title>\n'
            f"<style>{_STYLE}</style>\n</head>\n"
            f'<body data-fps="{fps:g}" data-playing="no">\n<h1>{title}</h1>\n<div id="panels"></div>\n'
            '<div id="controls"><button id="play" type="button">Play</button>'
            '<input id="position" type="range" min="0" max="0" step="1" value="0" aria-label="position">'
            '<span id="where"></span></div>\n<p id="skipped"></p>\n'
            '<table><thead><tr><th>quantity</th><th>value</th><th>unit</th></tr></thead>'
            '<tbody id="values"></tbody></table>\n'
            f'<script type="application/json" id="frames">{data}</script>\n<script>{_SCRIPT}</script>\n'
            "</body>\n</html>\n")
