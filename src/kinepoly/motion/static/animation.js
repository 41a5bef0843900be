"use strict";
const D = JSON.parse(document.getElementById("frames").textContent);
const drawing = document.getElementById("drawing");
const table = document.getElementById("values");
const cells = D.values.map(v => {
  const tr = document.createElement("tr");
  const name = document.createElement("td"), value = document.createElement("td"), u = document.createElement("td");
  name.innerHTML = v.label; value.className = "number"; value.dataset.name = v.name; u.textContent = v.unit;
  tr.append(name, value, u);
  table.appendChild(tr);
  return value;
});
const slider = document.getElementById("position");
slider.max = D.rows.length - 1;
let frame = 0, timer = null;
function show(k) {
  frame = Math.max(0, Math.min(D.rows.length - 1, k));
  const row = D.rows[frame];
  slider.value = frame;
  document.body.dataset.row = row;
  document.body.dataset.frame = frame;
  drawing.innerHTML = D.sheets[frame];
  D.values.forEach((v, j) => {
    const x = v.values[row];
    cells[j].dataset.value = x === null ? "" : String(x);
    cells[j].textContent = x === null ? "\u2014" : Number(x.toPrecision(6)).toString();  // by the number rule already
  });
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
