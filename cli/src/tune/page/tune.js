"use strict";
// The page of `glint tune`: shows the frame, follows the pointer with the highlight, and sends
// every accepted change to the server, which writes it to the shot file.

const token = new URLSearchParams(location.search).get("token") || "";
const $ = (id) => document.getElementById(id);
const canvas = $("view");
const context = canvas.getContext("2d");

// What the page knows. `state` is the server's StateView at `frame`.
const page = {
  state: null,
  frame: 1,
  highlight: null, // a shot entry index (includes first)
  layer: 0,
  param: null, // the parameter path whose keys the timeline shows
  format: new URLSearchParams(location.search).get("format") === "raw" ? "raw" : "png",
  playing: false,
  finalTimer: null,
  shadeMode: false, // drags move the cel shadow's edge; the panel shows a shade entry
  shadeEntry: null, // a shot shade entry index (includes first)
  lastPick: null, // the server's answer to the last click on the model
  maskMode: false, // drags draw the rectangle of the selected layer's mask
};

// What tests and the latency benchmark read: every painted frame, with its times.
window.glintTune = { paints: 0, latencies: [], records: [], last: null, errors: 0, lastError: "" };

function overlays() {
  return {
    seams: $("overlay-seams").checked, matte: $("overlay-matte").checked, pins: $("overlay-pins").checked,
    terminator: $("overlay-terminator").checked,
  };
}

// An error stays on the page until it is dismissed or another replaces it: frames painted
// after it do not clear it.
function showError(message) {
  if (!message) return;
  const dismiss = element("button", { id: "dismiss", title: "Dismiss", onclick: clearError }, "×");
  $("status").replaceChildren(dismiss, " ", element("span", { id: "message", title: message }, message));
  window.glintTune.errors += 1;
  window.glintTune.lastError = message;
}

function clearError() {
  $("status").replaceChildren();
}

async function api(method, url, body) {
  const options = { method, headers: { "X-Glint-Token": token } };
  if (body !== undefined) {
    options.headers["Content-Type"] = "application/json";
    options.body = JSON.stringify(body);
  }
  const response = await fetch(url, options);
  if (!response.ok) {
    let message = response.status + " " + response.statusText;
    try { message = (await response.json()).error || message; } catch (_) { /* not JSON */ }
    const error = new Error(message);
    error.status = response.status;
    throw error;
  }
  return response;
}

// ---- frames -------------------------------------------------------------------------------

// An image request goes as soon as the server has answered the last one, so that the server
// starts on the newest change while the last frame is still on its way to the page and being
// painted, and never holds a queue: while one is on the server only the newest waiting request
// is kept, the others dropped. A frame that arrives after a newer one was painted is dropped
// too. A final-quality frame goes alone.
const MAX_IN_FLIGHT = 2;
let inFlight = 0;
let onServer = 0; // requests the server has not answered yet
let waiting = null;
let sent = 0; // requests sent, numbering them
let painted = 0; // the number of the newest request painted

function requestImage(kind, body, onChanges) {
  waiting = { kind, body, onChanges, asked: performance.now() };
  pump();
}

async function pump() {
  if (!waiting) return;
  const alone = waiting.body && waiting.body.quality === "final";
  if (onServer > 0 || inFlight >= (alone ? 1 : MAX_IN_FLIGHT)) return;
  const job = waiting;
  waiting = null;
  inFlight += 1;
  onServer += 1;
  const number = ++sent;
  const stale = () => number < painted;
  try {
    const url = "/api/" + job.kind + "?format=" + page.format;
    const started = performance.now();
    let response;
    try {
      response = await api("POST", url, job.body);
    } finally {
      onServer -= 1;
      pump();
    }
    if (stale()) return;
    const width = Number(response.headers.get("X-Glint-Width"));
    const height = Number(response.headers.get("X-Glint-Height"));
    const renderMs = Number(response.headers.get("X-Glint-Render-Ms"));
    const changes = response.headers.get("X-Glint-Changes");
    const stages = (response.headers.get("X-Glint-Stages") || "").split(",").join(", ");
    const times = await paint(response, width, height, stale);
    if (!times) return;
    painted = number;
    showCentres(response.headers.get("X-Glint-Centres"));
    if (changes && job.onChanges) job.onChanges(JSON.parse(changes));
    const total = performance.now() - job.asked;
    const quality = (job.body && job.body.quality) || "preview";
    window.glintTune.paints += 1;
    const frame = job.body && job.body.frame;
    // Where the time went: waiting for the request before, the server's parts, the transfer
    // (the request there and the pixels back, less the server's own time), decoding, painting.
    const serverMs = Number(response.headers.get("X-Glint-Server-Ms"));
    const encodeMs = Number(response.headers.get("X-Glint-Encode-Ms"));
    const parts = {
      waited: started - job.asked,
      render: renderMs,
      encode: encodeMs,
      server_other: Math.max(0, serverMs - renderMs - encodeMs),
      transfer: Math.max(0, times.received - started - serverMs),
      decode: times.decoded - times.received,
      paint: times.painted - times.decoded,
    };
    window.glintTune.last = { quality, frame, renderMs, totalMs: total, parts, at: performance.now() };
    if (quality === "preview") {
      // The last thousand, for the latency benchmark and tests to read.
      window.glintTune.records.push(window.glintTune.last);
      if (window.glintTune.records.length > 1000) window.glintTune.records.shift();
    }
    if (quality === "preview") window.glintTune.latencies.push(total);
    $("frame-time").textContent = `${quality} ${width}×${height}: render ${renderMs.toFixed(1)} ms (${stages}), on screen ${total.toFixed(1)} ms`;
    if (quality === "preview") scheduleFinal();
  } catch (error) {
    showError(error.message);
  } finally {
    inFlight -= 1;
    pump();
  }
}

