// kinepoly edit: the page. It draws what the server sends (the sheet of `kinepoly draw`, the values of
// `kinepoly solve --json`) and sends edits back over the websocket; it holds no geometry of its own:
// a drag sends the pointer's place in the frame, and the server makes the edit of the scene from it.
"use strict";

const SVG_NS = "http://www.w3.org/2000/svg";
const $ = (id) => document.getElementById(id);

const editor = {
  socket: null,
  state: null,        // the server's last state
  good: null,         // the last state that had a drawing
  seq: 0,
  inFlight: null,     // {seq, started}: the message awaiting its answer
  pending: [],        // the messages made while one was in flight; a drag's moves coalesce: the latest wins
  drag: null,         // {kind, name, first}
  drafts: true,       // while dragging, ask for draft sheets (labels unsearched); the whole sheet when it stops
  drafted: false,     // whether the sheet shown, or one asked for, is a draft not yet asked whole
  pause: null,        // the timer that asks for the whole sheet when a drag pauses
  pauseMs: 150,       // a drag still this long gets its whole sheet
  timings: [],        // per answered drag move: milliseconds from the pointer event to the redrawn sheet
  fullTimings: [],    // per whole sheet after a drag: milliseconds from the release (or pause) to it redrawn
  adding: null,       // {slider, clicks}: a dyad being added by clicks
};
window.kinepolyEditor = editor;

function connect() {
  const url = new URL("ws", window.location.href);
  url.protocol = url.protocol === "https:" ? "wss:" : "ws:";
  const socket = new WebSocket(url.href);
  editor.socket = socket;
  socket.addEventListener("open", () => send({op: "state"}));
  socket.addEventListener("message", (event) => { const arrived = performance.now(); receive(JSON.parse(event.data), arrived); });
  socket.addEventListener("close", () => status("disconnected: is kinepoly edit still running?"));
}

const isMove = (message) => message.op === "edit" && message.merge === true;

function send(message, started) {
  if (editor.inFlight) {
    // never queue a stale move: a drag's move replaces the move waiting before it (and a whole sheet asked
    // before it, which the move would supersede); any other change waits its turn
    const pending = editor.pending;
    if (isMove(message)) {
      while (pending.length && (isMove(pending.at(-1).message) || pending.at(-1).message.op === "full")) pending.pop();
    }
    if (!(message.op === "full" && pending.length && pending.at(-1).message.op === "full")) {
      pending.push({message, started});
    }
    return;
  }
  editor.seq += 1;
  editor.inFlight = {seq: editor.seq, started: started ?? performance.now(), drag: message.op === "edit",
    full: message.op === "full"};
  editor.socket.send(JSON.stringify({...message, seq: editor.seq}));
}

function dragMove(message, started) {
  // a move of a drag (or of the input's slider): a draft sheet, and the whole one once it stops
  send({...message, draft: editor.drafts}, started);
  if (!editor.drafts) return;
  editor.drafted = true;
  clearTimeout(editor.pause);
  editor.pause = setTimeout(wholeSheet, editor.pauseMs);
}

function wholeSheet() {
  clearTimeout(editor.pause);
  editor.pause = null;
  if (!editor.drafted) return;
  editor.drafted = false;
  send({op: "full"});
}

function receive(state, arrived) {
  const flight = editor.inFlight;
  editor.inFlight = null;
  render(state);
  if (flight && (flight.drag || flight.full) && state.seq === flight.seq) {
    const received = arrived ?? performance.now();  // the answer's arrival, before the page parsed and drew it
    const into = flight.drag ? editor.timings : editor.fullTimings;
    // the frame that shows the new sheet is painted before a task queued from its animation callback runs
    requestAnimationFrame(() => setTimeout(() => {
      into.push({ms: performance.now() - flight.started, received: received - flight.started,
        server: state.timing_ms, ok: state.ok, draft: Boolean(state.draft)});
    }, 0));
  }
  if (editor.pending.length) {
    const {message, started} = editor.pending.shift();
    send(message, started);
  }
}

function status(text) { $("status").textContent = text; }

function render(state) {
  editor.state = state;
  $("path").textContent = state.path;
  $("dirty").textContent = state.dirty ? "●" : "";
  $("undo").disabled = !state.can_undo;
  $("redo").disabled = !state.can_redo;
  if (state.refused) status(state.refused);
  const message = $("message");
  message.hidden = state.ok;
  message.textContent = state.ok ? "" : state.errors.join("\n") +
    (state.svg ? "\n(the drawing is the last that solved)" : "");
  if (document.activeElement !== $("text")) $("text").value = state.text;
  if (state.svg) {
    editor.good = state;
    drawSheet(state);
    fields(state.handles);
    linksList(state.handles);
    values(state.ok ? state.result : state.good_result);
  }
  $("sheet").classList.toggle("stale", !state.ok);
  $("sheet").classList.toggle("draft", Boolean(state.draft));
}

