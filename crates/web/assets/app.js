// loomkin workbench: the views and their wiring to the JSON API. Written for loomkin.
(() => {
"use strict";

const { Chart, PALETTE, fmtValue } = window.LoomkinCharts;
const $ = (sel) => document.querySelector(sel);

// State visible to tests and to the console.
const loomkin = (window.loomkin = { ready: false, evalCount: 0, busy: false, charts: {}, errors: [] });
window.addEventListener("error", (e) => loomkin.errors.push(String(e.message)));
window.addEventListener("unhandledrejection", (e) => loomkin.errors.push(String(e.reason)));
// Per view, the field the page itself refused ({input}), until it is corrected: see refuseField.
const refusals = {};

// ---------------------------------------------------------------- API and status

// Every request can be cancelled: one that lasts over PROGRESS_AFTER_MS shows a progress line
// (what runs, for how long, against the server's time budget from /api/info) with a cancel button
// that aborts it; the server stops the computation when its client goes away.
const PROGRESS_AFTER_MS = 500;
const running = new Set(); // {path, t0, ctl}
let progressTimer = null;

async function api(path, body) {
  const ctl = new AbortController();
  const job = { path, t0: performance.now(), ctl };
  const init = body === undefined ? { signal: ctl.signal } : { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify(body), signal: ctl.signal };
  running.add(job);
  if (!progressTimer) progressTimer = setInterval(showProgress, 200);
  try {
    let res;
    try {
      res = await fetch("/api" + path, init);
    } catch (e) {
      if (ctl.signal.aborted) {
        const err = new Error("cancelled");
        err.cancelled = true;
        throw err;
      }
      throw e;
    }
    let data = null;
    try { data = await res.json(); } catch (_) { /* not JSON */ }
    if (!res.ok) {
      const msg = data && data.error ? data.error : `${res.status} ${res.statusText}`;
      const err = new Error(msg);
      err.field = data && data.field;
      throw err;
    }
    return data;
  } finally {
    running.delete(job);
    showProgress();
  }
}

// The newest request of each kind that a late answer could overwrite (a view's search, the law
// chosen, a comparison): `const current = newest("loom-stagger")` as one is sent; current() stays
// true until another of that kind is sent, or the kind is dropped (`newest.drop(kind)`: the state it
// was asked for is gone, e.g. another loom chosen). An answer, or a refusal, that is no longer
// current is not shown: it would replace the page's newer state, or send its own state's values
// with it (the Shedding view's law, 746bbb6, was the first such race).
const askedCount = {};
function newest(kind) {
  const n = (askedCount[kind] = (askedCount[kind] || 0) + 1);
  return () => askedCount[kind] === n;
}
newest.drop = (kind) => { askedCount[kind] = (askedCount[kind] || 0) + 1; };

// The progress line of the longest-running request, if it has run over PROGRESS_AFTER_MS.
function showProgress() {
  let box = $("#progress");
  if (!box) {
    box = el("div", { id: "progress", hidden: true }, el("span", { id: "progress-text" }), el("progress", { id: "progress-bar", max: 1, value: 0 }),
      el("button", { type: "button", id: "progress-cancel", textContent: "cancel", title: "stop this computation" }));
    box.setAttribute("role", "status");
    box.querySelector("button").addEventListener("click", () => { const j = longest(); if (j) j.ctl.abort(); });
    document.body.append(box);
  }
  const j = longest();
  if (!j) {
    box.hidden = true;
    if (!running.size && progressTimer) { clearInterval(progressTimer); progressTimer = null; }
    return;
  }
  const s = convert(performance.now() - j.t0, "ms", "s"), budget = loomkin.limits && loomkin.limits.heavy_budget_s;
  box.hidden = false;
  $("#progress-text").textContent = `computing ${j.path.replace(/^\//, "")}: ${s.toFixed(0)} s` + (budget ? ` (stopped after ${budget} s)` : "");
  $("#progress-bar").value = budget ? Math.min(1, s / budget) : 0;
}

function longest() {
  let best = null;
  for (const j of running) if (performance.now() - j.t0 > PROGRESS_AFTER_MS && (!best || j.t0 < best.t0)) best = j;
  return best;
}

function status(text, isError) {
  // A value the page refused stays the news until it is corrected (an answer to an earlier state may
  // still arrive).
  if (!isError && refusals[currentView]) return;
  const el = $("#status");
  el.textContent = text || "";
  el.className = isError ? "error" : "";
}

// Saves a file (through LoomkinCharts.download, which tests can watch).
function download(filename, text, type) {
  window.LoomkinCharts.download(filename, text, type);
}

function el(tag, props, ...children) {
  const e = document.createElement(tag);
  Object.assign(e, props || {});
  for (const c of children) e.append(c);
  return e;
}

function num(v, digits) {
  if (!isFinite(v)) return "–";
  if (digits === undefined) return fmtValue(v);
  const t = v.toFixed(digits);
  return /^-0(\.0*)?$/.test(t) ? t.slice(1) : t; // never "-0.0"
}

// ---------------------------------------------------------------- the request schemas

// GET /api/schema: the JSON Schema of every request the API checks, with the library's ranges.
// Every numeric field takes its min and max (and, where the schema has one, its first value) from
// it: the page writes no bound of its own. A slider beside a field moves over a view span of the
// page's choosing; the field takes whatever the library allows (docs/design/schema.md).
let schemas = {};
// The display units and their factors (`units` of GET /api/schema, from loomkin_units): the page
// converts with these and writes no factor of its own.
let units = {};

async function loadSchemas() {
  try { const s = await api("/schema"); schemas = s.routes; units = s.units; } catch (e) { status("schema: " + e.message, true); }
  loomkin.schemas = schemas;
}

// `v` in unit `from` converted to unit `to` ("m" to "mm"), by the schema's unit factors: a display
// unit is multiplied by its factor, the API's unit divided (as loomkin_units' m_from_mm).
function convert(v, from, to) {
  if (from === to) return v;
  const u = units[to], w = units[from];
  if (u && u.of === from) return v * u.factor;
  if (w && w.of === to) return v / w.factor;
  loomkin.errors.push(`no unit factor from ${from} to ${to}`);
  return NaN;
}

// The schema of the request key at `path` ("design.roller_radius_mm"; "motions_deg[]" for the
// items of an array) of a route's request, its $refs and optional (anyOf … null) resolved.
function schemaAt(route, path) {
  const r = schemas[route];
  if (!r) return null;
  const root = r.request;
  const deref = (s) => {
    for (let i = 0; s && i < 16; i++) {
      if (s.$ref) s = root.$defs[s.$ref.split("/").pop()];
      else if (s.anyOf) s = s.anyOf.find((x) => x.type !== "null");
      else break;
    }
    return s;
  };
  let s = deref(root);
  for (const key of path.split(".")) {
    const items = key.endsWith("[]");
    s = deref(s && s.properties && s.properties[items ? key.slice(0, -2) : key]);
    if (items) s = deref(s && s.items);
    if (!s) return null;
  }
  return s;
}

// The limits of a numeric request key: {min, max, minOpen, maxOpen, unit, default} (min or max
// undefined on a side without a bound).
function limitsOf(route, path) {
  const s = schemaAt(route, path);
  if (!s) return null;
  return {
    min: s.minimum !== undefined ? s.minimum : s.exclusiveMinimum, minOpen: s.exclusiveMinimum !== undefined,
    max: s.maximum !== undefined ? s.maximum : s.exclusiveMaximum, maxOpen: s.exclusiveMaximum !== undefined,
    unit: s["x-unit"] || "", default: s.default,
  };
}

// Sets a numeric input's min and max from the schema (an open side also as data-min-open /
// data-max-open), and its value from the schema's default when it has none; `unit` is the field's
// unit when it is not the request key's (a field in mm of a key in m: data-unit, the limits
// converted by the schema's unit factors). Returns the limits.
function applyLimits(input, route, path, unit) {
  const l = limitsOf(route, path);
  if (!l) { loomkin.errors.push(`no schema for ${route} ${path}`); return null; }
  const k = unit ? convert(1, l.unit, unit) : 1;
  if (unit) input.dataset.unit = unit;
  const text = (v) => String(+(v * k).toPrecision(12));
  input.removeAttribute("min"); input.removeAttribute("max");
  if (l.min !== undefined) input.min = text(l.min);
  if (l.max !== undefined) input.max = text(l.max);
  input.dataset.minOpen = String(l.minOpen);
  input.dataset.maxOpen = String(l.maxOpen);
  input.dataset.schema = `${route} ${path}`;
  if (input.value === "" && typeof l.default === "number") input.value = text(l.default);
  return l;
}

// Whether a typed value lies outside an input's min and max (open sides excluded).
function outOfLimits(input, v) {
  if (!isFinite(v)) return true;
  const lo = input.min === "" ? -Infinity : +input.min, hi = input.max === "" ? Infinity : +input.max;
  const loOpen = input.dataset.minOpen === "true", hiOpen = input.dataset.maxOpen === "true";
  return (loOpen ? v <= lo : v < lo) || (hiOpen ? v >= hi : v > hi);
}

// "0 < label ≤ 1000 mm": an input's limits in words.
function limitsText(input, label, unit) {
  const lo = input.min === "" ? null : input.min, hi = input.max === "" ? null : input.max;
  const l = lo === null ? "" : `${lo} ${input.dataset.minOpen === "true" ? "<" : "≤"} `;
  const h = hi === null ? "" : ` ${input.dataset.maxOpen === "true" ? "<" : "≤"} ${hi}`;
  return `${l}${label}${h}${unit ? " " + unit : ""}`;
}

// ---------------------------------------------------------------- shared pieces for every view

// A slider with a numeric field beside it; both edit one value. The slider moves in `step` over
// the view span [min, max]; the field takes any value (e.g. 15.5 mm of strap play) within the
// schema's limits of the request key `limits` = {route, path} (or the view span without one), also
// beyond the slider's span (the slider then rests at its end). onInput(v) on every move or typed
// value; onCommit(v) when an edit ends (slider released, field changed): record it for undo.
// Returns {label, range, field, set(v)}; set shows a value without calling back.
function sliderWithNumber(id, label, unit, min, max, step, value, onInput, onCommit, limits) {
  const range = el("input", { type: "range", min: String(min), max: String(max), step: String(step), value: String(value), id: id + "-range" });
  const field = el("input", { type: "number", min: String(min), max: String(max), step: "any", value: String(value), id, className: "short" });
  if (limits) applyLimits(field, limits.route, limits.path);
  field.setAttribute("aria-label", `${label} (${unit})`);
  range.addEventListener("input", () => { field.value = range.value; field.classList.remove("bad"); onInput(+range.value); });
  range.addEventListener("change", () => { if (onCommit) onCommit(+range.value); });
  field.addEventListener("change", () => {
    // The field's own bounds (the schema's, or the slider's as it has them now: a view may change
    // its span, e.g. a 720° cycle).
    const v = +field.value;
    if (field.value === "" || outOfLimits(field, v)) {
      const allowed = limits ? limitsText(field, label, unit) : `${field.min} … ${field.max} ${unit}`;
      const typed = field.validity && field.validity.badInput ? "not a number" : field.value || "(empty)";
      refuseField("", field, `${label}: ${typed} is out of range: allowed ${allowed}`);
      return;
    }
    field.classList.remove("bad");
    acceptField(field);
    range.value = String(v);
    onInput(v);
    if (onCommit) onCommit(v);
  });
  const set = (v) => { range.value = String(v); field.value = String(v); field.classList.remove("bad"); };
  // A new upper end of the slider's span (and of the field's, when the schema does not bound it).
  const setMax = (v) => { range.max = String(v); if (!limits) field.max = String(v); };
  return { setMax, label: el("label", { className: "slider" }, el("span", { textContent: `${label} (${unit})` }), el("div", { className: "num-slider" }, range, field)), range, field, set };
}

// Marks the inputs a refused request names (error.field, a JSON path such as
// "design.points[2]"), writes the message beside them (the header scrolls away) and in the header,
// and marks the view's charts stale: they keep the last valid result until a request succeeds.
// A table row is named as the table shows it, counted from 1 ("row 3 y", never
// "design.points[2][1]"). fields(path) → {inputs: [elements], row?: <tr>, rowNumber?: n,
// label?: text} or null.
function showFieldError(prefix, e, fields) {
  if (e.cancelled) { status((prefix ? prefix + ": " : "") + "cancelled"); return; }
  clearFieldErrors();
  let msg = e.message;
  const hit = e.field && fields ? fields(e.field) : null;
  if (hit) {
    for (const i of hit.inputs || []) if (i) i.classList.add("bad", "bad-api");
    if (hit.row) hit.row.classList.add("bad", "bad-api");
    let name = hit.label;
    if (hit.rowNumber) {
      // The API counts from 0 and may name a cell ("[2][1]": row 3, second column).
      const cell = /\]\[(\d+)\]$/.exec(e.field);
      name = `row ${hit.rowNumber}` + (cell && hit.columns ? ` ${hit.columns[+cell[1]]}` : "");
    }
    if (name) {
      msg = msg.split(e.field).join(name);
      if (!msg.startsWith(name)) msg = `${name}: ` + msg.replace(/^[\w.\[\]]+:\s*/, "");
    }
    const at = (hit.inputs || []).find((i) => i);
    if (at) fieldNote(at, msg);
  }
  markStale(true);
  status((prefix ? prefix + ": " : "") + msg, true);
}

// A refusal made by the page itself (a value that is not a number, out of the schema's limits):
// shown as a refused request's is, nothing is sent, and it stays shown (answers to earlier states
// that arrive meanwhile do not clear it) until the field is corrected (acceptField) or the state
// replaced (undo, redo, the address): see refusals.
function refuseField(prefix, input, message) {
  const e = new Error(message);
  e.field = "(page)";
  delete refusals[currentView];
  showFieldError(prefix, e, () => ({ inputs: [input] }));
  // Marked "bad" but not "bad-api": a value never recorded, which Ctrl+Z takes back first (undo).
  input.classList.remove("bad-api");
  refusals[currentView] = { input };
}

// The state shown is replaced (undo, redo, the address): a value the page refused is dropped with it.
function dropRefusal(view) {
  if (refusals[view]) refusals[view].input.classList.remove("bad");
  delete refusals[view];
  clearFieldErrors();
}

// A field holds a valid value again: its refusal, if any, is over.
function acceptField(input) {
  for (const v of Object.keys(refusals)) if (refusals[v].input === input) delete refusals[v];
}

// The message of a refused field, written just below it (below its table, for a table cell).
function fieldNote(input, text) {
  const anchor = input.closest("table") || input.closest(".num-slider") || input;
  let note = anchor.nextElementSibling;
  if (!note || !note.classList.contains("field-msg")) {
    note = el("small", { className: "field-msg" });
    note.setAttribute("role", "alert");
    anchor.insertAdjacentElement("afterend", note);
  }
  note.textContent = text;
}

// Marks (or clears) the charts of the view shown as stale: dimmed, with a note that they show the
// last valid result.
function markStale(on) {
  if (!currentView) return;
  for (const c of document.querySelectorAll(`#view-${currentView} .chart`)) c.classList.toggle("stale", on);
}

function clearFieldErrors() {
  if (refusals[currentView]) return;
  for (const x of document.querySelectorAll(".bad-api")) x.classList.remove("bad", "bad-api");
  // (A refusal of another view stays at its field until that view is shown and corrected.)
  for (const x of document.querySelectorAll(".field-msg")) if (!refusals[(x.closest(".view") || { id: "" }).id.replace(/^view-/, "")]) x.remove();
  markStale(false);
}

// The numbers of a list typed in a text field ("600, 750"), or null after refusing the field with
// the first entry that is not a number, named by its place in the list.
function numberList(prefix, input, label) {
  const words = input.value.split(/[,;\s]+/).filter((t) => t);
  const bad = words.findIndex((t) => !isFinite(Number(t)));
  if (bad >= 0) {
    refuseField(prefix, input, `${label}: entry ${bad + 1} ('${words[bad]}') is not a number`);
    return null;
  }
  if (!words.length) {
    refuseField(prefix, input, `${label}: give at least one number`);
    return null;
  }
  input.classList.remove("bad");
  acceptField(input);
  return words.map(Number);
}

// A number typed in a field, or null after refusing the field ("not a number" or "empty").
function numberIn(prefix, input, label) {
  const v = parseFloat(input.value);
  if (input.value.trim() !== "" && isFinite(v)) { input.classList.remove("bad"); acceptField(input); return v; }
  const why = input.validity && input.validity.badInput ? "is not a number" : input.value.trim() === "" ? "is empty" : `'${input.value}' is not a number`;
  refuseField(prefix, input, `${label}: ${why}`);
  return null;
}

// ---------------------------------------------------------------- undo, redo and the URL

// Each view keeps a history of its states (JSON snapshots): undo and redo walk it, and the state
// shown is written into the address, "#view/<state>", so that back, forward, reload and a shared
// link bring it back. A view calls
//   const h = viewHistory("servo", get, set);  // get(): the state; set(state): show it
//   h.ready();    // once its first state is shown: takes the state from the address if any
//   h.commit();   // after every edit (drag end, field changed, button)
const histories = {};
let currentView = null;

function encodeState(obj) {
  const bytes = new TextEncoder().encode(JSON.stringify(obj));
  let bin = "";
  for (const b of bytes) bin += String.fromCharCode(b);
  return btoa(bin).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}

function decodeState(text) {
  const bin = atob(text.replace(/-/g, "+").replace(/_/g, "/"));
  return JSON.parse(new TextDecoder().decode(Uint8Array.from(bin, (c) => c.charCodeAt(0))));
}

// "#view/state" → {view, state (text or null)}.
function parseHash(hash) {
  const h = (hash || "").replace(/^#/, "");
  const k = h.indexOf("/");
  return k < 0 ? { view: h, state: null } : { view: h.slice(0, k), state: h.slice(k + 1) || null };
}

function viewHistory(view, get, set) {
  const h = {
    states: [], at: -1, isReady: false,
    snapshot() { return JSON.stringify(get()); },
    // Records the state now shown (if it differs from the last one) and writes the address.
    commit(replace) {
      // A state holding a value the page refused is not recorded (Ctrl+Z first takes the value back).
      if (!h.isReady || refusals[view]) return;
      const snap = h.snapshot();
      if (snap !== h.states[h.at]) {
        h.states = h.states.slice(0, h.at + 1);
        h.states.push(snap);
        if (h.states.length > 200) h.states.shift();
        h.at = h.states.length - 1;
      }
      writeHash(view, replace);
      updateHistoryButtons();
    },
    undo() { if (h.at > 0) { h.at--; h.apply(); } },
    redo() { if (h.at < h.states.length - 1) { h.at++; h.apply(); } },
    apply() {
      dropRefusal(view);
      set(JSON.parse(h.states[h.at]));
      writeHash(view, false);
      updateHistoryButtons();
    },
    // A state from the address (back, forward, a typed or reloaded URL): shown and recorded.
    fromHash(text) {
      let state;
      try { state = decodeState(text); } catch (_) { status(`address: the ${view} state in the URL cannot be read; kept the one shown`, true); return; }
      if (JSON.stringify(state) === h.states[h.at]) return;
      dropRefusal(view);
      set(state);
      const snap = h.snapshot();
      h.states = h.states.slice(0, h.at + 1);
      h.states.push(snap);
      h.at = h.states.length - 1;
      updateHistoryButtons();
    },
    ready() {
      h.isReady = true;
      const p = parseHash(location.hash);
      if (p.view === view && p.state) h.fromHash(p.state);
      else h.commit(true);
      if (h.at < 0) h.commit(true);
    },
    current() { return get(); },
  };
  histories[view] = h;
  loomkin.histories[view] = h;
  return h;
}

function writeHash(view, replace) {
  if (view !== currentView) return;
  const h = histories[view];
  const hash = "#" + view + (h && h.at >= 0 ? "/" + encodeState(JSON.parse(h.states[h.at])) : "");
  if (location.hash === hash) return;
  if (replace) history.replaceState(null, "", hash); else history.pushState(null, "", hash);
}

function updateHistoryButtons() {
  const h = histories[currentView];
  $("#undo").disabled = !h || h.at <= 0;
  $("#redo").disabled = !h || h.at >= h.states.length - 1;
}

function undo() {
  const h = histories[currentView];
  if (!h) return;
  // A value the page refused before recording it (a numeric field out of range) is undone first:
  // the state shown is put back, then the next Ctrl+Z steps back through the history.
  const view = document.querySelector("#view-" + currentView);
  if (view && view.querySelector("input.bad:not(.bad-api)") && h.at >= 0) { h.apply(); return; }
  h.undo();
}

// A length the page takes in mm while the API takes m: checked here against the input's limits
// (the schema's, scaled to mm by applyLimits), so that a refusal names the field in the unit it is
// typed in (the API's message would give metres).
function mmRefused(prefix, input, label, value) {
  if (input.value !== "" && !outOfLimits(input, value)) { acceptField(input); return false; }
  refuseField(prefix, input, `${label}: ${input.value || "(empty)"} mm is out of range: allowed ${limitsText(input, label, "mm")}`);
  return true;
}

function redo() {
  const h = histories[currentView];
  if (h) h.redo();
}

document.addEventListener("keydown", (e) => {
  if (!(e.ctrlKey || e.metaKey) || e.altKey) return;
  const k = e.key.toLowerCase();
  if (k !== "z" && k !== "y") return;
  e.preventDefault();
  // A field being typed into ends its edit first (its change is recorded), then the undo.
  const a = document.activeElement;
  if (a && a !== document.body && a.blur) a.blur();
  if (k === "y" || e.shiftKey) redo(); else undo();
});

// ---------------------------------------------------------------- the loom-and-pattern picker

// Longest loaded file (characters) carried in the page's address: a WIF draft of 1000 picks on 24
// shafts is about 40 000; browsers take addresses of a few MB, but links this long break in mail.
const LINK_MAX_CHARS = 200000;
// Colours for up to 24 heald frames (front frame first), the same in every view.
const FRAME_COLOURS = ["#1d4ed8", "#dc2626", "#16a34a", "#9333ea", "#ea580c", "#0891b2", "#be123c", "#4d7c0f",
  "#7c3aed", "#b45309", "#0f766e", "#db2777", "#2563eb", "#b91c1c", "#15803d", "#a21caf", "#c2410c", "#0e7490",
  "#9f1239", "#65a30d", "#6d28d9", "#92400e", "#115e59", "#be185d"];

// The loom file and weave pattern of the views that run a loom (loom, insertion, servo shedding):
// the examples, or a loaded loom file (TOML) and pattern (WIF draft or lift plan). `ids` names the
// two selects and the two file inputs (each file input's label is its id + "-label"); `first` is the
// example shown first; `changed()` runs after the user picks or loads something.
//
// A loaded file travels in the view's state (so in the address, and a shared link reopens it) up
// to LINK_MAX_CHARS; a larger one stays in the page, the link shows the first example (or plain
// weave), and the page says so beside the file's name.
function loomPatternPicker(ex, ids, first, changed) {
  const p = { loomText: null, loomName: null, patternText: null, patternKind: null, patternName: null };
  const loomSel = el("select", { id: ids.loom });
  for (const l of ex.looms) loomSel.append(el("option", { value: l.name, textContent: l.name }));
  loomSel.append(el("option", { value: "upload", textContent: "a loom file (TOML) …" }));
  if (ex.looms.some((l) => l.name === first)) loomSel.value = first;
  const firstLoom = loomSel.value;
  const patSel = el("select", { id: ids.pattern });
  patSel.append(el("option", { value: "plain-default", textContent: "plain weave on the loom's frames" }));
  for (const x of ex.patterns) patSel.append(el("option", { value: x.name, textContent: x.name }));
  patSel.append(el("option", { value: "upload", textContent: "a WIF draft or lift plan …" }));
  const loomFile = el("input", { type: "file", accept: ".toml,text/plain", id: ids.loomUpload });
  const patFile = el("input", { type: "file", accept: ".wif,.txt,text/plain", id: ids.patternUpload });
  const loomName = el("span", { className: "hint" }), patName = el("span", { className: "hint" });
  const loomLabel = el("label", { className: "file", hidden: true, id: ids.loomUpload + "-label" }, "load…", loomFile);
  const patLabel = el("label", { className: "file", hidden: true, id: ids.patternUpload + "-label" }, "load…", patFile);
  const showLabels = () => { loomLabel.hidden = loomSel.value !== "upload"; patLabel.hidden = patSel.value !== "upload"; };
  const tooLarge = (text) => (text && text.length > LINK_MAX_CHARS ? ` (${text.length} characters: too large for the page's address, a link to this state opens ` : "");
  const names = () => {
    loomName.textContent = (p.loomName || "") + (tooLarge(p.loomText) && `${tooLarge(p.loomText)}${firstLoom})`);
    patName.textContent = (p.patternName || "") + (tooLarge(p.patternText) && `${tooLarge(p.patternText)}plain weave)`);
  };
  loomSel.addEventListener("change", () => {
    showLabels();
    if (loomSel.value === "upload" && !p.loomText) { loomFile.click(); return; }
    changed();
  });
  patSel.addEventListener("change", () => {
    showLabels();
    if (patSel.value === "upload" && !p.patternText) { patFile.click(); return; }
    changed();
  });
  loomFile.addEventListener("change", async () => {
    const f = loomFile.files[0]; if (!f) return;
    p.loomText = await f.text(); p.loomName = f.name; loomSel.value = "upload";
    names(); showLabels(); changed();
  });
  patFile.addEventListener("change", async () => {
    const f = patFile.files[0]; if (!f) return;
    p.patternText = await f.text(); p.patternKind = /\.wif$/i.test(f.name) || /^\s*\[WIF\]/im.test(p.patternText) ? "wif" : "lift_plan";
    p.patternName = f.name; patSel.value = "upload";
    names(); showLabels(); changed();
  });
  const carried = (text, name, extra) => (text && text.length <= LINK_MAX_CHARS ? { name, text, ...extra } : undefined);
  Object.assign(p, {
    loomSel, patSel,
    // The panel's rows: each select with its load button and the loaded file's name.
    nodes: [
      el("label", { className: "wide" }, "loom file", loomSel), el("div", { className: "row wrap" }, loomLabel, loomName),
      el("label", { className: "wide" }, "weave pattern", patSel), el("div", { className: "row wrap" }, patLabel, patName),
    ],
    // The picker's part of the view's state.
    state() {
      const st = {
        loom: loomSel.value === "upload" && !p.loomText ? firstLoom : loomSel.value,
        pattern: patSel.value === "upload" && !p.patternText ? "plain-default" : patSel.value,
      };
      if (st.loom === "upload") st.loom_file = carried(p.loomText, p.loomName);
      if (st.pattern === "upload") st.pattern_file = carried(p.patternText, p.patternName, { kind: p.patternKind });
      names();
      return st;
    },
    // Sets the picker from a state; true when the loom or the pattern changed.
    restore(st) {
      if (st.loom === "upload" && st.loom_file) { p.loomText = st.loom_file.text; p.loomName = st.loom_file.name; }
      if (st.pattern === "upload" && st.pattern_file) {
        p.patternText = st.pattern_file.text; p.patternKind = st.pattern_file.kind === "wif" ? "wif" : "lift_plan";
        p.patternName = st.pattern_file.name;
      }
      const pick = (sel, v, ok, fallback) => { sel.value = v; if (sel.value !== v || (v === "upload" && !ok)) sel.value = fallback; };
      const before = loomSel.value + "\n" + patSel.value;
      pick(loomSel, st.loom, !!p.loomText, firstLoom);
      pick(patSel, st.pattern, !!p.patternText, "plain-default");
      names(); showLabels();
      return loomSel.value + "\n" + patSel.value !== before;
    },
    // The request's loom file (`loom_toml`) and pattern (`{wif}` or `{lift_plan}`; none: plain weave).
    source(q) {
      if (loomSel.value === "upload") { if (p.loomText) q.loom_toml = p.loomText; }
      else q.loom_toml = ex.looms.find((l) => l.name === loomSel.value).text;
      const pv = patSel.value;
      if (pv === "upload") { if (p.patternText) q.pattern = { [p.patternKind]: p.patternText }; }
      else if (pv !== "plain-default") {
        const text = ex.patterns.find((x) => x.name === pv).text;
        q.pattern = /\.wif$/.test(pv) ? { wif: text } : { lift_plan: text };
      }
      return q;
    },
  });
  return p;
}

Object.assign(loomkin, { histories: {}, undo, redo, encodeState, decodeState });
window.LoomkinShared = { sliderWithNumber, showFieldError, clearFieldErrors, refuseField, numberIn, numberList, viewHistory, download, api, newest, status, el, num, applyLimits, loomPatternPicker, FRAME_COLOURS };

// ---------------------------------------------------------------- tabs

const VIEW_TITLES = { servo: "Servo law", catalogue: "Law catalogue", shed: "Shedding", picking: "Picking", dobby: "Dobby", dynamics: "Dynamics" };
const initialised = {};

// Shows a view; `fromAddress` when the address already names it (no new history entry).
function showView(name, fromAddress) {
  if (!document.querySelector(`#tabs button[data-view="${name}"]`)) return;
  currentView = name;
  loomkin.view = name;
  for (const b of document.querySelectorAll("#tabs button")) b.setAttribute("aria-selected", String(b.dataset.view === name));
  for (const s of document.querySelectorAll(".view")) s.hidden = s.id !== "view-" + name;
  if (!initialised[name] && VIEWS[name]) { initialised[name] = true; VIEWS[name](); }
  for (const c of Object.values(loomkin.charts)) c.draw();
  if (!fromAddress) writeHash(name, false);
  else if (histories[name] && !parseHash(location.hash).state) writeHash(name, true);
  updateHistoryButtons();
}

// The address changed (typed, back, forward): switch view and take its state.
function onAddress() {
  const p = parseHash(location.hash);
  if (!p.view) return;
  if (p.view !== currentView) showView(p.view, true);
  const h = histories[p.view];
  if (h && h.isReady && p.state) h.fromHash(p.state);
}
window.addEventListener("hashchange", onAddress);
window.addEventListener("popstate", onAddress);

// ---------------------------------------------------------------- servo law editor

const DRIVE_FIELDS = [
  ["stroke_m", "stroke H", "m"],
  ["motion_angle_deg", "motion angle", "°"],
  ["moving_mass_kg", "moving mass m", "kg"],
  ["pinion_radius_m", "pinion radius r", "m"],
  ["gear_ratio", "gear ratio i", "–"],
  ["motor_inertia_kg_m2", "motor inertia Jm", "kg·m²"],
  ["spring_n_m", "spring rate k", "N/m"],
  ["spring_preload_n", "spring preload Fpre", "N"],
  ["damping_n_s_m", "damping c", "N·s/m"],
  ["constant_force_n", "constant force Fc", "N"],
  ["efficiency", "efficiency η", "–"],
  ["return_angle_deg", "return angle", "°", "= motion angle"],
  ["dwell_after_rise_deg", "dwell after rise", "°", "half the rest"],
];
const MIN_GAP = 0.002;
const servo = { design: null, result: null, inflight: false, queued: false };
loomkin.design = () => servo.design;

function initServo() {
  const editor = new Chart($("#servo-editor-chart"), {
    id: "editor", title: "Acceleration shape — drag the points", height: 300,
    x: { label: "x = fraction of motion angle", unit: "–", range: [0, 1] },
    y: { label: "spline f", unit: "def. units", range: [-1.25, 1.25] },
  });
  const torque = new Chart($("#servo-torque-chart"), {
    id: "torque", title: "Motor torque over one turn (rise from 0°)", height: 240,
    x: { label: "main-shaft angle φ", unit: "°", range: [0, 360], step: 30 }, y: { label: "torque M", unit: "N·m", includeZero: true },
  });
  const power = new Chart($("#servo-power-chart"), {
    id: "power", title: "Motor power over one turn", height: 200,
    x: { label: "main-shaft angle φ", unit: "°", range: [0, 360], step: 30 }, y: { label: "power P", unit: "W", includeZero: true },
  });
  const rack = new Chart($("#servo-rack-chart"), {
    id: "rack", title: "Rack position over one turn", height: 180,
    x: { label: "main-shaft angle φ", unit: "°", range: [0, 360], step: 30 }, y: { label: "position u", unit: "mm", includeZero: true },
  });
  const kin = {};
  for (const [k, label] of [["s", "displacement s"], ["v", "velocity v = ds/dx"], ["a", "acceleration a = d²s/dx²"], ["j", "jerk j = d³s/dx³"]]) {
    kin[k] = new Chart($("#servo-kin-charts"), {
      id: "kin-" + k, title: label, height: 190, x: { label: "x", unit: "–", range: [0, 1] }, y: { label: k, unit: "–" },
    });
  }
  Object.assign(loomkin.charts, { editor, torque, power, rack, ...Object.fromEntries(Object.entries(kin).map(([k, c]) => ["kin_" + k, c])) });
  servo.charts = { editor, torque, power, rack, kin };
  editor.setPoints([], { onDrag: dragPoint, onDragEnd: () => { evaluate(); servo.history.commit(); } });
  $("#drag-x").addEventListener("change", (e) => { editor.freeX = e.target.checked; });
  servo.history = viewHistory("servo", () => servo.design, (d) => setDesign(d));

  const form = $("#drive-form");
  for (const [key, label, unit, optional] of DRIVE_FIELDS) {
    const input = el("input", { type: "number", step: "any", name: key, id: "drive-" + key, placeholder: optional || "" }); // optional: blank = default
    input.addEventListener("input", () => { if (readDrive()) evaluate(); });
    input.addEventListener("change", () => servo.history.commit());
    form.append(el("label", {}, `${label} (${unit})`, input));
  }
  $("#speeds").addEventListener("input", () => { if (readSpeeds()) evaluate(); });
  $("#speeds").addEventListener("change", () => servo.history.commit());
  $("#spline-end").addEventListener("change", (e) => { servo.design.end = e.target.value; evaluate(); servo.history.commit(); });
  $("#point-add").addEventListener("click", addPoint);
  $("#optimise").addEventListener("click", optimise);
  $("#export-coeffs").addEventListener("click", () => exportDesign("coeffs"));
  $("#export-coeffs-json").addEventListener("click", () => exportDesign("json"));
  $("#export-cam").addEventListener("click", () => exportDesign("csv"));
  $("#export-xyva").addEventListener("click", () => exportDesign("xyva"));
  $("#export-poly5").addEventListener("click", () => exportDesign("poly5"));
  $("#save-json").addEventListener("click", () => saveDesign("json"));
  $("#save-toml").addEventListener("click", () => saveDesign("toml"));
  $("#load-file").addEventListener("change", loadDesign);
  $("#reset-design").addEventListener("click", () => loadDefault());
  loadDefault();
}

async function loadDefault() {
  try {
    const d = await api("/servo/default");
    setDesign(d.design);
    if (servo.history.isReady) servo.history.commit(); else servo.history.ready();
  } catch (e) { status("default design: " + e.message, true); }
}

function setDesign(design) {
  servo.design = design;
  for (const [key] of DRIVE_FIELDS) $("#drive-" + key).value = design.drive[key] ?? "";
  $("#speeds").value = design.speeds_rpm.join(", ");
  $("#spline-end").value = design.end;
  renderPointsTable();
  evaluate();
}

// Reads the drive fields into the design; false (the first bad field refused at the field) when
// one is not a number.
function readDrive() {
  for (const [key, label, , optional] of DRIVE_FIELDS) {
    const input = $("#drive-" + key);
    if (optional && input.value.trim() === "" && !(input.validity && input.validity.badInput)) { delete servo.design.drive[key]; continue; }
    const v = numberIn("", input, label);
    if (v === null) return false;
    servo.design.drive[key] = v;
  }
  return true;
}

function readSpeeds() {
  const v = numberList("", $("#speeds"), "main-shaft speeds");
  if (v === null) return false;
  servo.design.speeds_rpm = v;
  return true;
}

function renderPointsTable() {
  const body = $("#points-table tbody");
  body.replaceChildren();
  const pts = servo.design.points, n = pts.length;
  pts.forEach(([x, y], i) => {
    const fixed = i === 0 || i === n - 1;
    const xi = el("input", { type: "number", step: "any", value: String(+x.toFixed(6)), disabled: fixed, id: `pt-x-${i}` });
    const yi = el("input", { type: "number", step: "any", value: String(+y.toFixed(6)), disabled: fixed, id: `pt-y-${i}` });
    const onInput = () => {
      const nx = numberIn("", xi, `row ${i + 1} x`);
      const ny = nx === null ? null : numberIn("", yi, `row ${i + 1} y`);
      if (nx !== null && ny !== null) { pts[i] = [nx, ny]; evaluate(); servo.history.commit(); }
    };
    xi.addEventListener("change", onInput);
    yi.addEventListener("change", onInput);
    const del = el("button", { type: "button", className: "icon", textContent: "×", title: "remove point", disabled: fixed || n <= 4 });
    del.addEventListener("click", () => { pts.splice(i, 1); renderPointsTable(); evaluate(); servo.history.commit(); });
    body.append(el("tr", { id: `pt-row-${i}` }, el("td", { textContent: String(i + 1) }), el("td", {}, xi), el("td", {}, yi), el("td", {}, del)));
  });
}

function updatePointsTable() {
  servo.design.points.forEach(([x, y], i) => {
    const xi = $(`#pt-x-${i}`), yi = $(`#pt-y-${i}`);
    if (xi && document.activeElement !== xi) xi.value = String(+x.toFixed(6));
    if (yi && document.activeElement !== yi) yi.value = String(+y.toFixed(6));
  });
}

function addPoint() {
  // Split the widest interval in the middle, with Y on the current spline.
  const pts = servo.design.points;
  let k = 0;
  for (let i = 1; i < pts.length; i++) if (pts[i][0] - pts[i - 1][0] > pts[k + 1][0] - pts[k][0]) k = i - 1;
  const x = (pts[k][0] + pts[k + 1][0]) / 2;
  let y = (pts[k][1] + pts[k + 1][1]) / 2;
  if (servo.result) y = LoomkinCharts.interp(servo.result.spline.x, servo.result.spline.f, x);
  pts.splice(k + 1, 0, [x, Math.max(-1, Math.min(1, y))]);
  renderPointsTable();
  evaluate();
  servo.history.commit();
}

// Mouse drag of definition point i to chart coordinates (x, y), kept inside its neighbours.
function dragPoint(i, x, y) {
  const pts = servo.design.points, n = pts.length;
  if (i <= 0 || i >= n - 1) return;
  const lo = pts[i - 1][0] + MIN_GAP, hi = pts[i + 1][0] - MIN_GAP;
  pts[i] = [Math.min(hi, Math.max(lo, x)), Math.min(1, Math.max(-1, y))];
  drawPoints();
  updatePointsTable();
  evaluate();
}

function drawPoints() {
  const pts = servo.design.points, n = pts.length;
  servo.charts.editor.setPoints(pts.map(([x, y], i) => ({ x, y, fixed: i === 0 || i === n - 1 })));
}

// One evaluation in flight at a time; while dragging, the newest state is sent when the last answer is in.
function evaluate() {
  if (!servo.design) return;
  if (servo.inflight) { servo.queued = true; return; }
  servo.inflight = true;
  loomkin.busy = true;
  const started = performance.now();
  api("/servo/evaluate", { design: servo.design })
    .then((r) => {
      servo.result = r;
      clearFieldErrors();
      renderServo(r);
      status(`evaluated in ${(performance.now() - started).toFixed(0)} ms (server ${r.compute_ms.toFixed(2)} ms)`);
    })
    .catch((e) => showFieldError("", e, servoField))
    .finally(() => {
      servo.inflight = false;
      loomkin.evalCount++;
      if (servo.queued) { servo.queued = false; evaluate(); } else { loomkin.busy = false; }
    });
}

// The inputs a refused servo design names: a definition point (its table row, counted from 1),
// a drive field or the speeds.
function servoField(path) {
  let m = /^design\.points\[(\d+)\]/.exec(path);
  if (m) {
    const i = +m[1];
    return { inputs: [$(`#pt-x-${i}`), $(`#pt-y-${i}`)], row: $(`#pt-row-${i}`), rowNumber: i + 1, columns: ["x", "y"] };
  }
  m = /^design\.drive\.(\w+)/.exec(path);
  if (m) return { inputs: [$(`#drive-${m[1]}`)], label: (DRIVE_FIELDS.find((f) => f[0] === m[1]) || [m[1], m[1]])[1] };
  if (/^design\.speeds_rpm/.test(path)) return { inputs: [$("#speeds")], label: "main-shaft speeds" };
  return null;
}

function renderServo(r) {
  const ch = servo.charts;
  drawPoints();
  ch.editor.setSeries([
    { label: "spline f(x) through the points", x: r.spline.x, y: r.spline.f, color: PALETTE[0] },
  ]);
  ch.torque.setSeries(r.speeds.map((s, k) => ({ label: `${num(s.speed_rpm)} rpm`, x: s.angle_deg, y: s.torque_nm, color: PALETTE[k + 1] })));
  ch.power.setSeries(r.speeds.map((s, k) => ({ label: `${num(s.speed_rpm)} rpm`, x: s.angle_deg, y: s.power_w, color: PALETTE[k + 1] })));
  if (r.speeds.length) ch.rack.setSeries([{ label: "", x: r.speeds[0].angle_deg, y: r.speeds[0].u_m.map((u) => convert(u, "m", "mm")) }]);
  const L = r.law.samples;
  for (const k of ["s", "v", "a", "j"]) ch.kin[k].setSeries([{ label: "", x: L.x, y: L[k], color: PALETTE[0] }]);

  const tb = $("#torque-table tbody");
  tb.replaceChildren(...r.speeds.map((s, k) => el("tr", {},
    el("td", { textContent: num(s.speed_rpm) }),
    el("td", { textContent: num(s.peak_torque_nm, 3), id: `peak-torque-${k}` }),
    el("td", { textContent: num(s.rms_torque_nm, 3), id: `rms-torque-${k}` }),
    el("td", { textContent: num(s.peak_power_w, 1), id: `peak-power-${k}` }))));
  const m = r.law.metrics;
  const rows = [
    ["Cv = max v", m.cv], ["Ca = max |a|", m.ca], ["Ca+ / Ca−", `${num(m.ca_pos)} / ${num(m.ca_neg)}`], ["Cj = max |j|", m.cj],
    ["Cm = max v·a", m.cm], ["Ca,rms", m.ca_rms], ["continuity class", `C${r.law.continuity_class}`],
    ["end slope D", r.d], ["scale a = c·f", r.scale],
  ];
  $("#servo-metrics tbody").replaceChildren(...rows.map(([k, v]) =>
    el("tr", {}, el("th", { textContent: k }), el("td", { textContent: typeof v === "number" ? num(v) : v }))));
}

async function optimise() {
  const btn = $("#optimise");
  btn.disabled = true;
  status("optimising…");
  // The optimum is of the design sent: a design edited while the search ran (a point dragged, a
  // drive field typed, undo) keeps its edits, and the optimum is not applied over them.
  const sent = JSON.stringify(servo.design);
  try {
    const r = await api("/servo/optimize", { design: servo.design, objective: $("#objective").value, move_x: $("#move-x").checked });
    if (JSON.stringify(servo.design) !== sent) {
      status("optimise: the design was edited while the search ran: its optimum is not applied (optimise again)");
      btn.disabled = false;
      return;
    }
    servo.design.points = r.def_points;
    renderPointsTable();
    evaluate();
    servo.history.commit();
    const rows = r.before.map((b, k) => {
      const a = r.after[k];
      return el("tr", {}, el("td", { textContent: num(b.speed_rpm) }),
        el("td", { textContent: `${num(b.peak_torque_nm, 2)} → ${num(a.peak_torque_nm, 2)}` }),
        el("td", { textContent: `${num(b.rms_torque_nm, 2)} → ${num(a.rms_torque_nm, 2)}` }));
    });
    $("#optimise-report").replaceChildren(el("table", { className: "data" },
      el("thead", {}, el("tr", {}, el("th", { textContent: "rpm" }), el("th", { textContent: "peak (N·m)" }), el("th", { textContent: "RMS (N·m)" }))),
      el("tbody", {}, ...rows)));
    status(`optimised in ${num(r.elapsed_ms, 0)} ms`);
  } catch (e) { if (JSON.stringify(servo.design) === sent) status("optimise: " + e.message, true); }
  btn.disabled = false;
}

async function exportDesign(format) {
  try {
    const rows = parseInt($("#cam-rows").value, 10);
    const r = await api("/servo/export", { design: servo.design, format, ...(isFinite(rows) ? { rows } : {}) });
    download(r.filename, r.text, r.media_type);
    status(`exported ${r.filename}` + (r.note ? ` — ${r.note}` : ""));
  } catch (e) { status("export: " + e.message, true); }
}

async function saveDesign(format) {
  try {
    const r = await api("/servo/design/save", { design: servo.design, format });
    download(r.filename, r.text, r.media_type);
    status(`saved ${r.filename}`);
  } catch (e) { status("save: " + e.message, true); }
}

async function loadDesign(ev) {
  const file = ev.target.files[0];
  if (!file) return;
  try {
    const text = await file.text();
    const format = /\.toml$/i.test(file.name) ? "toml" : /\.json$/i.test(file.name) ? "json" : "auto";
    const r = await api("/servo/design/load", { text, format });
    setDesign(r.design);
    servo.history.commit();
    status(`loaded ${file.name}`);
  } catch (e) { status(`load ${file.name}: ${e.message}`, true); }
  ev.target.value = "";
}

// ---------------------------------------------------------------- law catalogue

// The compared laws: a list of {name, params}; one law may appear several times with different
// parameters (variants), each one a curve and a row of the table.
const catalogueState = { entries: [{ name: "cycloidal", params: {} }, { name: "modified-trapezoid", params: { ramp: "0.125" } }, { name: "poly345", params: {} }], laws: [] };
const MAX_COMPARED = 8;

async function initCatalogue() {
  const charts = {};
  for (const [k, label] of [["s", "displacement s"], ["v", "velocity v = ds/dx"], ["a", "acceleration a = d²s/dx²"], ["j", "jerk j = d³s/dx³"]]) {
    charts[k] = new Chart($("#catalogue-charts"), { id: "cat-" + k, title: label, height: 240, x: { label: "x", unit: "–", range: [0, 1] }, y: { label: k, unit: "–" } });
    loomkin.charts["cat_" + k] = charts[k];
  }
  catalogueState.charts = charts;
  catalogueState.history = viewHistory("catalogue", () => catalogueState.entries, (entries) => {
    catalogueState.entries = entries;
    renderCatalogueList();
    compareLaws();
  });
  try {
    const cat = await api("/laws");
    for (const law of cat.laws) {
      const m = /^(\w+)=([^\s]+)/.exec(law.params);
      if (m) {
        law.key = m[1];
        law.default = law.name === "piecewise" ? "0.25:sine-ramp:0:1,0.25:cosine-ramp:1:0,0.25:sine-ramp:0:-1,0.25:cosine-ramp:-1:0" : m[2];
      }
    }
    catalogueState.laws = cat.laws;
  } catch (e) { status("catalogue: " + e.message, true); }
  renderCatalogueList();
  compareLaws();
  catalogueState.history.ready();
}

function catalogueChanged() {
  renderCatalogueList();
  compareLaws();
  catalogueState.history.commit();
}

// The list: a box per law (ticked when compared), then one parameter field per variant of it.
function renderCatalogueList() {
  const list = $("#catalogue-list");
  const entries = catalogueState.entries;
  list.replaceChildren();
  for (const law of catalogueState.laws) {
    const mine = entries.map((e, i) => [e, i]).filter(([e]) => e.name === law.name);
    const box = el("input", { type: "checkbox", checked: mine.length > 0, id: "cat-" + law.name });
    box.addEventListener("change", () => {
      if (box.checked) {
        if (entries.length >= MAX_COMPARED) { box.checked = false; status(`at most ${MAX_COMPARED} laws are compared`, true); return; }
        entries.push({ name: law.name, params: law.key ? { [law.key]: law.default } : {} });
      } else {
        catalogueState.entries = entries.filter((e) => e.name !== law.name);
      }
      catalogueChanged();
    });
    const row = el("div", { className: "check" }, box, el("label", { htmlFor: box.id, textContent: law.name, title: law.description }));
    list.append(row);
    if (law.key) {
      const variants = mine.length ? mine : [[null, -1]];
      variants.forEach(([e, i], k) => {
        const inp = el("input", { type: "text", value: e ? e.params[law.key] ?? law.default : law.default, title: law.params, spellcheck: false, disabled: !e, id: `cat-param-${i}` });
        inp.addEventListener("change", () => { e.params = { [law.key]: inp.value }; compareLaws(); catalogueState.history.commit(); });
        const line = k === 0 ? row : el("div", { className: "check variant" }, el("span", { className: "hint", textContent: "variant" }));
        line.append(el("small", { textContent: law.key + " =" }), inp);
        if (k > 0) {
          const del = el("button", { type: "button", className: "icon", textContent: "×", title: "remove this variant" });
          del.addEventListener("click", () => { entries.splice(i, 1); catalogueChanged(); });
          line.append(del);
          list.append(line);
        }
      });
      if (mine.length) {
        const add = el("button", { type: "button", className: "icon", textContent: "+ variant", title: `compare ${law.name} with another ${law.key}`, id: `cat-variant-${law.name}` });
        add.addEventListener("click", () => {
          if (entries.length >= MAX_COMPARED) { status(`at most ${MAX_COMPARED} laws are compared`, true); return; }
          const last = mine[mine.length - 1][0];
          entries.splice(mine[mine.length - 1][1] + 1, 0, { name: law.name, params: { ...last.params } });
          catalogueChanged();
        });
        row.append(add);
      }
    }
    list.append(el("div", { className: "hint", textContent: law.description }));
  }
}

async function compareLaws() {
  const laws = catalogueState.entries.map((e) => ({ name: e.name, params: e.params || {} }));
  if (laws.length === 0) {
    newest.drop("catalogue");
    for (const k of ["s", "v", "a", "j"]) catalogueState.charts[k].setSeries([]);
    $("#catalogue-metrics tbody").replaceChildren();
    return;
  }
  // Every edit sends its comparison at once: only the newest one's answer is drawn (an earlier,
  // slower one may arrive after it).
  const current = newest("catalogue");
  try {
    const r = await api("/laws/compare", { laws, samples: 801 });
    if (!current()) return;
    clearFieldErrors();
    for (const k of ["s", "v", "a", "j"]) {
      catalogueState.charts[k].setSeries(r.laws.map((l, i) => ({ label: l.label, x: l.samples.x, y: l.samples[k], color: PALETTE[i % PALETTE.length], dash: DASHES[Math.floor(i / 4) % DASHES.length] })));
    }
    $("#catalogue-metrics tbody").replaceChildren(...r.laws.map((l, i) => {
      const sw = el("span", { className: "swatch" });
      sw.style.background = PALETTE[i % PALETTE.length];
      const m = l.metrics;
      return el("tr", { id: `cat-row-${i}` }, el("td", {}, sw, l.label), ...[m.cv, m.ca, m.ca_pos, m.ca_neg, m.cj, m.cm, m.ca_rms].map((v) => el("td", { textContent: num(v) })),
        el("td", { textContent: "C" + l.continuity_class }));
    }));
    status(`${r.laws.length} laws compared`);
  } catch (e) {
    if (!current()) return;
    showFieldError("compare", e, (f) => {
      const m = /^laws\[(\d+)\]/.exec(f);
      const e = m && catalogueState.entries[+m[1]];
      return e ? { inputs: [$(`#cat-param-${m[1]}`)], label: `law ${+m[1] + 1} of the comparison (${e.name})` } : null;
    });
  }
}

const DASHES = [[], [7, 4], [2, 3]];


// ---------------------------------------------------------------- picking scenario

const picking = { values: {}, inflight: false, queued: false };

async function initPicking() {
  const root = $("#picking-root");
  const panel = el("div", { className: "panel" }, el("h2", { textContent: "Loom settings" }),
    el("p", { className: "hint", textContent: "The paper's under-pick mechanism (Jederán 1959), its cam designed for V = 17 m/s over X = 0.22 m. Move a slider: the pick is recomputed." }));
  const method = el("select", { id: "picking-method" }, el("option", { value: "closed", textContent: "closed form (corrected)" }), el("option", { value: "ode", textContent: "numerical (DOP853)" }));
  method.addEventListener("change", () => { simulatePick(); picking.history.commit(); });
  const table = el("table", { className: "data", id: "picking-outcome" }, el("caption", { textContent: "End of the pick" }), el("tbody"));
  const charts = el("div", { className: "grid-charts" });
  root.append(el("div", { className: "results" }, panel, table), charts);
  const mk = (id, title, label, unit) => new Chart(charts, { id, title, height: 230, x: { label: "time from shuttle start t", unit: "ms" }, y: { label, unit } });
  picking.charts = { x: mk("pick-x", "Displacement", "displacement", "mm"), v: mk("pick-v", "Velocity", "velocity", "m/s"), a: mk("pick-a", "Acceleration", "acceleration", "m/s²") };
  Object.assign(loomkin.charts, { pick_x: picking.charts.x, pick_v: picking.charts.v, pick_a: picking.charts.a });
  try {
    const info = await api("/picking/settings");
    picking.sliders = {};
    for (const s of info.settings) {
      picking.values[s.key] = s.designed;
      // The slider moves in round steps; the field beside it takes any value (15.5 mm of play).
      const step = niceRound((s.max - s.min) / 200);
      // The slider spans the paper's range; the field takes the library's (the request schema's).
      const w = sliderWithNumber("pick-" + s.key, s.description, s.unit, s.min, s.max, step, +s.designed.toPrecision(6),
        (v) => { picking.values[s.key] = v; simulatePick(); }, () => picking.history.commit(),
        { route: "/api/picking/simulate", path: "settings." + s.key });
      w.field.value = String(+s.designed.toPrecision(6));
      picking.sliders[s.key] = w;
      panel.append(w.label);
    }
    panel.append(el("label", { className: "slider" }, el("span", { textContent: "route" }), method));
  } catch (e) { status("picking: " + e.message, true); }
  picking.history = viewHistory("picking", () => ({ settings: picking.values, method: $("#picking-method").value }), (st) => {
    Object.assign(picking.values, st.settings || {});
    for (const [k, w] of Object.entries(picking.sliders || {})) w.set(picking.values[k]);
    if (st.method) $("#picking-method").value = st.method;
    simulatePick();
  });
  simulatePick();
  picking.history.ready();
}

// 1, 2 or 5 times a power of ten, at or below v (slider steps).
function niceRound(v) {
  const p = Math.pow(10, Math.floor(Math.log10(v)));
  const f = v / p;
  return (f >= 5 ? 5 : f >= 2 ? 2 : 1) * p;
}

function simulatePick() {
  if (picking.inflight) { picking.queued = true; return; }
  picking.inflight = true;
  api("/picking/simulate", { settings: picking.values, method: $("#picking-method").value })
    .then((r) => {
      const c = r.curves, ch = picking.charts;
      ch.x.setSeries([{ label: "cam (nominal) s", x: c.t_ms, y: c.nominal_mm, dash: [6, 4] }, { label: "shuttle x", x: c.t_ms, y: c.actual_mm }]);
      ch.v.setSeries([{ label: "cam (nominal)", x: c.t_ms, y: c.nominal_v_m_s, dash: [6, 4] }, { label: "shuttle", x: c.t_ms, y: c.actual_v_m_s }]);
      ch.a.setSeries([{ label: "cam (nominal)", x: c.t_ms, y: c.nominal_a_m_s2, dash: [6, 4] }, { label: "shuttle", x: c.t_ms, y: c.actual_a_m_s2 }]);
      const o = r.outcome;
      const rows = [
        ["shuttle velocity at the end", `${num(o.velocity_m_s, 3)} m/s`, "pick-velocity"],
        ["required velocity", `${num(o.required_velocity_m_s, 3)} m/s`],
        ["velocity above the required", `${num(o.velocity_vs_required_pct, 1)} %`],
        ["picking distance", `${num(convert(o.distance_m, "m", "mm"), 1)} mm`],
        ["pick duration", `${num(convert(o.t_end_s, "s", "ms"), 2)} ms`],
        ["peak acceleration", `${num(o.accel_peak_m_s2, 0)} m/s²`],
        ["end of the pick", o.end === "separation" ? "shuttle left the picker early" : "end of the cam rise"],
        ["route", o.method + (o.note ? ` — ${o.note}` : "")],
      ];
      $("#picking-outcome tbody").replaceChildren(...rows.map(([k, v, id]) => el("tr", {}, el("th", { textContent: k }), el("td", { textContent: v, id: id || "" }))));
      status("pick simulated");
    })
    .catch((e) => showFieldError("picking", e, (f) => {
      const m = /^settings\.(\w+)/.exec(f);
      return m && picking.sliders && picking.sliders[m[1]] ? { inputs: [picking.sliders[m[1]].field], label: m[1] } : null;
    }))
    .finally(() => { picking.inflight = false; if (picking.queued) { picking.queued = false; simulatePick(); } });
}


// ---------------------------------------------------------------- shedding Pareto explorer

const shed = { result: null, chosen: 0 };
// One clearly different colour per motion angle (up to 12), none close to the black front or
// the amber "chosen" marker.
const CLOUD_COLOURS = ["#1d4ed8", "#0891b2", "#16a34a", "#9333ea", "#db2777", "#dc2626", "#92400e", "#4f46e5", "#0f766e", "#65a30d", "#64748b", "#be123c"];

function initShed() {
  const root = $("#shed-root");
  const field = (label, input) => el("label", {}, label, input);
  const family = el("select", { id: "shed-family" },
    el("option", { value: "trapezoid", textContent: "trapezoid (sine rise, plateau, cosine fall)" }),
    el("option", { value: "lead-trapezoid", textContent: "lead-trapezoid (zero lead + trapezoid)" }),
    el("option", { value: "linear-trapezoid", textContent: "linear-trapezoid" }));
  const inputs = {
    step: el("input", { type: "number", step: "any", value: "0.025", id: "shed-step" }),
    motions: el("input", { type: "text", value: "180, 200, 220, 240, 260, 280, 300", id: "shed-motions", spellcheck: false }),
    threshold: el("input", { type: "number", step: "any", id: "shed-threshold" }),
    // mm, as `loomkin shed … --stroke-mm` (the request's conditions.stroke_mm).
    stroke: el("input", { type: "number", step: "any", value: "100", id: "shed-stroke" }),
    speed: el("input", { type: "number", step: "any", id: "shed-speed" }),
    jerk: el("input", { type: "number", step: "any", placeholder: "none", id: "shed-jerk" }),
  };
  const pareto = "/api/shed/pareto";
  applyLimits(inputs.step, pareto, "step");
  applyLimits(inputs.threshold, pareto, "conditions.threshold");
  applyLimits(inputs.stroke, pareto, "conditions.stroke_mm");
  applyLimits(inputs.speed, pareto, "conditions.speed_rpm");
  applyLimits(inputs.jerk, pareto, "max_jerk_m_s3");
  const log = el("input", { type: "checkbox", id: "shed-log" });
  const form = el("div", { className: "panel" }, el("h2", { textContent: "Family and grid" }),
    el("p", { className: "hint", textContent: "Heald-frame laws (Makarov et al. 2004): every law of the family on a grid of relative lengths k_Ti, at each motion angle. Click a point of the Pareto front to see that law. A jerk limit keeps only the laws whose peak jerk stays under it (laws whose acceleration jumps have no bounded jerk)." }),
    el("div", { className: "grid2" }, field("law family", family), field("grid step of k_Ti (–)", inputs.step),
      field("motion angles φ (°)", inputs.motions), field("dwell threshold T (–)", inputs.threshold),
      field("stroke h (mm)", inputs.stroke), field("main-shaft speed n (rpm)", inputs.speed),
      field("jerk limit (m/s³)", inputs.jerk)),
    el("label", { className: "check" }, log, "log scale for the peak acceleration"));
  const table = el("table", { className: "data", id: "shed-chosen" }, el("caption", { textContent: "Chosen law" }), el("tbody"));
  const charts = el("div", { className: "charts" });
  root.append(el("div", { className: "results" }, form, table), charts);
  shed.pareto = new Chart(charts, { id: "shed-pareto", title: "Pareto explorer", height: 360,
    x: { label: "weft-crossing window φ*", unit: "°" }, y: { label: "peak frame acceleration", unit: "m/s²" } });
  const row = el("div", { className: "grid-charts" });
  charts.append(row);
  // The frame's period is two picks: up over the first turn, down over the second (0 … 720°).
  const mk = (id, title, label, unit) => new Chart(row, { id, title, height: 220, x: { label: "main-shaft angle", unit: "°", range: [0, 720], step: 90 }, y: { label, unit, includeZero: true } });
  shed.s = mk("shed-s", "Frame displacement (up, then down)", "s", "mm");
  shed.v = mk("shed-v", "Frame velocity over two picks", "v", "m/s");
  shed.a = mk("shed-a", "Frame acceleration over two picks", "a", "m/s²");
  shed.j = mk("shed-j", "Frame jerk over two picks", "j", "m/s³");
  Object.assign(loomkin.charts, { shed_pareto: shed.pareto, shed_s: shed.s, shed_v: shed.v, shed_a: shed.a, shed_j: shed.j });
  shed.pareto.setHandlers({ onClick: (x, y, px, py) => pickFront(px, py) });
  for (const e of [family, ...Object.values(inputs)]) e.addEventListener("change", () => { computePareto(); shed.history.commit(); });
  log.addEventListener("change", () => { shed.logTouched = true; shed.pareto.opts.y.log = log.checked; shed.pareto.resetView(); shed.history.commit(); });
  shed.inputs = { family, ...inputs };
  shed.log = log;
  shed.history = viewHistory("shed", () => ({
    family: family.value, step: inputs.step.value, motions_deg: inputs.motions.value, threshold: inputs.threshold.value,
    stroke_mm: inputs.stroke.value, speed_rpm: inputs.speed.value, max_jerk_m_s3: inputs.jerk.value, log: log.checked, chosen: shed.chosen,
  }), (st) => {
    family.value = st.family; inputs.step.value = st.step; inputs.motions.value = st.motions_deg; inputs.threshold.value = st.threshold;
    inputs.stroke.value = st.stroke_mm; inputs.speed.value = st.speed_rpm; inputs.jerk.value = st.max_jerk_m_s3 || "";
    log.checked = !!st.log; shed.logTouched = true; shed.pareto.opts.y.log = log.checked;
    computePareto(st.chosen);
  });
  computePareto().then(() => shed.history.ready());
}

function shedConditions() {
  const i = shed.inputs;
  return { threshold: +i.threshold.value, stroke_mm: +i.stroke.value, speed_rpm: +i.speed.value };
}

function shedJerkLimit() {
  const t = shed.inputs.jerk.value.trim();
  return t === "" ? null : +t;
}

// The inputs a refused shedding request names.
function shedField(path) {
  const i = shed.inputs;
  const map = { "conditions.threshold": [i.threshold, "dwell threshold T"], "conditions.stroke_mm": [i.stroke, "stroke h"], "conditions.stroke_m": [i.stroke, "stroke h"], "conditions.speed_rpm": [i.speed, "main-shaft speed n"],
    step: [i.step, "grid step"], max_jerk_m_s3: [i.jerk, "jerk limit"], family: [i.family, "law family"] };
  if (/^motions_deg/.test(path)) {
    const m = /\[(\d+)\]/.exec(path);
    return { inputs: [i.motions], label: m ? `motion angle ${+m[1] + 1} of the list` : "motion angles" };
  }
  const hit = map[path];
  return hit ? { inputs: [hit[0]], label: hit[1] } : null;
}

// One Pareto request in flight at a time: a change made meanwhile is sent when the answer is in,
// so an earlier, slower answer never overwrites a later one (the promise settles after both). The
// page's own refusals are made at once, before any wait (the history records no refused state).
function computePareto(chosen) {
  const req = paretoRequest();
  if (req === null) return Promise.resolve();
  if (shed.inflight) { shed.queued = { chosen }; return shed.inflight; }
  shed.inflight = computeParetoNow(req, chosen).finally(() => {
    shed.inflight = null;
    if (shed.queued) { const q = shed.queued; shed.queued = null; return computePareto(q.chosen); }
  });
  return shed.inflight;
}

// The Pareto request of the fields shown, or null after refusing a field the page can judge.
function paretoRequest() {
  const i = shed.inputs;
  // 0 < h ≤ 1 m, as the library's Conditions.
  if (mmRefused("shedding", i.stroke, "stroke h", +i.stroke.value)) return null;
  const motions_deg = numberList("shedding", i.motions, "motion angles");
  if (motions_deg === null) return null;
  const req = { family: i.family.value, step: +i.step.value, motions_deg, conditions: shedConditions() };
  const jl = shedJerkLimit();
  if (jl !== null) req.max_jerk_m_s3 = jl;
  return req;
}

async function computeParetoNow(req, chosen) {
  status("evaluating the grid…");
  try {
    const r = await api("/shed/pareto", req);
    clearFieldErrors();
    shed.result = r;
    // The front shown and the laws drawn from it belong to this request, not to the fields as they
    // are when a law is chosen (a field may have been changed, or refused, since it was sent).
    shed.asked = req;
    const byMotion = {}, over = { x: [], y: [] };
    r.cloud.motion_deg.forEach((m, k) => {
      const ok = !r.cloud.within_jerk_limit || r.cloud.within_jerk_limit[k];
      const d = ok ? (byMotion[m] = byMotion[m] || { x: [], y: [] }) : over;
      d.x.push(r.cloud.window_deg[k]);
      d.y.push(r.cloud.peak_accel_m_s2[k]);
    });
    const front = [...r.front].sort((a, b) => a.criteria.window_deg - b.criteria.window_deg);
    shed.front = front;
    const series = [];
    if (over.x.length) series.push({ label: "over the jerk limit", mode: "points", radius: 1.1, x: over.x, y: over.y, color: "#cbd5e1", hover: false });
    Object.entries(byMotion).forEach(([m, d], k) => series.push({ label: `φ = ${m}°`, mode: "points", radius: 1.3, x: d.x, y: d.y, color: CLOUD_COLOURS[k % CLOUD_COLOURS.length] }));
    series.push({ label: "Pareto front", mode: "markers", line: true, radius: 4, color: "#111827", x: front.map((c) => c.criteria.window_deg), y: front.map((c) => c.criteria.peak_accel_m_s2) });
    shed.series = series;
    // Accelerations over more than two decades (the lead-trapezoid family reaches 10⁵ m/s²) are
    // drawn on a log axis, unless the box was set by hand.
    if (!shed.logTouched) {
      const ys = r.cloud.peak_accel_m_s2.filter((v) => v > 0);
      shed.log.checked = ys.length > 0 && Math.max(...ys) / Math.min(...ys) > 100;
      shed.pareto.opts.y.log = shed.log.checked;
    }
    shed.pareto.view = null;
    shed.pareto.setSeries(series);
    const n = Object.keys(byMotion).length;
    status(`${r.laws} laws × ${r.cloud.motion_deg.length / Math.max(1, r.laws)} motion angles; ${r.front.length} on the Pareto front` +
      (over.x.length ? `; ${over.x.length} of ${r.cloud.motion_deg.length} over the jerk limit` : "") + (n ? "" : " — no law within the jerk limit"));
    if (front.length) await chooseLaw(chosen !== undefined && chosen < front.length ? chosen : Math.floor(front.length / 2));
    else { for (const c of [shed.s, shed.v, shed.a, shed.j]) c.setSeries([]); $("#shed-chosen tbody").replaceChildren(); }
  } catch (e) { showFieldError("shedding", e, shedField); }
}

function pickFront(px, py) {
  if (!shed.front || !shed.pareto.L) return;
  let best = -1, bd = Infinity;
  shed.front.forEach((c, k) => {
    const [qx, qy] = shed.pareto.toPx(shed.pareto.L, c.criteria.window_deg, c.criteria.peak_accel_m_s2);
    const d = (qx - px) ** 2 + (qy - py) ** 2;
    if (d < bd) { bd = d; best = k; }
  });
  if (best >= 0) chooseLaw(best).then(() => shed.history.commit());
}

async function chooseLaw(k) {
  const c = shed.front[k];
  if (!c) return;
  shed.chosen = k;
  const sel = { label: "chosen", mode: "markers", radius: 7, color: "#f59e0b", hover: false, x: [c.criteria.window_deg], y: [c.criteria.peak_accel_m_s2] };
  shed.pareto.setSeries([...shed.series, sel]);
  // Only the answer for the law chosen last is drawn (an earlier choice's may arrive after it).
  const current = newest("shed-law");
  try {
    const r = await api("/shed/law", { family: shed.asked.family, lengths: c.lengths, motion_deg: c.criteria.motion_deg, conditions: shed.asked.conditions, samples: 2881 });
    if (!current()) return;
    shed.s.setSeries([{ label: "", x: r.angle_deg, y: r.s_mm }]);
    shed.v.setSeries([{ label: "", x: r.angle_deg, y: r.v_m_s }]);
    shed.a.setSeries([{ label: "", x: r.angle_deg, y: r.a_m_s2 }]);
    const q = r.criteria, jl = shedJerkLimit();
    // Jerk inside the segments; where the acceleration jumps the jerk is unbounded: those
    // angles are marked by vertical bars (the jump is in the table).
    shed.j.bands = (r.accel_jumps_deg || []).map((x) => [x - 0.8, x + 0.8]);
    shed.j.hlines = jl !== null ? [{ y: jl, label: `jerk limit ${num(jl)} m/s³` }, { y: -jl }] : [];
    shed.j.setSeries([{ label: q.accel_jump_m_s2 > 0 ? "jerk (unbounded at the shaded jumps)" : "", x: r.angle_deg, y: r.j_m_s3 }]);
    const jumps = q.accel_jump_m_s2 > 0;
    const jerkText = jumps ? `unbounded: the acceleration jumps by ${num(q.accel_jump_m_s2, 1)} m/s² (${num(q.peak_jerk_m_s3, 0)} m/s³ between jumps)`
      : `${num(q.peak_jerk_m_s3, 0)} m/s³`;
    const rows = [
      ["relative lengths k_Ti", c.lengths.map((v) => num(v, 3)).join(" : ")],
      ["motion angle φ", `${num(q.motion_deg, 1)} °`], ["dwell", `${num(q.dwell_deg, 1)} °`],
      ["conditional dwell", `${num(q.conditional_dwell_deg, 1)} °`], ["window φ*", `${num(q.window_deg, 1)} °`],
      ["Ca", num(q.ca)], ["Cv", num(q.cv)], ["Cj", num(q.cj)], ["peak acceleration", `${num(q.peak_accel_m_s2, 1)} m/s²`],
      ["peak velocity", `${num(q.peak_velocity_m_s, 3)} m/s`], ["RMS acceleration", `${num(q.rms_accel_m_s2, 1)} m/s²`],
      ["peak jerk", jerkText, "shed-peak-jerk"],
    ];
    if (jl !== null) rows.push(["within the jerk limit", !jumps && q.peak_jerk_m_s3 <= jl ? `yes (${num(jl)} m/s³)` : `no (${num(jl)} m/s³)`, "shed-jerk-ok"]);
    $("#shed-chosen tbody").replaceChildren(...rows.map(([a, b, id]) => el("tr", {}, el("th", { textContent: a }), el("td", { textContent: b, id: id || "" }))));
  } catch (e) { if (current()) showFieldError("shedding law", e, shedField); }
}


// ---------------------------------------------------------------- dobby modulator

const dobby = { req: null, result: null };

async function initDobby() {
  const root = $("#dobby-root");
  const inputs = {
    cycles: el("input", { type: "number", step: "1", id: "dobby-cycles" }),
    dwell: el("input", { type: "number", step: "any", id: "dobby-dwell" }),
    centre: el("input", { type: "number", step: "any", id: "dobby-centre" }),
    rise: el("select", { id: "dobby-rise" }),
    alpha: el("input", { type: "number", step: "any", id: "dobby-alpha" }),
    roller: el("input", { type: "number", step: "any", id: "dobby-roller" }),
  };
  for (const name of ["cycloidal", "modified-sine", "modified-trapezoid", "poly345", "poly4567", "harmonic"]) inputs.rise.append(el("option", { value: name, textContent: name }));
  applyLimits(inputs.cycles, "/api/dobby/synthesize", "law.cycles");
  applyLimits(inputs.alpha, "/api/dobby/synthesize", "geometry.alpha_deg");
  applyLimits(inputs.roller, "/api/dobby/synthesize", "roller_m", "mm");
  const angleW = sliderWithNumber("dobby-angle", "input angle φ2", "°", 0, 360, 1, 40, () => drawDobby(), () => dobby.history.commit());
  const angle = angleW.range;
  const play = el("button", { type: "button", id: "dobby-play", textContent: "▶ turn the crank" });
  let timer = null;
  play.addEventListener("click", () => {
    if (timer) { clearInterval(timer); timer = null; play.textContent = "▶ turn the crank"; return; }
    play.textContent = "⏸ stop";
    timer = setInterval(() => { angleW.set((+angle.value + 2) % 360); drawDobby(); }, 40);
  });
  const field = (label, input) => el("label", {}, label, input);
  const panel = el("div", { className: "panel" }, el("h2", { textContent: "Output law and modulator" }),
    el("p", { className: "hint", textContent: "Stäubli-type rotary-dobby modulator: the conjugate cams Γ (roller B) and Γ′ (roller C) synthesised for the output law. Move the slider to turn the input crank." }),
    el("div", { className: "grid2" }, field("cycles per turn (–)", inputs.cycles), field("dwell per cycle (°)", inputs.dwell),
      field("first dwell centred at (°)", inputs.centre), field("rise law", inputs.rise),
      field("angle α slot–arm AB (°)", inputs.alpha), field("roller radius (mm)", inputs.roller)),
    angleW.label, play,
    el("div", { className: "row wrap" },
      el("button", { type: "button", id: "dobby-dxf", textContent: "DXF of the cams (mm)", title: "both cams: roller-centre curves and groove walls, as loomkin dobby synthesize --dxf" }),
      el("button", { type: "button", id: "dobby-csv", textContent: "Cam table (CSV)", title: "centre curves and walls of both cams per input angle, as loomkin dobby synthesize --points-csv" })));
  const table = el("table", { className: "data", id: "dobby-summary" }, el("caption", { textContent: "Checks" }), el("tbody"));
  const charts = el("div", { className: "grid-charts" });
  root.append(el("div", { className: "results" }, panel, table), charts);
  dobby.scene = new LoomkinCharts.Scene(charts, { id: "dobby-scene", title: "Cams and mechanism", height: 480, unit: "mm", scale: convert(1, "m", "mm") });
  loomkin.dobbyScene = () => dobby.scene;
  const side = el("div", { className: "charts" });
  charts.append(side);
  const mk = (id, title, label, unit, step) => new Chart(side, { id, title, height: 150, x: { label: "input angle φ2", unit: "°", range: [0, 360], step: 30 }, y: { label, unit, step } });
  dobby.phi = mk("dobby-phi", "Output angle", "φ6", "°", 90);
  dobby.omega = mk("dobby-omega", "Output speed and acceleration at ω2 = 1 rad/s", "ω6, ε6", "rad/s, rad/s²");
  dobby.mu = mk("dobby-mu", "Pressure angles (limit dashed)", "μ", "°");
  Object.assign(loomkin.charts, { dobby_phi: dobby.phi, dobby_omega: dobby.omega, dobby_mu: dobby.mu });
  dobby.inputs = inputs; dobby.angle = angle; dobby.angleW = angleW;
  $("#dobby-dxf").addEventListener("click", () => exportDobby("dxf"));
  $("#dobby-csv").addEventListener("click", () => exportDobby("csv"));
  try {
    dobby.req = await api("/dobby/default");
    const r = dobby.req;
    inputs.cycles.value = r.law.cycles; inputs.dwell.value = r.law.dwell_deg; inputs.centre.value = r.law.dwell_centre_deg;
    inputs.rise.value = r.law.rise.name; inputs.alpha.value = r.geometry.alpha_deg; inputs.roller.value = convert(r.roller_m, "m", "mm");
  } catch (e) { status("dobby: " + e.message, true); return; }
  for (const e of Object.values(inputs)) e.addEventListener("change", () => { synthesizeDobby(); dobby.history.commit(); });
  dobby.history = viewHistory("dobby", () => ({ ...readDobbyInputs(), angle_deg: +angle.value }), (st) => {
    const i = dobby.inputs;
    i.cycles.value = st.law.cycles; i.dwell.value = st.law.dwell_deg; i.centre.value = st.law.dwell_centre_deg;
    i.rise.value = st.law.rise.name; i.alpha.value = st.geometry.alpha_deg; i.roller.value = st.roller_mm;
    if (st.angle_deg !== undefined) angleW.set(st.angle_deg);
    synthesizeDobby();
  });
  synthesizeDobby().then(() => dobby.history.ready());
}

// The page's request: the roller radius in mm (as the CLI's --roller-mm), the rest as the API.
function readDobbyInputs() {
  const i = dobby.inputs, r = dobby.req;
  return {
    law: { cycles: parseInt(i.cycles.value, 10), dwell_deg: +i.dwell.value, dwell_centre_deg: +i.centre.value, rise: { name: i.rise.value, params: {} } },
    geometry: { ...r.geometry, alpha_deg: +i.alpha.value }, roller_mm: +i.roller.value, step_deg: r.step_deg,
  };
}

function dobbyRequest() {
  const q = readDobbyInputs();
  return { law: q.law, geometry: q.geometry, roller_m: convert(q.roller_mm, "mm", "m"), step_deg: q.step_deg };
}

function dobbyField(path) {
  const i = dobby.inputs;
  const map = { "law.cycles": [i.cycles, "cycles per turn"], "law.dwell_deg": [i.dwell, "dwell per cycle"], "law.dwell_centre_deg": [i.centre, "first dwell centre"],
    "law.rise": [i.rise, "rise law"], "geometry.alpha_deg": [i.alpha, "angle α"], roller_m: [i.roller, "roller radius"] };
  const hit = map[path];
  return hit ? { inputs: [hit[0]], label: hit[1] } : null;
}

async function exportDobby(format) {
  try {
    const r = await api("/dobby/export", { request: dobbyRequest(), format });
    download(r.filename, r.text, r.media_type);
    status(`exported ${r.filename}`);
  } catch (e) { showFieldError("dobby export", e, (f) => dobbyField(f.replace(/^request\./, ""))); }
}

async function synthesizeDobby() {
  // The roller's limits as /api/dobby/synthesize's schema, in mm.
  if (mmRefused("dobby", dobby.inputs.roller, "roller radius", +dobby.inputs.roller.value)) return;
  const r = dobbyRequest();
  dobby.req = r;
  // Every change sends its synthesis at once: only the newest one's answer is drawn.
  const current = newest("dobby");
  try {
    const res = await api("/dobby/synthesize", r);
    if (!current()) return;
    clearFieldErrors();
    dobby.result = res;
    const c = res.curves;
    dobby.phi.setSeries([{ label: "φ6", x: c.phi2_deg, y: c.phi6_deg }]);
    dobby.omega.setSeries([{ label: "ω6 (rad/s)", x: c.phi2_deg, y: c.omega6_rad_s }, { label: "ε6 (rad/s²)", x: c.phi2_deg, y: c.eps6_rad_s2 }]);
    // The limit as a dashed series across the turn (in the legend and inside the axis range).
    const lim = res.pressure_limit_deg;
    dobby.mu.setSeries([{ label: "roller B", x: c.phi2_deg, y: c.mu_b_deg }, { label: "roller C", x: c.phi2_deg, y: c.mu_c_deg }, { label: "output", x: c.phi2_deg, y: c.mu_out_deg },
      { label: `limit ${num(lim)}°`, x: [0, 360], y: [lim, lim], dash: [6, 4], color: "#dc2626", width: 1.4, hover: false }]);
    const all = [...res.cam.wall_left, ...res.cam.wall_right, ...res.counter_cam.wall_left, ...res.counter_cam.wall_right, ...res.cam.centre, ...res.counter_cam.centre, ...res.poses.flatMap((p) => [p.a, p.b, p.c, p.d])];
    const xs = all.map((p) => p[0]), ys = all.map((p) => p[1]);
    const pad = 0.04;
    dobby.bounds = [Math.min(...xs) - pad, Math.min(...ys) - pad, Math.max(...xs) + pad, Math.max(...ys) + pad];
    const s = res.summary, ch = s.checks || s; // the checks may be flattened into the summary
    const rows = [
      ["output law", s.law], ["largest lag |φ6 − φ2|", `${num(s.lag_max_deg, 2)}° (limit ${num(s.lag_limit_deg, 2)}°)`],
      ["admissible α", `${num(s.admissible_alpha_deg[0], 1)}° … ${num(s.admissible_alpha_deg[1], 1)}°`],
      ["ω6 range", `${num(ch.omega6_min_rad_s, 3)} … ${num(ch.omega6_max_rad_s, 3)} rad/s`],
      ["ε6 range", `${num(ch.eps6_min_rad_s2, 3)} … ${num(ch.eps6_max_rad_s2, 3)} rad/s²`],
      ["max pressure angle B / C", `${num(ch.mu_b_max_deg, 1)}° / ${num(ch.mu_c_max_deg, 1)}°`],
      ["undercut", s.undercut ? "yes" : "no"], ["warnings", res.warnings.length ? res.warnings.map((w) => w.message).join("; ") : "none"],
    ];
    $("#dobby-summary tbody").replaceChildren(...rows.map(([a, b]) => el("tr", {}, el("th", { textContent: a }), el("td", { textContent: b }))));
    status("cams synthesised");
    drawDobby();
  } catch (e) { if (current()) showFieldError("dobby", e, dobbyField); }
}

function drawDobby() {
  const res = dobby.result;
  if (!res) return;
  const phi = +dobby.angle.value % 360;
  let k = 0, bd = Infinity;
  res.poses.forEach((p, j) => { const d = Math.abs(p.phi2_deg - phi); if (d < bd) { bd = d; k = j; } });
  const p = res.poses[k], r = dobby.req.roller_m;
  dobby.poseDeg = p.phi2_deg;
  const far = [p.a[0] + 1.4 * (p.d[0] - p.a[0]), p.a[1] + 1.4 * (p.d[1] - p.a[1])];
  const items = [
    // The cams are closed curves over the whole turn: the last point (359°) joins the first (0°).
    { kind: "line", pts: res.cam.wall_left, color: "#1f5fa8", width: 1.5, legend: "Γ", closed: true, name: "cam wall left" },
    { kind: "line", pts: res.cam.wall_right, color: "#1f5fa8", width: 1.5, closed: true, name: "cam wall right" },
    { kind: "line", pts: res.cam.centre, color: "#1f5fa8", width: 1, dash: [4, 4], closed: true, name: "cam roller-centre curve" },
    { kind: "line", pts: res.counter_cam.wall_left, color: "#15803d", width: 1.5, legend: "Γ′", closed: true, name: "counter-cam wall left" },
    { kind: "line", pts: res.counter_cam.wall_right, color: "#15803d", width: 1.5, closed: true, name: "counter-cam wall right" },
    { kind: "line", pts: res.counter_cam.centre, color: "#15803d", width: 1, dash: [4, 4], closed: true, name: "counter-cam roller-centre curve" },
    { kind: "line", pts: [p.a, far], color: "#9ca3af", width: 5, legend: "slot" },
    { kind: "line", pts: [p.o, p.a], color: "#111827", width: 4, legend: "crank OA" },
    { kind: "line", pts: [p.b, p.a, p.c], color: "#c2410c", width: 4, legend: "lever BAC" },
    { kind: "line", pts: [p.o, p.d], color: "#7c3aed", width: 4, legend: "crank OD" },
    { kind: "circle", c: p.b, r, color: "#c2410c", fill: "rgba(194,65,12,0.15)" },
    { kind: "circle", c: p.c, r, color: "#c2410c", fill: "rgba(194,65,12,0.15)" },
    ...[p.o, p.a, p.d].map((q) => ({ kind: "circle", c: q, r: 0, minPx: 4, color: "#111827", fill: "#fff" })),
    ...[["O", p.o], ["A", p.a], ["B", p.b], ["C", p.c], ["D", p.d]].map(([t, q]) => ({ kind: "label", at: q, text: t })),
  ];
  dobby.scene.setItems(items, dobby.bounds);
  for (const ch of [dobby.phi, dobby.omega, dobby.mu]) { ch.markerX = p.phi2_deg; ch.draw(); }
}

// ---------------------------------------------------------------- elastic dynamics

const dyn = { inflight: false, queued: false, sweepDirty: true, cycleToml: null, lastSweep: null };

async function initDynamics() {
  const root = $("#dynamics-root");
  let example;
  try { example = await api("/dynamics/example"); } catch (e) { status("dynamics: " + e.message, true); return; }
  dyn.cycleToml = example.cycle_toml;
  const source = el("select", { id: "dyn-source" },
    el("option", { value: "example", textContent: "heald-frame example cycle" }),
    el("option", { value: "law", textContent: "a catalogue law: rise–dwell–return–dwell" }),
    el("option", { value: "file", textContent: "a cycle file (TOML) …" }));
  const law = el("select", { id: "dyn-law" });
  try { for (const l of (await api("/laws")).laws) law.append(el("option", { value: l.name, textContent: l.name })); } catch (e) { status("laws: " + e.message, true); }
  law.value = "modified-sine";
  const dynRoute = "/api/dynamics/response";
  const stroke = el("input", { type: "number", step: "any", value: "100", id: "dyn-stroke" });
  const motion = el("input", { type: "number", step: "any", value: "120", id: "dyn-motion" });
  applyLimits(stroke, dynRoute, "law.stroke_mm");
  applyLimits(motion, dynRoute, "law.motion_deg");
  const file = el("input", { type: "file", accept: ".toml,text/plain", id: "dyn-file" });
  const fileName = el("span", { className: "hint", textContent: "" });
  const lawBox = el("div", { className: "grid2", hidden: true }, el("label", {}, "law", law), el("label", {}, "stroke (mm)", stroke), el("label", {}, "motion angle, rise and return (°)", motion));
  const fileBox = el("div", { hidden: true }, el("label", { className: "file" }, "load a cycle file", file), fileName);
  const changed = () => { dyn.sweepDirty = true; respond(); };
  const commit = () => dyn.history.commit();
  const showSource = () => { lawBox.hidden = source.value !== "law"; fileBox.hidden = source.value !== "file"; };
  source.addEventListener("change", () => {
    showSource();
    if (source.value === "file" && !dyn.fileText) { file.click(); return; }
    changed();
    commit();
  });
  for (const e of [law, stroke, motion]) e.addEventListener("change", () => { changed(); commit(); });
  file.addEventListener("change", async () => {
    const f = file.files[0]; if (!f) return;
    dyn.fileText = await f.text(); fileName.textContent = f.name; changed();
  });
  dyn.source = source; dyn.law = law; dyn.stroke = stroke; dyn.motion = motion;
  dyn.values = { speed_rpm: example.speed_rpm, natural_hz: example.natural_hz, damping_ratio: example.damping_ratio };
  // The sliders' spans are the view's (the speeds, frames and damping of looms); the fields beside
  // them take the library's ranges from the request schema.
  const speed = sliderWithNumber("dyn-speed", "main-shaft speed", "rpm", 50, 1500, 1, example.speed_rpm, (v) => { dyn.values.speed_rpm = v; respond(); }, commit, { route: dynRoute, path: "speed_rpm" });
  const fn = sliderWithNumber("dyn-fn", "natural frequency of the frame f_n", "Hz", 5, 300, 0.5, example.natural_hz, (v) => { dyn.values.natural_hz = v; changed(); }, commit, { route: dynRoute, path: "natural_hz" });
  const zeta = sliderWithNumber("dyn-zeta", "damping ratio ζ", "–", 0, 0.5, 0.005, example.damping_ratio, (v) => { dyn.values.damping_ratio = v; changed(); }, commit, { route: dynRoute, path: "damping_ratio" });
  dyn.speedW = speed; dyn.fnW = fn; dyn.zetaW = zeta;
  const steady = el("input", { type: "checkbox", id: "dyn-steady" });
  steady.addEventListener("change", () => { changed(); commit(); });
  dyn.steady = steady;
  const from = el("input", { type: "number", step: "any", value: "100", id: "dyn-from", className: "short" });
  const to = el("input", { type: "number", step: "any", value: "1200", id: "dyn-to", className: "short" });
  applyLimits(from, dynRoute, "sweep.from_rpm");
  applyLimits(to, dynRoute, "sweep.to_rpm");
  for (const e of [from, to]) e.addEventListener("change", () => { changed(); commit(); });
  dyn.from = from; dyn.to = to;
  // The state in the address; a loaded cycle file is not (it stays in the page only).
  dyn.history = viewHistory("dynamics", () => ({
    source: source.value === "file" ? "example" : source.value, law: law.value, stroke_mm: stroke.value, motion_deg: motion.value,
    ...dyn.values, steady: steady.checked, sweep_from_rpm: from.value, sweep_to_rpm: to.value,
  }), (st) => {
    source.value = st.source; law.value = st.law; stroke.value = st.stroke_mm; motion.value = st.motion_deg;
    dyn.values = { speed_rpm: st.speed_rpm, natural_hz: st.natural_hz, damping_ratio: st.damping_ratio };
    speed.set(st.speed_rpm); fn.set(st.natural_hz); zeta.set(st.damping_ratio);
    steady.checked = !!st.steady; from.value = st.sweep_from_rpm; to.value = st.sweep_to_rpm;
    showSource();
    changed();
  });
  const panel = el("div", { className: "panel" }, el("h2", { textContent: "Cycle and frame" }),
    el("p", { className: "hint", textContent: "The frame as a mass on a spring and damper driven through the cycle, solved exactly. Move the speed: the vibration left in the dwells (shaded) is redrawn; the sweep shows the speeds to avoid." }),
    el("label", { className: "wide" }, "cycle", source), lawBox, fileBox, fn.label, zeta.label, speed.label,
    el("label", { className: "check" }, steady, "periodic steady state (else one cycle from rest)"),
    el("div", { className: "row" }, "sweep from", from, "to", to, "rpm"));
  const table = el("table", { className: "data", id: "dyn-summary" }, el("caption", { textContent: "Response" }), el("tbody"));
  const charts = el("div", { className: "grid-charts" });
  root.append(el("div", { className: "results" }, panel, table), charts);
  const ax = { label: "main-shaft angle", unit: "°", range: [0, 360], step: 30 };
  dyn.pos = new Chart(charts, { id: "dyn-pos", title: "Position", height: 220, x: ax, y: { label: "position", unit: "mm" } });
  dyn.err = new Chart(charts, { id: "dyn-err", title: "Dynamic error x − s (dwells shaded)", height: 220, x: ax, y: { label: "x − s", unit: "mm" } });
  dyn.acc = new Chart(charts, { id: "dyn-acc", title: "Acceleration of the frame", height: 220, x: ax, y: { label: "x''", unit: "m/s²" } });
  dyn.sweep = new Chart(charts, { id: "dyn-sweep", title: "Speed sweep: residual vibration", height: 220, x: { label: "main-shaft speed", unit: "rpm" }, y: { label: "amplitude", unit: "mm", includeZero: true } });
  Object.assign(loomkin.charts, { dyn_pos: dyn.pos, dyn_err: dyn.err, dyn_acc: dyn.acc, dyn_sweep: dyn.sweep });
  respond();
  dyn.history.ready();
}

// The input a refused dynamics request names.
function dynField(path) {
  const map = [["speed_rpm", dyn.speedW.field, "main-shaft speed"], ["natural_hz", dyn.fnW.field, "natural frequency"],
    ["damping_ratio", dyn.zetaW.field, "damping ratio"], ["law.stroke_mm", dyn.stroke, "stroke"], ["law.motion_deg", dyn.motion, "motion angle"],
    ["law.law", dyn.law, "law"], ["sweep.from_rpm", dyn.from, "sweep from"], ["sweep.to_rpm", dyn.to, "sweep to"], ["sweep", dyn.from, "sweep"],
    ["cycle_toml", dyn.source, "cycle file"]];
  const hit = map.find(([k]) => path === k || path.startsWith(k + ".") || path.startsWith(k + "["));
  return hit ? { inputs: [hit[1]], label: hit[2] } : null;
}

function dynRequest() {
  const q = { speed_rpm: dyn.values.speed_rpm, natural_hz: dyn.values.natural_hz, damping_ratio: dyn.values.damping_ratio, steady: dyn.steady.checked };
  if (dyn.source.value === "law") q.law = { law: { name: dyn.law.value, params: {} }, stroke_mm: +dyn.stroke.value, motion_deg: +dyn.motion.value };
  else if (dyn.source.value === "file" && dyn.fileText) q.cycle_toml = dyn.fileText;
  if (dyn.sweepDirty) q.sweep = { from_rpm: +dyn.from.value, to_rpm: +dyn.to.value, points: 400 };
  return q;
}

function respond() {
  if (dyn.inflight) { dyn.queued = true; return; }
  dyn.inflight = true;
  const q = dynRequest();
  api("/dynamics/response", q)
    .then((r) => {
      if (q.sweep) dyn.sweepDirty = false;
      clearFieldErrors();
      const c = r.curves, u = r.unit, rep = r.report;
      for (const ch of [dyn.pos, dyn.err]) ch.opts.y.unit = u;
      dyn.acc.opts.y.unit = r.acceleration_unit;
      dyn.err.bands = r.dwells_deg;
      dyn.pos.setSeries([{ label: "input s (rigid law)", x: c.angle_deg, y: c.s, dash: [6, 4] }, { label: "frame x", x: c.angle_deg, y: c.x }]);
      dyn.err.setSeries([{ label: "x − s", x: c.angle_deg, y: c.error }]);
      dyn.acc.setSeries([{ label: "frame x''", x: c.angle_deg, y: c.a }]);
      if (r.sweep) {
        dyn.lastSweep = r.sweep;
        dyn.sweep.opts.y.unit = u;
        dyn.sweep.setSeries([{ label: "residual amplitude", x: r.sweep.speed_rpm, y: r.sweep.residual_amplitude }, { label: "peak |x − s|", x: r.sweep.speed_rpm, y: r.sweep.peak_dynamic_error, dash: [6, 4] }]);
      }
      dyn.sweep.markerX = rep.speed_rpm; dyn.sweep.draw();
      const rows = [
        ["residual vibration (largest over the dwells)", `${num(rep["residual_amplitude_" + u], 4)} ${u} (${num(rep.residual_amplitude_pct_of_stroke, 3)} % of stroke)`, "dyn-residual"],
        ["peak dynamic error |x − s|", `${num(rep["peak_dynamic_error_" + u], 4)} ${u} at ${num(rep.peak_dynamic_error_at_deg, 1)}°`],
        ["peak acceleration |x''|", `${num(rep["peak_acceleration_" + (u === "mm" ? "m_s2" : "rad_s2")], 1)} ${r.acceleration_unit} (rigid law ${num(rep["peak_input_acceleration_" + (u === "mm" ? "m_s2" : "rad_s2")], 1)})`],
        ["rigidity ratio f_n / f_shaft", `${num(rep.rigidity_ratio, 2)}${rep.rigidity_warning ? " — below 10 (VDI 2149): the rigid law does not describe the motion" : ""}`, "dyn-rigidity"],
      ];
      $("#dyn-summary tbody").replaceChildren(...rows.map(([k, v, id]) => el("tr", {}, el("th", { textContent: k }), el("td", { textContent: v, id: id || "" }))));
      status(`response at ${num(rep.speed_rpm)} rpm`);
    })
    .catch((e) => showFieldError("dynamics", e, dynField))
    .finally(() => { dyn.inflight = false; if (dyn.queued) { dyn.queued = false; respond(); } });
}

// ---------------------------------------------------------------- start

const VIEWS = { servo: initServo, catalogue: initCatalogue, shed: initShed, picking: initPicking, dobby: initDobby, dynamics: initDynamics };
window.LoomkinViews = VIEWS;
// Views in files of their own (cam.js, loom.js) register here: they load after this file and
// before the tabs are built (start waits for /api/info).
window.LoomkinApp = {
  api, status, download, el, num, convert, sliderWithNumber, loomkin,
  register(name, title, init) { VIEWS[name] = init; VIEW_TITLES[name] = title; },
};

async function start() {
  await loadSchemas();
  applyLimits($("#cam-rows"), "/api/servo/export", "rows");
  let views = ["servo", "catalogue"];
  try { const info = await api("/info"); views = info.views; loomkin.limits = info.limits; } catch (e) { status("info: " + e.message, true); }
  const tabs = $("#tabs");
  for (const v of views) {
    const b = el("button", { type: "button", textContent: VIEW_TITLES[v] || v, role: "tab" });
    b.dataset.view = v;
    b.addEventListener("click", () => showView(v));
    tabs.append(b);
  }
  $("#undo").addEventListener("click", undo);
  $("#redo").addEventListener("click", redo);
  const want = parseHash(location.hash).view;
  showView(views.includes(want) ? want : views[0], views.includes(want));
  loomkin.ready = true;
}

start();
})();