// The canvas as large as the stage allows, its aspect kept.
function fitCanvas() {
  if (!canvas.width) return;
  const stage = $("stage").getBoundingClientRect();
  const scale = Math.min((stage.width - 20) / canvas.width, (stage.height - 60) / canvas.height);
  canvas.style.width = Math.max(1, Math.floor(canvas.width * scale)) + "px";
  const layer = $("draw-layer");
  if (layer.width !== canvas.width || layer.height !== canvas.height) {
    layer.width = canvas.width;
    layer.height = canvas.height;
  }
  layer.style.width = canvas.style.width;
  drawOverlay();
}
window.addEventListener("resize", fitCanvas);

// Paints the server's answer unless it is `stale` once decoded; when its body had arrived, was
// decoded and was painted, or null when it was not painted.
async function paint(response, width, height, stale = () => false) {
  const times = {};
  const image = await decode(response, width, height, times);
  if (stale()) {
    if (image.bitmap) image.bitmap.close();
    return null;
  }
  draw(image);
  if (image.bitmap) image.bitmap.close();
  times.painted = performance.now();
  return times;
}

// A frame's pixels from the server's answer, decoded: a bitmap of a PNG, or raw pixels.
// `times`, when given, gets when the body had arrived and when it was decoded.
async function decode(response, width, height, times = {}) {
  if (page.format === "png") {
    const blob = await response.blob();
    times.received = performance.now();
    const bitmap = await createImageBitmap(blob);
    times.decoded = performance.now();
    return { width, height, bitmap };
  }
  const bytes = await response.arrayBuffer();
  times.received = performance.now();
  const pixels = new ImageData(new Uint8ClampedArray(bytes), width, height);
  times.decoded = performance.now();
  return { width, height, pixels };
}

function draw(image) {
  if (canvas.width !== image.width || canvas.height !== image.height) {
    canvas.width = image.width;
    canvas.height = image.height;
  }
  fitCanvas();
  if (image.bitmap) {
    context.clearRect(0, 0, image.width, image.height);
    context.drawImage(image.bitmap, 0, 0);
  } else {
    context.putImageData(image.pixels, 0, 0);
  }
}

// The layer whose centres the frame marks: the selected one, while the page neither plays nor
// edits the shade. Playback leaves them out, so that its frames come as fast as it plays.
function centresOverlay() {
  const layer = currentLayer();
  if (!$("overlay-centres").checked || page.playing || page.shadeMode || !layer) return null;
  return [page.highlight, layer.index];
}

function frameBody(changes, quality) {
  const marks = Object.assign(overlays(), { centres: centresOverlay() });
  return { frame: page.frame, quality: quality || "preview", overlays: marks, changes: changes || [] };
}

// The centres a frame marked (`x,y,shown;…`): a note when the layer shows more than one, for
// a highlight seen twice on a patch is seldom what was meant.
function showCentres(header) {
  const note = $("centres-note");
  if (header === null) return;
  const centres = header === "" ? [] : header.split(";").map((c) => c.split(",").map(Number));
  window.glintTune.centres = centres;
  const shown = centres.filter((c) => c[2] === 1).length;
  note.textContent = centres.length > 1
    ? `layer ${currentLayer() ? currentLayer().index : 0} has ${centres.length} centres (${shown} in view, crossed on the frame): a highlight shows once for each`
    : "";
}

function showFrame(changes) {
  requestImage("frame", frameBody(changes));
}

// When the user pauses, the same frame at final quality.
function scheduleFinal() {
  clearTimeout(page.finalTimer);
  if (page.playing || dragging) return;
  page.finalTimer = setTimeout(() => {
    if (!inFlight && !waiting && !page.playing && !dragging) requestImage("frame", frameBody([], "final"));
  }, 600);
}

// ---- state --------------------------------------------------------------------------------

async function loadState() {
  const response = await api("GET", "/api/state?frame=" + page.frame);
  page.state = await response.json();
  const s = page.state;
  $("file").textContent = s.file;
  $("frame").min = s.frames[0];
  $("frame").max = s.frames[1];
  $("frame").value = page.frame;
  $("frame-number").value = page.frame;
  $("undo").disabled = s.undo === 0;
  $("redo").disabled = s.redo === 0;
  // Why undo is greyed out after an edit made elsewhere.
  const note = s.undo === 0 && s.redo === 0 ? s.history_note : null;
  $("history-note").textContent = note ? "history cleared" : "";
  $("history-note").title = note || "";
  $("undo").title = note || "Undo (Ctrl+Z)";
  if (s.disk_error) showError("the file does not load now: " + s.disk_error);
  if (page.highlight === null && s.highlights.length > 0) {
    const editable = s.highlights.find((h) => h.file_index !== null);
    page.highlight = (editable || s.highlights[0]).entry;
  }
  if (page.shadeEntry === null && s.shade.length > 0) {
    const editable = s.shade.find((e) => e.file_index !== null);
    page.shadeEntry = (editable || s.shade[0]).entry;
  }
  renderPanel();
  renderKeys();
}

function currentHighlight() {
  return page.state && page.state.highlights.find((h) => h.entry === page.highlight);
}

function currentLayer() {
  const h = currentHighlight();
  return h && h.layers[Math.min(page.layer, h.layers.length - 1)];
}

function currentShade() {
  return page.state && page.state.shade.find((e) => e.entry === page.shadeEntry);
}

