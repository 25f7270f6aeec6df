#include "app/control/control_page.h"

namespace gb {

// The page reads the namespace (GET /), builds its controls from it, and talks OSC over the WebSocket: sets and cues
// out as OSC messages (reals as doubles, so a value at a range's end is not rounded out of it), LISTENed values in.
// The body's data-ready is 1 once the namespace is read and the WebSocket open (the browser test waits for it).
std::string_view controlPageHtml() {
  static constexpr std::string_view page = R"gbpage(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>giantbubble control</title>
<link rel="icon" href="data:,">
<style>
body{font-family:sans-serif;margin:0;background:#111;color:#eee}
header{position:sticky;top:0;background:#222;padding:.5em;z-index:1}
#status{font-size:.85em;line-height:1.4}
#cues,#presets{display:flex;flex-wrap:wrap;gap:.4em;padding:.5em}
button{font-size:1.1em;padding:.7em 1em;border-radius:.4em;border:0;background:#3a6ea5;color:#fff;min-width:5.5em}
button.danger{background:#a53a3a}
details{border-top:1px solid #333;padding:.3em .5em}
summary{font-weight:bold;padding:.4em 0;cursor:pointer}
.param{display:grid;grid-template-columns:1fr 7em;gap:.2em .5em;padding:.4em 0;border-bottom:1px solid #222}
.param label{grid-column:1/3;font-size:.9em}
.param small{color:#999}
input[type=range]{width:100%;height:2em}
input[type=number],input[type=text],select{font-size:1em;width:100%;box-sizing:border-box}
#presets input,#presets select{width:auto;flex:1}
</style></head>
<body data-ready="0">
<header><div id="status">connecting...</div></header>
<div id="cues"></div>
<div id="presets"></div>
<div id="params"></div>
<script>
"use strict";
const token = new URLSearchParams(location.search).get("token");
const withToken = (url) => token ? url + (url.includes("?") ? "&" : "?") + "token=" + encodeURIComponent(token) : url;
const pad4 = (n) => (n + 3) & ~3;
const encoder = new TextEncoder(), decoder = new TextDecoder();
function oscEncode(address, type, value) {
  const a = encoder.encode(address), t = encoder.encode("," + type);
  const s = type === "s" ? encoder.encode(value) : null;
  const size = pad4(a.length + 1) + pad4(t.length + 1) + (s ? pad4(s.length + 1) : type === "d" ? 8 : 4);
  const buffer = new ArrayBuffer(size), view = new DataView(buffer), bytes = new Uint8Array(buffer);
  let at = 0;
  bytes.set(a, at); at += pad4(a.length + 1);
  bytes.set(t, at); at += pad4(t.length + 1);
  if (type === "d") view.setFloat64(at, value);
  else if (type === "i") view.setInt32(at, value);
  else if (type === "f") view.setFloat32(at, value);
  else bytes.set(s, at);
  return buffer;
}
function oscDecode(buffer) {
  const bytes = new Uint8Array(buffer), view = new DataView(buffer);
  let at = 0;
  const text = () => { let end = at; while (end < bytes.length && bytes[end]) end++;
    const s = decoder.decode(bytes.subarray(at, end)); at = pad4(end + 1); return s; };
  const address = text(), types = text();
  const t = types[1];
  const value = t === "f" ? view.getFloat32(at) : t === "i" ? view.getInt32(at) : t === "d" ? view.getFloat64(at)
              : t === "s" ? text() : null;
  return {address, value};
}
let socket = null;
const send = (address, type, value) => { if (socket && socket.readyState === 1) socket.send(oscEncode(address, type, value)); };
const sliders = {};
const statusValues = {};
function el(tag, props, parent) { const e = document.createElement(tag); Object.assign(e, props || {}); if (parent) parent.appendChild(e); return e; }
// A slider's position 0..1000 and a value: logarithmic over a positive range of more than two decades.
function scaleOf(lo, hi) {
  const log = lo > 0 && hi / lo >= 100;
  return {
    toValue: (p) => Math.min(hi, Math.max(lo, log ? lo * Math.pow(hi / lo, p / 1000) : lo + (hi - lo) * p / 1000)),
    toPosition: (v) => log ? 1000 * Math.log(v / lo) / Math.log(hi / lo) : (hi > lo ? 1000 * (v - lo) / (hi - lo) : 0)};
}
function addParam(node, parent) {
  const name = node.FULL_PATH.split("/").pop();
  const lo = node.RANGE[0].MIN, hi = node.RANGE[0].MAX, integer = node.TYPE === "i";
  const scale = scaleOf(lo, hi);
  const row = el("div", {className: "param"}, parent);
  const unit = node.UNIT && node.UNIT[0] ? " (" + node.UNIT[0] + ")" : "";
  const next = (node.TAGS || []).includes("next_film") ? " [next film]" : "";
  const label = el("label", {textContent: name + unit + next}, row);
  label.title = node.DESCRIPTION || "";
  el("small", {textContent: " " + (node.DESCRIPTION || "")}, label);
  const slider = el("input", {type: "range", min: 0, max: 1000, step: 1, name}, row);
  const number = el("input", {type: "number", min: lo, max: hi, step: integer ? 1 : "any", name: name + "_value"}, row);
  const readOnly = node.ACCESS === 1;
  slider.disabled = number.disabled = readOnly;
  const show = (v) => { number.value = integer ? v : Number(v.toPrecision(6)); slider.value = scale.toPosition(v); };
  const set = (v) => { v = integer ? Math.round(v) : v; show(v); send(node.FULL_PATH, integer ? "i" : "d", v); };
  slider.addEventListener("input", () => set(scale.toValue(Number(slider.value))));
  number.addEventListener("change", () => set(Number(number.value)));
  show(node.VALUE[0]);
  sliders[node.FULL_PATH] = {show, slider, number};
}
function addCue(name, label, danger) {
  const b = el("button", {textContent: label, id: "cue-" + name}, document.getElementById("cues"));
  if (danger) b.className = "danger";
  b.addEventListener("click", () => name === "pause" ? send("/giantbubble/pause", "i", statusValues.paused ? 0 : 1)
                                                      : send("/giantbubble/" + name, "i", 1));
}
function addPresets(node) {
  const box = document.getElementById("presets");
  const choice = el("select", {id: "preset-choice"}, box);
  for (const name of node.RANGE[0].VALS) el("option", {value: name, textContent: name}, choice);
  el("button", {textContent: "Recall", id: "preset-recall"}, box).addEventListener("click", () => {
    if (choice.value) send("/giantbubble/preset", "s", choice.value); });
  const name = el("input", {type: "text", placeholder: "preset name", id: "preset-name"}, box);
  el("button", {textContent: "Save", id: "preset-save"}, box).addEventListener("click", () => {
    if (name.value) send("/giantbubble/preset/save", "s", name.value); });
}
function showStatus() {
  const s = statusValues, f = (v, d) => v === undefined ? "-" : Number(v).toFixed(d);
  document.getElementById("status").textContent = f(s.fps, 1) + " frames/s, real time x" + f(s.realtime_factor, 2) +
    " | film: " + (s.film_state || "-") + ", " + f(s.film_area, 2) + " m2 | performer: " + (s.performer || "-") +
    (s.paused ? " | PAUSED" : "") + " | " + (s.last_event || "");
}
function listen(path) { socket.send(JSON.stringify({COMMAND: "LISTEN", DATA: path})); }
async function start() {
  const response = await fetch(withToken("/"));
  const root = await response.json();
  const show = root.CONTENTS.giantbubble.CONTENTS;
  for (const [name, label, danger] of [["dip", "Dip"], ["burst", "Burst", true], ["reset", "Reset"], ["pause", "Pause"],
       ["colouring", "Colouring"], ["camera", "Camera"], ["operator", "Overlay"]]) addCue(name, label, danger);
  addPresets(show.preset);
  const groups = {};
  for (const node of Object.values(show.param.CONTENTS)) {
    const group = (node.TAGS && node.TAGS[0]) || "Other";
    if (!groups[group]) { groups[group] = el("details", {}, document.getElementById("params"));
      el("summary", {textContent: group}, groups[group]); }
    addParam(node, groups[group]);
  }
  socket = new WebSocket(withToken((location.protocol === "https:" ? "wss://" : "ws://") + location.host + "/"));
  socket.binaryType = "arraybuffer";
  socket.onopen = () => {
    for (const name of Object.keys(show.status.CONTENTS)) listen("/giantbubble/status/" + name);
    for (const path of Object.keys(sliders)) listen(path);
    document.body.dataset.ready = "1";
  };
  socket.onmessage = (event) => {
    if (!(event.data instanceof ArrayBuffer)) return;
    const {address, value} = oscDecode(event.data);
    if (address.startsWith("/giantbubble/status/")) { statusValues[address.slice(20)] = value; showStatus(); }
    const slider = sliders[address];
    if (slider && document.activeElement !== slider.slider && document.activeElement !== slider.number) slider.show(value);
  };
  socket.onclose = () => { document.getElementById("status").textContent = "disconnected: reload the page"; };
}
start().catch((e) => { document.getElementById("status").textContent = "cannot read the show: " + e; });
</script>
</body></html>
)gbpage";
  return page;
}

}  // namespace gb