function drawSheet(state) {
  const sheet = $("sheet");
  sheet.innerHTML = state.svg.replace(/^<\?xml[^>]*>\s*/, "");
  const svg = sheet.querySelector("svg");
  svg.removeAttribute("width");
  svg.removeAttribute("height");
  const layer = document.createElementNS(SVG_NS, "g");
  layer.setAttribute("id", "handles");
  const h = state.handles;
  const input = h.input;
  for (const [name, point] of Object.entries(h.points)) {
    const isInput = input && input.point === name;
    if (!point.written && !isInput) continue;  // a point the loader made (a cam's profile centre): not the scene's
    addHandle(layer, state.view, point.at, name, isInput ? "input" : point.frame ? "frame" : "point", 2.0);
  }
  for (const [name, at] of Object.entries(h.guess)) addHandle(layer, state.view, at, name, "guess", 3.2);
  svg.appendChild(layer);
}

function toSheet(view, at) {
  return [view.origin[0] + view.scale * at[0], view.height - (view.origin[1] + view.scale * at[1])];
}

function toScene(view, svg, event) {
  const p = svg.createSVGPoint();
  p.x = event.clientX;
  p.y = event.clientY;
  const q = p.matrixTransform(svg.getScreenCTM().inverse());
  return [(q.x - view.origin[0]) / view.scale, (view.height - q.y - view.origin[1]) / view.scale];
}

function addHandle(layer, view, at, name, kind, radius) {
  const g = document.createElementNS(SVG_NS, "g");
  g.setAttribute("class", `handle ${kind}`);
  g.dataset.name = name;
  g.dataset.kind = kind;
  const [x, y] = toSheet(view, at);
  const c = document.createElementNS(SVG_NS, "circle");
  c.setAttribute("cx", x);
  c.setAttribute("cy", y);
  c.setAttribute("r", radius);
  if (kind === "guess") {  // grabbed by its ring: inside it lies the point's own handle
    const grip = document.createElementNS(SVG_NS, "circle");
    Object.entries({cx: x, cy: y, r: radius, class: "grip"}).forEach(([k, v]) => grip.setAttribute(k, v));
    g.appendChild(grip);
  }
  const title = document.createElementNS(SVG_NS, "title");
  title.textContent = kind === "guess" ? `[guess] ${name}: drag to pick the assembly nearest it`
    : kind === "input" ? `${name}: drag to move the input (Shift: change the link)` : `${name}: drag to move`;
  g.prepend(title, c);
  layer.appendChild(g);
}

function editFor(kind, name, at, shift) {
  if (kind === "guess") return {op: "guess", point: name, to: at};
  if (kind === "input" && !shift) return {op: "drive", to: at};
  return {op: "move-point", point: name, to: at};
}

const ADD_PROMPTS = [
  "click the point of the mechanism the new dyad starts from",
  "click where the new joint goes",
  "click the point it pins to, or an empty place for a new frame pivot (Esc cancels)",
];
const SLIDER_PROMPT = "click a place along the slide on the frame, from the new joint (Esc cancels)";

function startAdding(slider) {
  editor.adding = {slider, clicks: []};
  $("add-pin").classList.toggle("active", !slider);
  $("add-slider").classList.toggle("active", slider);
  status(ADD_PROMPTS[0]);
}

function stopAdding(text) {
  editor.adding = null;
  $("add-pin").classList.remove("active");
  $("add-slider").classList.remove("active");
  document.querySelectorAll(".click-mark").forEach((mark) => mark.remove());
  status(text);
}

function addClick(event) {
  const adding = editor.adding;
  const handle = event.target.closest(".handle");
  const name = handle && handle.dataset.kind !== "guess" ? handle.dataset.name : null;
  const svg = $("sheet").querySelector("svg");
  const at = toScene(editor.good.view, svg, event);
  const step = adding.clicks.length;
  if (step === 0 && !name) { status(`${ADD_PROMPTS[0]}: that place is no point`); return; }
  adding.clicks.push(step === 0 ? {point: name} : step === 1 ? {at} : name && !adding.slider ? {point: name} : {at});
  const mark = document.createElementNS(SVG_NS, "circle");
  const [x, y] = toSheet(editor.good.view, at);
  Object.entries({cx: x, cy: y, r: 1.0, class: "click-mark"}).forEach(([k, v]) => mark.setAttribute(k, v));
  svg.querySelector("#handles").appendChild(mark);
  if (adding.clicks.length < 3) { status(adding.slider && step === 1 ? SLIDER_PROMPT : ADD_PROMPTS[step + 1]); return; }
  const [from, joint, to] = adding.clicks;
  stopAdding("");
  send({op: "edit", edit: {op: "add-dyad", from: from.point, joint: joint.at, to, slider: adding.slider}});
}