// A layer's or a shade entry's parameters: its operations' and its own.
function allParams(layer) {
  if (!layer) return [];
  return layer.ops.flatMap((op) => op.params).concat(layer.params);
}

function findParam(path) {
  return allParams(page.shadeMode ? currentShade() : currentLayer()).find((p) => p.path === path);
}

// A change to a parameter's value at the current frame: a key where the track is keyed, the
// constant otherwise.
function valueChange(param, value) {
  if (param.keys.length > 0) return { kind: "key", path: param.path, frame: page.frame, value };
  return { kind: "set", path: param.path, value };
}

async function commit(changes) {
  try {
    await api("POST", "/api/commit", { changes });
    await loadState();
    showFrame();
  } catch (error) {
    showError(error.message);
    await loadState().catch(() => {});
    showFrame();
  }
}

// ---- panel --------------------------------------------------------------------------------

function element(tag, attributes, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes || {})) {
    if (k.startsWith("on")) e.addEventListener(k.slice(2), v);
    else if (k === "dataset") Object.assign(e.dataset, v);
    else if (v !== null && v !== undefined && v !== false) e.setAttribute(k, v === true ? "" : v);
  }
  for (const c of children) e.append(c);
  return e;
}

function isKeyedHere(param) {
  return param.keys.some((k) => Math.abs(k - page.frame) < 1e-9);
}

// A slider's position for a value and back: on a logarithmic slider (`param.log`) the position
// is log10 of the value, and a value read back keeps three significant digits.
function sliderPosition(param, value) {
  return param.log ? Math.log10(Math.max(value, param.slider[0])) : value;
}

function sliderValue(param, position) {
  return param.log ? Number(Math.pow(10, Number(position)).toPrecision(3)) : Number(position);
}

// A parameter's row: its slider, its field and its key buttons; with `why`, the reason it
// cannot be edited, as their tooltip.
function paramRow(param, editable, why) {
  const value = param.value.length > 0 ? param.value[0] : 0;
  const [low, high] = param.slider.map((v) => sliderPosition(param, v));
  // A power of ten, about a thousandth of the span, so that values stay short decimals.
  const step = Math.pow(10, Math.floor(Math.log10((high - low) / 500)));
  const range = element("input", {
    type: "range", min: low, max: high, step, value: sliderPosition(param, value),
    dataset: { path: param.path, scale: param.log ? "log" : "linear" }, disabled: !editable,
    title: why || null,
  });
  const legal = `${param.min_open ? "(" : "["}${param.min ?? "-inf"}, ${param.max ?? "inf"}${param.max_open ? ")" : "]"}`;
  const number = element("input", {
    type: "number", value: param.value.length > 0 ? String(value) : "", placeholder: "none",
    title: why || `${param.name}: any value in ${legal}`,
    step: "any", min: param.min ?? null, max: param.max ?? null,
    dataset: { number: param.path }, disabled: !editable,
  });
  const select = () => { page.param = param.path; renderKeys(); markSelected(); };
  range.addEventListener("input", () => {
    select();
    number.value = String(sliderValue(param, range.value));
    showFrame([valueChange(param, [sliderValue(param, range.value)])]);
  });
  range.addEventListener("change", () => commit([valueChange(param, [sliderValue(param, range.value)])]));
  number.addEventListener("change", () => {
    select();
    commit([valueChange(param, [Number(number.value)])]);
  });
  range.addEventListener("focus", select);
  const keyed = isKeyedHere(param);
  const key = element("button", {
    class: "key" + (keyed ? " on" : ""), title: `Key ${param.name} at this frame`,
    dataset: { key: param.path }, disabled: !editable || param.value.length === 0,
    onclick: () => { select(); commit([{ kind: "key", path: param.path, frame: page.frame, value: param.value }]); },
  }, "◆");
  const unkey = element("button", {
    class: "key", title: `Delete ${param.name}'s key at this frame`,
    dataset: { unkey: param.path }, disabled: !editable || !keyed,
    onclick: () => { select(); commit([{ kind: "delete", path: param.path, frame: page.frame }]); },
  }, "×");
  return element("div", { class: "param" + (page.param === param.path ? " selected" : ""), dataset: { row: param.path } },
    element("label", { title: param.path }, param.name), range, number, key, unkey);
}

function colourRow(param, editable) {
  const toHex = (c) => {
    const s = c <= 0.0031308 ? c * 12.92 : 1.055 * Math.pow(c, 1 / 2.4) - 0.055;
    return Math.round(Math.min(1, Math.max(0, s)) * 255).toString(16).padStart(2, "0");
  };
  const toLinear = (h) => {
    const s = parseInt(h, 16) / 255;
    return s <= 0.04045 ? s / 12.92 : Math.pow((s + 0.055) / 1.055, 2.4);
  };
  const read = (hex) => [toLinear(hex.slice(1, 3)), toLinear(hex.slice(3, 5)), toLinear(hex.slice(5, 7))];
  const picker = element("input", { type: "color", value: "#" + param.value.map(toHex).join(""), dataset: { path: param.path }, disabled: !editable });
  picker.addEventListener("input", () => showFrame([valueChange(param, read(picker.value))]));
  picker.addEventListener("change", () => commit([valueChange(param, read(picker.value))]));
  const key = element("button", {
    class: "key" + (isKeyedHere(param) ? " on" : ""), dataset: { key: param.path }, disabled: !editable,
    title: "Key the colour at this frame",
    onclick: () => commit([{ kind: "key", path: param.path, frame: page.frame, value: param.value }]),
  }, "◆");
  return element("div", { class: "param", dataset: { row: param.path } },
    element("label", {}, "colour"), picker, element("span"), key, element("span"));
}

// In shade mode: the shade entry's operations, keyed and set as a layer's are.
function renderShadePanel(box) {
  const entry = currentShade();
  if (!entry) {
    box.append(element("p", { id: "no-shade" }, "the shot has no shade entries: add one to `shade` in the shot file (docs/shot-format.md)"));
    return;
  }
  const editable = entry.file_index !== null;
  const pickEntry = element("select", { id: "shade-choice", onchange: (e) => { page.shadeEntry = Number(e.target.value); page.param = null; renderPanel(); renderKeys(); } },
    ...page.state.shade.map((x) => element("option", { value: x.entry, selected: x.entry === entry.entry }, `shade ${x.entry}: ${x.patches.join(", ")}`)));
  box.append(element("h3", {}, "shade"), pickEntry);
  if (!editable) box.append(element("p", {}, `written in ${entry.written_in}: edit it there (tune changes only the shot file)`));
  if (entry.translation === null) box.append(element("p", {}, "no Translate in this stack: add one in the shot file to drag the shadow's edge"));
  box.append(element("h3", {}, "operations on the light"));
  entry.ops.forEach((op, i) => {
    box.append(element("div", { class: "op" },
      element("div", { class: "op-head" }, element("span", { class: "name" }, `${i}. ${op.name}`)),
      ...op.params.map((p) => paramRow(p, editable))));
  });
  if (entry.params.length > 0) {
    box.append(element("h3", {}, "mask"));
    for (const p of entry.params) box.append(paramRow(p, editable));
  }
}

function renderPanel() {
  const box = $("layer");
  box.replaceChildren();
  if (page.shadeMode) {
    renderShadePanel(box);
    return;
  }
  const h = currentHighlight();
  if (!h) return;
  const editable = h.file_index !== null;
  const fileIndex = h.file_index;
  const pickHighlight = element("select", { id: "highlight-choice", onchange: (e) => { page.highlight = Number(e.target.value); page.layer = 0; page.param = null; renderPanel(); renderKeys(); showFrame(); } },
    ...page.state.highlights.map((x) => element("option", { value: x.entry, selected: x.entry === h.entry }, `highlight ${x.entry}: ${x.patches.join(", ")}`)));
  const choose = element("select", { id: "layer-choice", onchange: (e) => { page.layer = Number(e.target.value); renderPanel(); renderKeys(); showFrame(); } },
    ...h.layers.map((l) => element("option", { value: l.index, selected: l.index === page.layer }, "layer " + l.index)));
  box.append(element("h3", {}, "highlight"), pickHighlight, " ", choose);
  if (!editable) box.append(element("p", {}, `written in ${h.written_in}: edit it there (tune changes only the shot file)`));
  const layer = currentLayer();
  if (!layer) return;
  if (layer.pinned_to) box.append(element("p", {}, `pinned to ${layer.pinned_to}: dragging moves the pin`));
  // A pin solves the placing translation (the last Translate) at every frame: its α and β
  // are not the layer's to set.
  const placing = layer.pinned_to ? layer.ops.map((op) => op.name).lastIndexOf("Translate") : -1;
  const solved = `solved at every frame by the pin on ${layer.pinned_to}: drag to move the pin`;
  // Pin to the point last clicked, where this highlight is drawn; or take the pin out.
  const here = page.lastPick && page.lastPick.highlight === h.entry ? page.lastPick : null;
  const pinHere = element("button", {
    id: "pin-here", disabled: !editable || !here,
    title: here
      ? `Pin the layer to ${here.patch} at u ${here.uv[0].toFixed(3)}, v ${here.uv[1].toFixed(3)}, the point last clicked`
      : "Click the model where this highlight is drawn to pick the point to pin to",
    onclick: () => structural({ kind: "pin", patch: here.patch, u: here.uv[0], v: here.uv[1] }),
  }, "pin here");
  const unpin = element("button", {
    id: "unpin", disabled: !editable || !layer.pinned_to, title: "Take the pin out: the translation is used as written",
    onclick: () => structural({ kind: "unpin" }),
  }, "unpin");
  const structural = (change) => commit([Object.assign({ highlight: fileIndex, layer: layer.index }, change)]);
  // A pinned layer holds the shape it has at this frame while the view turns, or lets it go.
  const holds = layer.holds !== null && layer.holds !== undefined;
  const hold = element("button", {
    id: "hold", disabled: !editable || !layer.pinned_to,
    title: holds
      ? `The pin holds the shape of frame ${layer.holds}: let the shape follow the view again`
      : "Keep the shape this frame shows — its area, length and width on the surface — while the view and light change",
    onclick: () => structural({ kind: "hold", frame: holds ? null : Math.round(page.frame) }),
  }, holds ? `let go of frame ${layer.holds}'s shape` : "hold this shape");
  box.append(element("div", {}, pinHere, " ", unpin, " ", hold));
  box.append(element("h3", {}, "operations"));
  layer.ops.forEach((op, i) => {
    const head = element("div", { class: "op-head" },
      element("span", { class: "name" }, `${i}. ${op.name}`),
      element("button", { title: "Move up", disabled: !editable || i === 0, onclick: () => structural({ kind: "move_op", from: i, to: i - 1 }) }, "↑"),
      element("button", { title: "Move down", disabled: !editable || i === layer.ops.length - 1, onclick: () => structural({ kind: "move_op", from: i, to: i + 1 }) }, "↓"),
      element("button", { title: "Remove", dataset: { remove: i }, disabled: !editable, onclick: () => structural({ kind: "remove_op", index: i }) }, "✕"));
    const rows = op.params.map((p) => (i === placing ? paramRow(p, false, solved) : paramRow(p, editable)));
    box.append(element("div", { class: "op" }, head, ...rows));
  });
  const kind = element("select", { id: "op-kind" }, ...page.state.op_kinds.map((k) => element("option", { value: k }, k)));
  box.append(element("div", {}, kind, " ",
    element("button", { id: "add-op", disabled: !editable, onclick: () => structural({ kind: "insert_op", index: layer.ops.length, op: kind.value }) }, "add operation")));
  box.append(element("h3", {}, "layer"));
  for (const p of layer.params) {
    box.append(p.name === "colour" ? colourRow(p, editable) : paramRow(p, editable));
  }
  const shape = layer.shape === "keyed outline" ? `keyed outline (keys at ${layer.shape_keys.join(", ")})` : layer.shape;
  box.append(element("div", { id: "shape" }, `shape: ${shape} `,
    layer.shape === "disc" ? "" : element("button", { id: "to-disc", disabled: !editable, title: "Make the shape the disc again", onclick: () => structural({ kind: "disc" }) }, "disc")));
  box.append(element("div", {},
    layer.has_mask
      ? element("button", { id: "remove-mask", disabled: !editable, onclick: () => structural({ kind: "remove_mask" }) }, "remove mask")
      : element("button", { id: "add-mask", disabled: !editable, onclick: () => structural({ kind: "add_mask" }) }, "add mask")));
}