function linksList(handles) {
  const list = $("links");
  list.replaceChildren();
  for (const link of handles.links) {
    const li = document.createElement("li");
    li.textContent = `link ${link.name}: ${link.points.join(", ")}`;
    if (handles.removable.includes(link.name)) {
      const button = document.createElement("button");
      button.type = "button";
      button.textContent = "remove";
      button.dataset.link = link.name;
      button.addEventListener("click", () => send({op: "edit", edit: {op: "remove-link", link: link.name}}));
      li.appendChild(button);
    }
    list.appendChild(li);
  }
}

function onPointerDown(event) {
  if (editor.adding && editor.good) { event.preventDefault(); addClick(event); return; }
  const handle = event.target.closest(".handle");
  if (!handle || !editor.good) return;
  event.preventDefault();
  $("sheet").setPointerCapture?.(event.pointerId);  // the sheet, not its drawing: that is replaced at each answer
  const svg = $("sheet").querySelector("svg");
  const at = toScene(editor.good.view, svg, event);
  const h = editor.good.handles;
  const center = handle.dataset.kind === "guess" ? h.guess[handle.dataset.name] : h.points[handle.dataset.name].at;
  editor.drag = {kind: handle.dataset.kind, name: handle.dataset.name, shift: event.shiftKey, first: true,
    offset: [center[0] - at[0], center[1] - at[1]]};  // the handle's centre follows, not the pointer's place on it
}

function onPointerMove(event) {
  const drag = editor.drag;
  if (!drag) return;
  const svg = $("sheet").querySelector("svg");
  const pointer = toScene(editor.good.view, svg, event);
  const at = [pointer[0] + drag.offset[0], pointer[1] + drag.offset[1]];
  const started = event.timeStamp || performance.now();  // the event's time, on performance.now()'s clock
  dragMove({op: "edit", edit: editFor(drag.kind, drag.name, at, drag.shift), merge: !drag.first}, started);
  drag.first = false;
}

function onPointerUp() {
  if (!editor.drag) return;
  editor.drag = null;
  wholeSheet();  // released: the whole sheet at once
}

function number(x) {
  if (typeof x !== "number") return String(x);
  const a = Math.abs(x);
  return a !== 0 && (a < 1e-3 || a >= 1e6) ? x.toExponential(4) : String(Number(x.toPrecision(6)));
}

function field(container, label, value, onChange, range) {
  const row = document.createElement("label");
  row.className = "field";
  const name = document.createElement("span");
  name.textContent = label;
  const input = document.createElement("input");
  input.type = "number";
  input.step = "any";
  input.value = number(value);
  input.dataset.key = label;
  input.addEventListener("change", () => { if (input.value !== "") onChange(Number(input.value), false); });
  row.append(name, input);
  container.appendChild(row);
  if (range) {
    const slider = document.createElement("input");
    slider.type = "range";
    Object.assign(slider, range);
    slider.value = value;
    slider.dataset.key = `${label}-range`;
    let first = true;
    slider.addEventListener("input", () => { onChange(Number(slider.value), !first, true); first = false; });
    slider.addEventListener("change", () => { first = true; wholeSheet(); });
    container.appendChild(slider);
  }
}

function fields(handles) {
  const box = $("input-fields");
  if (box.contains(document.activeElement)) return;
  box.replaceChildren();
  const values = handles.fields;
  if (!values) {
    box.textContent = "This scene's input is edited in its text.";
  } else {
    for (const [key, value] of Object.entries(values)) {
      const range = key === "angle" ? {min: -180, max: 180, step: 0.5} : null;
      field(box, key, value, (v, merge, sliding) => {
        const message = {op: "edit", edit: {op: "set", key: ["input", key], value: v}, merge};
        if (sliding) dragMove(message); else send(message);
      },
        range && editor.state.result?.units?.angle === "deg" ? range : null);
    }
  }
  const table = $("lengths");
  if (!table.contains(document.activeElement)) {
    table.replaceChildren();
    for (const item of handles.lengths) {
      const tr = table.insertRow();
      tr.insertCell().textContent = `link ${item.link}`;
      tr.insertCell().textContent = `${item.from}${item.point}`;
      const input = document.createElement("input");
      input.type = "number";
      input.step = "any";
      input.min = "0";
      input.value = number(item.length);
      input.dataset.key = `${item.link}:${item.point}`;
      input.addEventListener("change", () => send({op: "edit",
        edit: {op: "length", link: item.link, point: item.point, value: Number(input.value)}}));
      tr.insertCell().appendChild(input);
    }
  }
  const guesses = $("guesses");
  const names = Object.entries(handles.guess);
  guesses.textContent = names.length
    ? "The assembly nearest the [guess]: " + names.map(([n, at]) => `${n} (${number(at[0])}, ${number(at[1])})`).join(", ")
      + "; drag its dashed ring to the other side to take the other assembly."
    : "No [guess]: the default assembly (see the warnings).";
  // a dyad's inner joint with no guess: give it one where it is, then drag its ring
  const joints = Object.entries(handles.points).filter(([n, p]) => p.written && handles.assembly.includes(n));
  for (const [name, point] of joints) {
    const button = document.createElement("button");
    button.type = "button";
    button.textContent = `guess ${name}`;
    button.title = `add [guess] ${name} where it is now: its ring then picks the assembly`;
    button.dataset.guess = name;
    button.addEventListener("click", () => send({op: "edit", edit: {op: "guess", point: name, to: point.at}}));
    guesses.append(" ", button);
  }
}