function markSelected() {
  for (const row of document.querySelectorAll(".param")) row.classList.toggle("selected", row.dataset.row === page.param);
}

// ---- timeline -----------------------------------------------------------------------------

function selectedKeys() {
  const p = page.param && findParam(page.param);
  if (p) return p.keys;
  const all = allParams(currentLayer()).flatMap((q) => q.keys);
  return [...new Set(all)].sort((a, b) => a - b);
}

function renderKeys() {
  const box = $("keys");
  box.replaceChildren();
  if (!page.state) return;
  const [first, last] = page.state.frames;
  const p = page.param && findParam(page.param);
  $("param-name").textContent = p ? p.name : "";
  for (const k of selectedKeys()) {
    const at = last > first ? (k - first) / (last - first) : 0;
    box.append(element("span", { style: `left: ${(at * 100).toFixed(3)}%`, dataset: { frame: k } }));
  }
}

async function goToFrame(frame) {
  const [first, last] = page.state ? page.state.frames : [frame, frame];
  page.frame = Math.min(last, Math.max(first, frame));
  $("frame").value = page.frame;
  $("frame-number").value = page.frame;
  showFrame();
  await loadState().catch((e) => showError(e.message));
}

function jumpKey(direction) {
  const keys = selectedKeys();
  const next = direction > 0 ? keys.find((k) => k > page.frame + 1e-9) : [...keys].reverse().find((k) => k < page.frame - 1e-9);
  if (next !== undefined) goToFrame(next);
}

// ---- playback -------------------------------------------------------------------------------

// Frames rendered ahead of the playhead and kept decoded, by frame, while the state they were
// rendered from (its version, the pixel format and the overlays) stays: playback shows them at
// the shot's fps, and a second time round the loop renders nothing.
const PLAYBACK_KEPT = 240;
const PLAYBACK_AHEAD = 12;
const playback = { key: null, frames: new Map() };
window.glintTune.played = []; // [frame, time] of each frame playback showed
window.glintTune.playbackRenders = 0; // frames playback asked the server for

function playbackKey() {
  return `${page.state.version} ${page.format} ${JSON.stringify(overlays())}`;
}

// The frames kept, dropped when what they were rendered from changed.
function keptFrames() {
  const key = playbackKey();
  if (playback.key !== key) {
    for (const image of playback.frames.values()) if (image.bitmap) image.bitmap.close();
    playback.frames.clear();
    playback.key = key;
  }
  return playback.frames;
}

function frameAfter(frame) {
  const [first, last] = page.state.frames;
  return frame >= last ? first : frame + 1;
}

// While playing, renders the next frames the playhead will reach that are not kept yet, one
// at a time.
async function renderAhead() {
  while (page.playing) {
    const kept = keptFrames();
    const key = playback.key;
    let frame = page.frame;
    let missing = null;
    for (let k = 0; k < PLAYBACK_AHEAD && missing === null; k++) {
      frame = frameAfter(frame);
      if (!kept.has(frame)) missing = frame;
    }
    if (missing === null) {
      await new Promise((r) => setTimeout(r, 10));
      continue;
    }
    try {
      const body = { frame: missing, quality: "preview", overlays: overlays(), changes: [] };
      const response = await api("POST", "/api/frame?format=" + page.format, body);
      const width = Number(response.headers.get("X-Glint-Width"));
      const height = Number(response.headers.get("X-Glint-Height"));
      const image = await decode(response, width, height);
      window.glintTune.playbackRenders += 1;
      if (playback.key !== key || !page.playing) {
        if (image.bitmap) image.bitmap.close();
        continue;
      }
      kept.set(missing, image);
      if (kept.size > PLAYBACK_KEPT) {
        const [oldest, dropped] = kept.entries().next().value;
        if (dropped.bitmap) dropped.bitmap.close();
        kept.delete(oldest);
      }
    } catch (error) {
      showError(error.message);
      page.playing = false;
      $("play").textContent = "play";
    }
  }
}