function values(result) {
  const table = $("values");
  table.replaceChildren();
  if (!result) return;
  const units = result.units;
  const head = (cells) => { const tr = table.insertRow(); for (const c of cells) { const th = document.createElement("th"); th.textContent = c; tr.appendChild(th); } };
  const row = (cells) => { const tr = table.insertRow(); for (const c of cells) tr.insertCell().textContent = c; };
  if (result.links) {
    head(["link", `angle (${units.angle})`, "omega (rad/s)", "alpha (rad/s²)"]);
    for (const [name, v] of Object.entries(result.links)) row([name, number(v.angle), number(v.omega ?? ""), number(v.alpha ?? "")]);
  }
  if (result.points) {
    head(["point", `|v| (${units.length}/s)`, `|a| (${units.length}/s²)`, ""]);
    const size = (p) => p ? number(Math.hypot(p[0], p[1])) : "";
    for (const [name, v] of Object.entries(result.points)) row([name, size(v.velocity), size(v.acceleration), ""]);
  }
  if (result.sliders) {
    head(["slider", "s", "s_dot", "s_ddot"]);
    for (const [name, v] of Object.entries(result.sliders)) row([name, number(v.s), number(v.s_dot ?? ""), number(v.s_ddot ?? "")]);
  }
  const check = result.check || {};
  const warnings = (result.warnings || []).map((w) => `${w.code}: ${w.message}`).join("\n");
  $("check").textContent = `check against the ${check.reference ?? "analytic"} solution: largest relative error `
    + `${number(check.max_rel_error)}` + (warnings ? `\n${warnings}` : "");
  const steps = $("steps");
  steps.replaceChildren();
  (result.steps || []).forEach((step, i) => {
    const li = document.createElement("li");
    li.textContent = step.text;
    li.title = "show this step's sheet";
    li.addEventListener("click", () => {
      $("step-image").src = `api/steps/${i + 1}.svg?seq=${editor.seq}`;
      $("step-dialog").showModal();
    });
    steps.appendChild(li);
  });
}

async function save(force) {
  const response = await fetch("api/save", {method: "POST", headers: {"Content-Type": "application/json"},
    body: JSON.stringify({force})});
  const body = await response.json();
  if (response.status === 409 && !force) {
    if (window.confirm(`${body.error}. Overwrite it with the editor's text?`)) return save(true);
    status("not saved: the file changed on disk");
    return;
  }
  if (!response.ok) { status(`not saved: ${body.error}`); return; }
  status(`saved ${body.saved}`);
  send({op: "state"});
}

function start() {
  const sheet = $("sheet");
  sheet.addEventListener("pointerdown", onPointerDown);
  sheet.addEventListener("pointermove", onPointerMove);
  window.addEventListener("pointerup", onPointerUp);  // released anywhere, even off the drawing
  window.addEventListener("pointercancel", onPointerUp);
  $("undo").addEventListener("click", () => send({op: "undo"}));
  $("redo").addEventListener("click", () => send({op: "redo"}));
  $("save").addEventListener("click", () => save(false));
  $("apply").addEventListener("click", () => send({op: "text", text: $("text").value}));
  $("add-pin").addEventListener("click", () => startAdding(false));
  $("add-slider").addEventListener("click", () => startAdding(true));
  document.addEventListener("keydown", (event) => {
    if (event.key === "Escape" && editor.adding) { stopAdding("adding cancelled"); return; }
    if (!(event.ctrlKey || event.metaKey) || event.target === $("text")) return;
    const key = event.key.toLowerCase();
    if (key === "z" && !event.shiftKey) { event.preventDefault(); send({op: "undo"}); }
    else if (key === "y" || (key === "z" && event.shiftKey)) { event.preventDefault(); send({op: "redo"}); }
    else if (key === "s") { event.preventDefault(); save(false); }
  });
  connect();
}

start();