function play() {
  page.playing = !page.playing;
  $("play").textContent = page.playing ? "pause" : "play";
  if (!page.playing) {
    loadState().catch(() => {});
    scheduleFinal();
    return;
  }
  clearTimeout(page.finalTimer);
  renderAhead();
  const period = 1000 / page.state.fps;
  let due = performance.now();
  // Each display refresh: the next frame, once it is kept and due; a frame is due one period
  // after the one before, or at once where playback fell behind waiting for it.
  const tick = (now) => {
    if (!page.playing) return;
    const next = frameAfter(page.frame);
    const image = keptFrames().get(next);
    if (image && now >= due) {
      page.frame = next;
      $("frame").value = next;
      $("frame-number").value = next;
      draw(image);
      window.glintTune.paints += 1;
      window.glintTune.played.push([next, now]);
      window.glintTune.last = { quality: "preview", frame: next, renderMs: 0, totalMs: 0, at: now };
      due = now - due > period ? now + period : due + period;
    }
    requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
}

// ---- the pointer ----------------------------------------------------------------------------

let dragging = false;
let pressed = null;
let dragChanges = null;

function imagePosition(event) {
  const rect = canvas.getBoundingClientRect();
  return {
    x: (event.clientX - rect.left) / rect.width * canvas.width - 0.5,
    y: (event.clientY - rect.top) / rect.height * canvas.height - 0.5,
  };
}

canvas.addEventListener("pointerdown", async (event) => {
  if (drawing.on || page.maskMode) return;
  const at = imagePosition(event);
  const press = { x: at.x, y: at.y, picked: null };
  pressed = press;
  canvas.setPointerCapture(event.pointerId);
  try {
    const response = await api("POST", "/api/pick", { frame: page.frame, x: at.x, y: at.y });
    const pick = await response.json();
    // A click is over before its pick arrives: the pick still selects.
    press.picked = pick;
    page.lastPick = pick;
    const parts = pick.parts.length ? ` (${pick.parts.join(", ")})` : "";
    const where = `${pick.patch}${parts} at u ${pick.uv[0].toFixed(3)}, v ${pick.uv[1].toFixed(3)}`;
    if (page.shadeMode) {
      const light = `N·L′ ${pick.n_dot_l.toFixed(3)}`;
      if (pick.shade.length === 0) {
        $("selection").textContent = `${where}, ${light}: no shade entry`;
        return;
      }
      if (!pick.shade.includes(page.shadeEntry)) page.shadeEntry = pick.shade[pick.shade.length - 1];
      $("selection").textContent = `${where}, ${light}: shade ${page.shadeEntry}`;
      renderPanel();
      renderKeys();
      return;
    }
    if (pick.highlight === null) {
      $("selection").textContent = `${where}: no highlight`;
      return;
    }
    const before = `${page.highlight} ${page.layer}`;
    if (pick.highlight !== page.highlight) page.layer = 0;
    page.highlight = pick.highlight;
    if (pick.covering.length > 0 && !pick.covering.includes(page.layer)) page.layer = pick.covering[0];
    $("selection").textContent = `${where}: highlight ${pick.highlight}, layer ${page.layer}`;
    renderPanel();
    renderKeys();
    // Another layer's centres, unless a drag is under way and brings its own frame.
    if (before !== `${page.highlight} ${page.layer}` && !dragging) showFrame();
  } catch (error) {
    $("selection").textContent = error.message;
  }
});

canvas.addEventListener("pointermove", (event) => {
  if (drawing.on || page.maskMode || !pressed) return;
  const at = imagePosition(event);
  if (!dragging && Math.hypot(at.x - pressed.x, at.y - pressed.y) < 3) return;
  if (page.shadeMode) {
    const entry = currentShade();
    if (!entry || entry.file_index === null || !pressed.picked || !pressed.picked.shade.includes(page.shadeEntry)) return;
    dragging = true;
    clearTimeout(page.finalTimer);
    requestImage("shade_drag", {
      frame: page.frame, x: at.x, y: at.y, entry: page.shadeEntry,
      quality: "preview", overlays: overlays(),
    }, (changes) => { dragChanges = changes; showChanges(changes); });
    return;
  }
  const h = currentHighlight();
  if (!h || h.file_index === null || !pressed.picked || pressed.picked.highlight !== page.highlight) return;
  dragging = true;
  clearTimeout(page.finalTimer);
  requestImage("drag", {
    frame: page.frame, x: at.x, y: at.y, highlight: page.highlight, layer: page.layer,
    quality: "preview", overlays: overlays(),
  }, (changes) => { dragChanges = changes; showChanges(changes); });
});

// The values a drag would write, shown in the panel's fields and sliders as it goes.
function showChanges(changes) {
  for (const change of changes) {
    if (!change.path || !Array.isArray(change.value) || change.value.length !== 1) continue;
    const param = findParam(change.path);
    const number = document.querySelector(`input[data-number="${CSS.escape(change.path)}"]`);
    const range = document.querySelector(`input[type=range][data-path="${CSS.escape(change.path)}"]`);
    if (number) number.value = String(change.value[0]);
    if (range && param) range.value = String(sliderPosition(param, change.value[0]));
  }
}

async function release() {
  const was = dragging;
  pressed = null;
  dragging = false;
  if (!was) return;
  // The last drag request may still be on its way: wait for it, then write what it showed.
  while (inFlight || waiting) await new Promise((r) => setTimeout(r, 5));
  const changes = dragChanges;
  dragChanges = null;
  if (changes) await commit(changes);
}

canvas.addEventListener("pointerup", release);
canvas.addEventListener("pointercancel", release);

// ---- a mask drawn as a rectangle ----------------------------------------------------------

// In mask mode a drag on the model spans the selected layer's mask: its u and v bounds become
// those of the surface points under the drag's two corners, on one patch.
const masking = { from: null, to: null };

function setMaskMode(on) {
  if (on && drawing.on) setDrawing(false);
  if (on && page.shadeMode) setShadeMode(false);
  page.maskMode = on;
  $("mask-mode").classList.toggle("on", on);
  canvas.style.cursor = on ? "crosshair" : "";
  masking.from = masking.to = null;
  drawMaskRectangle();
}

function drawMaskRectangle() {
  const layer = $("draw-layer");
  const g = layer.getContext("2d");
  g.clearRect(0, 0, layer.width, layer.height);
  if (!masking.from || !masking.to) return;
  const scale = canvas.width / Math.max(1, canvas.getBoundingClientRect().width);
  g.lineWidth = 1.5 * scale;
  g.strokeStyle = "#ffd84a";
  const [a, b] = [masking.from, masking.to];
  g.strokeRect(Math.min(a.x, b.x) + 0.5, Math.min(a.y, b.y) + 0.5, Math.abs(b.x - a.x), Math.abs(b.y - a.y));
}

// The selected highlight and layer, where the shot file itself holds them; otherwise none, and
// the page says what to pick `to` do.
function editableLayer(to) {
  const h = currentHighlight();
  const layer = currentLayer();
  if (!h || !layer || h.file_index === null) {
    showError(`pick a highlight of the shot file ${to}`);
    return {};
  }
  return { h, layer };
}

async function pickAt(at) {
  const response = await api("POST", "/api/pick", { frame: page.frame, x: at.x, y: at.y });
  return response.json();
}

// The changes that give the layer the mask [u0, u1] × [v0, v1]: the mask added first where the
// layer has none; each bound keyed at this frame where its track has keys, set otherwise.
function maskChanges(layer, h, [u0, u1], [v0, v1]) {
  const epsilon = layer.params.find((p) => p.name === "epsilon");
  const base = epsilon.path.slice(0, -"epsilon".length);
  const changes = layer.has_mask ? [] : [{ kind: "add_mask", highlight: h.file_index, layer: layer.index }];
  const bounds = [["mask.u[0]", u0], ["mask.u[1]", u1], ["mask.v[0]", v0], ["mask.v[1]", v1]];
  for (const [name, value] of bounds) {
    const param = layer.params.find((p) => p.name === name);
    changes.push(param ? valueChange(param, [value]) : { kind: "set", path: base + name, value: [value] });
  }
  return changes;
}

async function finishMask() {
  const [from, to] = [masking.from, masking.to];
  masking.from = masking.to = null;
  drawMaskRectangle();
  if (!from || !to || Math.hypot(to.x - from.x, to.y - from.y) < 2) return;
  const { h, layer } = editableLayer("to mask its layer");
  if (!layer) return;
  try {
    const [a, b] = [await pickAt(from), await pickAt(to)];
    if (a.highlight !== h.entry || b.highlight !== h.entry) {
      showError(`both corners of a mask must be on patches of highlight ${h.entry}`);
      return;
    }
    if (a.patch !== b.patch) {
      showError(`a mask's corners must be on one patch: ${a.patch} and ${b.patch}`);
      return;
    }
    const u = [Math.min(a.uv[0], b.uv[0]), Math.max(a.uv[0], b.uv[0])];
    const v = [Math.min(a.uv[1], b.uv[1]), Math.max(a.uv[1], b.uv[1])];
    await commit(maskChanges(layer, h, u, v));
  } catch (error) {
    showError(error.message);
  }
}

canvas.addEventListener("pointerdown", (event) => {
  if (!page.maskMode) return;
  masking.from = masking.to = imagePosition(event);
  canvas.setPointerCapture(event.pointerId);
});

canvas.addEventListener("pointermove", (event) => {
  if (!page.maskMode || !masking.from) return;
  masking.to = imagePosition(event);
  drawMaskRectangle();
});

canvas.addEventListener("pointerup", () => {
  if (page.maskMode) finishMask();
});

// ---- drawing an outline ------------------------------------------------------------------

// The corners drawn so far, in image pixels (pixel centres at integers); kept after "done" so
// that they can be moved and sent again (keyed at another frame, say).
const drawing = { on: false, points: [], held: null, sent: 0 };
window.glintTune.drawing = drawing;

// How near, in image pixels, a press must be to a corner to take it.
function grabRadius() {
  const rect = canvas.getBoundingClientRect();
  return 8 * canvas.width / Math.max(1, rect.width);
}

function nearestCorner(at) {
  let best = -1;
  let distance = grabRadius();
  drawing.points.forEach((p, i) => {
    const d = Math.hypot(p.x - at.x, p.y - at.y);
    if (d <= distance) { best = i; distance = d; }
  });
  return best;
}

function drawOverlay() {
  const layer = $("draw-layer");
  const g = layer.getContext("2d");
  g.clearRect(0, 0, layer.width, layer.height);
  if (!drawing.on || drawing.points.length === 0) return;
  const scale = canvas.width / Math.max(1, canvas.getBoundingClientRect().width);
  g.lineWidth = 1.5 * scale;
  g.strokeStyle = "#ffd84a";
  g.beginPath();
  drawing.points.forEach((p, i) => (i === 0 ? g.moveTo(p.x + 0.5, p.y + 0.5) : g.lineTo(p.x + 0.5, p.y + 0.5)));
  if (drawing.points.length > 2) g.closePath();
  g.stroke();
  g.fillStyle = "#ff5fd2";
  for (const p of drawing.points) {
    g.beginPath();
    g.arc(p.x + 0.5, p.y + 0.5, 3 * scale, 0, 2 * Math.PI);
    g.fill();
  }
}

function setDrawing(on) {
  if (on && page.shadeMode) setShadeMode(false);
  if (on && page.maskMode) setMaskMode(false);
  drawing.on = on;
  drawing.held = null;
  $("draw").classList.toggle("on", on);
  $("draw-bar").hidden = !on;
  canvas.style.cursor = on ? "copy" : "";
  drawOverlay();
}

async function finishDrawing() {
  if (!drawing.on) return;
  const { layer } = editableLayer("to draw its outline");
  if (!layer) return;
  try {
    const body = {
      frame: page.frame, highlight: page.highlight, layer: layer.index,
      points: drawing.points.map((p) => [p.x, p.y]), key: $("draw-key").checked,
    };
    await api("POST", "/api/draw", body);
    drawing.sent += 1;
    await loadState();
    showFrame();
  } catch (error) {
    // Nothing was written: the frame stays as it is, the error on the page.
    showError(error.message);
  }
}

canvas.addEventListener("pointerdown", (event) => {
  if (!drawing.on) return;
  const at = imagePosition(event);
  const near = nearestCorner(at);
  if (event.shiftKey || event.button === 2) {
    if (near >= 0) drawing.points.splice(near, 1);
  } else if (near >= 0) {
    drawing.held = near;
    canvas.setPointerCapture(event.pointerId);
  } else {
    drawing.points.push(at);
  }
  drawOverlay();
});

canvas.addEventListener("pointermove", (event) => {
  if (!drawing.on || drawing.held === null) return;
  drawing.points[drawing.held] = imagePosition(event);
  drawOverlay();
});

canvas.addEventListener("pointerup", () => { drawing.held = null; });
canvas.addEventListener("contextmenu", (event) => { if (drawing.on) event.preventDefault(); });

$("draw").addEventListener("click", () => setDrawing(!drawing.on));
$("mask-mode").addEventListener("click", () => setMaskMode(!page.maskMode));
$("draw-done").addEventListener("click", finishDrawing);
$("draw-clear").addEventListener("click", () => { drawing.points = []; drawOverlay(); });
$("draw-cancel").addEventListener("click", () => setDrawing(false));

// ---- controls -----------------------------------------------------------------------------

$("frame").addEventListener("input", () => goToFrame(Number($("frame").value)));
$("frame-number").addEventListener("change", () => goToFrame(Number($("frame-number").value)));
$("prev-key").addEventListener("click", () => jumpKey(-1));
$("next-key").addEventListener("click", () => jumpKey(1));
$("play").addEventListener("click", play);
for (const id of ["overlay-seams", "overlay-matte", "overlay-pins", "overlay-terminator", "overlay-centres"]) {
  $(id).addEventListener("change", () => showFrame());
}

function setShadeMode(on) {
  if (on && drawing.on) setDrawing(false);
  if (on && page.maskMode) setMaskMode(false);
  page.shadeMode = on;
  page.param = null;
  $("shade-mode").classList.toggle("on", on);
  // The shadow's edge is what a shade drag moves: show it.
  if (on) $("overlay-terminator").checked = true;
  renderPanel();
  renderKeys();
  showFrame();
}
$("shade-mode").addEventListener("click", () => setShadeMode(!page.shadeMode));

async function history(which) {
  try {
    await api("POST", "/api/" + which);
    await loadState();
    showFrame();
  } catch (error) {
    showError(error.message);
  }
}
$("undo").addEventListener("click", () => history("undo"));
$("redo").addEventListener("click", () => history("redo"));
document.addEventListener("keydown", (event) => {
  if (event.target instanceof HTMLInputElement && event.target.type !== "range") return;
  const z = event.key === "z" || event.key === "Z";
  if ((event.ctrlKey || event.metaKey) && z) { event.preventDefault(); history(event.shiftKey ? "redo" : "undo"); }
  else if ((event.ctrlKey || event.metaKey) && event.key === "y") { event.preventDefault(); history("redo"); }
  else if (event.key === " " && !(event.target instanceof HTMLInputElement)) { event.preventDefault(); play(); }
  else if ((event.key === "d" || event.key === "D") && !event.ctrlKey && !event.metaKey && !(event.target instanceof HTMLInputElement)) setDrawing(!drawing.on);
  else if ((event.key === "s" || event.key === "S") && !event.ctrlKey && !event.metaKey && !(event.target instanceof HTMLInputElement)) setShadeMode(!page.shadeMode);
  else if ((event.key === "m" || event.key === "M") && !event.ctrlKey && !event.metaKey && !(event.target instanceof HTMLInputElement)) setMaskMode(!page.maskMode);
  else if (event.key === "Enter" && drawing.on) { event.preventDefault(); finishDrawing(); }
  else if (event.key === "Escape" && drawing.on) setDrawing(false);
  else if (event.key === "Backspace" && drawing.on && drawing.points.length > 0) { event.preventDefault(); drawing.points.pop(); drawOverlay(); }
});

// Changes made elsewhere (a text editor saving the file) arrive here.
async function follow(version) {
  for (;;) {
    try {
      const response = await api("GET", "/api/wait?version=" + version);
      const next = (await response.json()).version;
      if (next !== version) {
        version = next;
        if (!page.state || page.state.version !== next) {
          await loadState();
          showFrame();
        }
      }
    } catch (error) {
      showError("the server stopped: " + error.message);
      await new Promise((r) => setTimeout(r, 2000));
    }
  }
}

(async () => {
  try {
    await loadState();
    if (page.frame !== page.state.frames[0]) {
      page.frame = page.state.frames[0];
      await loadState();
    }
    showFrame();
    follow(page.state.version);
  } catch (error) {
    showError(error.message);
  }
})();
