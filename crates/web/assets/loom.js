// loomkin workbench: the loom view — a loom file weaving a pattern: the pattern grid, the frames'
// lifts over the main-shaft angle, the shedding torque over the repeat (and with stagger), the
// timing diagram (shed open to the carrier against the insertion window). Written for loomkin.
(() => {
"use strict";

const { Chart, PALETTE, addTools } = window.LoomkinCharts;
const { api, status, download, el, num, loomkin, register } = window.LoomkinApp;
const { viewHistory, showFieldError, clearFieldErrors, loomPatternPicker, newest, FRAME_COLOURS } = window.LoomkinShared;

const loom = { inflight: false, queued: false, result: null, stagger: null, picker: null };

async function initLoom() {
  const panel = document.querySelector("#loom-panel");
  const root = document.querySelector("#loom-root");
  let ex;
  try { ex = await api("/loom/examples"); } catch (e) { status("loom: " + e.message, true); return; }
  loom.examples = ex;
  const picker = loomPatternPicker(ex, { loom: "loom-file", pattern: "loom-pattern", loomUpload: "loom-upload", patternUpload: "loom-pattern-upload" },
    null, () => { resetStagger(); evaluate(); loom.history.commit(); });
  loom.picker = picker;
  const { loomSel, patSel } = picker;
  const fromPick = el("input", { type: "number", min: "1", step: "1", value: "1", id: "loom-from-pick", className: "short" });
  const picks = el("input", { type: "number", step: "1", id: "loom-picks", className: "short" });
  window.LoomkinShared.applyLimits(picks, "/api/loom/evaluate", "picks");
  const objective = el("select", { id: "loom-objective" }, el("option", { value: "peak", textContent: "peak torque" }), el("option", { value: "rms", textContent: "RMS torque" }));
  const minClearance = el("input", { type: "number", step: "any", id: "loom-min-clearance", className: "short" });
  window.LoomkinShared.applyLimits(minClearance, "/api/loom/stagger", "min_clearance_mm");
  const optimise = el("button", { type: "button", id: "loom-optimise", textContent: "Optimise stagger" });
  const apply = el("input", { type: "checkbox", id: "loom-apply-stagger", disabled: true });
  const save = el("button", { type: "button", id: "loom-save", textContent: "Loom file with this stagger", disabled: true });
  const staggerNote = el("p", { className: "hint", id: "loom-stagger-note" });
  panel.append(
    el("h2", { textContent: "Loom and pattern" }),
    el("p", { className: "hint", textContent: "0° = beat-up; pick p is inserted in [360p, 360p + 360). Frames are numbered from the front." }),
    ...picker.nodes,
    el("h2", { textContent: "Timing diagram" }),
    el("div", { className: "row" }, "picks", fromPick, "to", el("span", { id: "loom-to-pick" }), "(", picks, "picks )"),
    el("h2", { textContent: "Stagger" }),
    el("p", { className: "hint", textContent: "Crossing-angle offsets per frame (or group) that lower the peak or RMS shedding torque while every pick keeps its insertion window." }),
    el("div", { className: "row wrap" }, objective, optimise),
    el("div", { className: "row" }, "keep a least clearance of", minClearance, "mm"),
    el("label", { className: "check" }, apply, "draw with the optimised stagger"),
    el("div", { className: "row wrap" }, save), staggerNote);

  const summary = el("table", { className: "data", id: "loom-summary" }, el("caption", { textContent: "Loom" }), el("tbody"));
  const frames = el("table", { className: "data", id: "loom-frames" }, el("caption", { textContent: "Frames (front first)" }),
    el("thead", {}, el("tr", {}, ...["frame", "fell (mm)", "stroke (mm)", "shed angle (°)", "max strain", "moves"].map((t) => el("th", { textContent: t })))), el("tbody"));
  const gridWrap = el("div", { className: "chart", id: "loom-grid" });
  const gridCanvas = el("canvas", { role: "img", ariaLabel: "weave pattern: picks by frames, raised frames filled" });
  gridWrap.append(gridCanvas);
  // The pattern grid saves as the charts do: PNG, SVG (drawn by the same code) and CSV (0/1 per frame).
  loom.gridChart = { wrap: gridWrap, canvas: gridCanvas, ctx: gridCanvas.getContext("2d"), hoverX: null,
    draw: () => drawGrid(), resetView: () => drawGrid(), fileStem: () => "loom-pattern",
    toSVG: () => window.LoomkinCharts.renderSVG(loom.gridChart), toCSV: patternCSV };
  addTools(loom.gridChart, ["png", "svg", "csv"]);
  root.append(el("div", { className: "results" }, summary, gridWrap));
  const charts = el("div", { className: "charts" });
  root.append(charts);
  const ang = { label: "main-shaft angle (0 = beat-up)", unit: "°" };
  loom.lifts = new Chart(charts, { id: "loom-lifts", title: "Frame positions from the level shed (colours as in the pattern)", height: 240, x: { ...ang }, y: { label: "lift", unit: "mm", includeZero: true } });
  loom.timing = new Chart(charts, { id: "loom-timing", title: "Timing: clear shed at the carrier (common window shaded)", height: 260, x: { ...ang }, y: { label: "height", unit: "mm", includeZero: true } });
  loom.torque = new Chart(charts, { id: "loom-torque", title: "Shedding torque over the repeat", height: 240, x: { label: "main-shaft angle over the repeat", unit: "°" }, y: { label: "torque", unit: "N·m", includeZero: true } });
  root.append(frames);
  Object.assign(loomkin.charts, { loom_lifts: loom.lifts, loom_timing: loom.timing, loom_torque: loom.torque });
  loom.grid = gridCanvas;
  if (window.ResizeObserver) new ResizeObserver(() => drawGrid()).observe(gridCanvas);
  loom.inputs = { loomSel, patSel, fromPick, picks, objective, apply, minClearance };

  // Every edit is recorded for undo and written into the address (#loom/<state>).
  const commit = () => loom.history.commit();
  for (const e of [fromPick, picks]) e.addEventListener("change", () => { evaluate(); commit(); });
  apply.addEventListener("change", () => { evaluate(); commit(); });
  objective.addEventListener("change", commit);
  minClearance.addEventListener("change", commit);
  optimise.addEventListener("click", runStagger);
  save.addEventListener("click", () => { if (loom.stagger) download("loom-staggered.toml", loom.stagger.loom_toml, "text/plain"); });
  loom.save = save;
  // The state: loom, pattern (a loaded file travels in it, see loomPatternPicker), the timing
  // picks, the objective and whether the optimised stagger is drawn. The stagger is kept while the
  // loom and pattern stay (it is computed, not stored).
  loom.history = viewHistory("loom", () => ({
    ...picker.state(),
    from_pick: fromPick.value, picks: picks.value, objective: objective.value, min_clearance_mm: minClearance.value, stagger_drawn: apply.checked,
  }), (st) => {
    if (picker.restore(st)) resetStagger();
    fromPick.value = st.from_pick; picks.value = st.picks; objective.value = st.objective;
    if (st.min_clearance_mm !== undefined) minClearance.value = st.min_clearance_mm;
    apply.checked = !!st.stagger_drawn && !!loom.stagger;
    evaluate();
  });
  evaluate();
  loom.history.ready();
}

// The pattern as CSV: one row per pick, 1 where the frame is raised (frames front first).
function patternCSV() {
  const g = loom.result && loom.result.pattern;
  if (!g) return "pick\n";
  const lines = [["pick", ...Array.from({ length: g.shafts }, (_, i) => `frame ${i + 1} raised (0/1)`)].join(",")];
  g.rows.forEach((row, p) => lines.push([p + 1, ...row.map((b) => (b ? 1 : 0))].join(",")));
  return lines.join("\n") + "\n";
}

// The input a refused request names.
function loomField(path) {
  const i = loom.inputs;
  const map = [["picks", i.picks, "picks"], ["from_pick", i.fromPick, "first pick"], ["pattern", i.patSel, "weave pattern"],
    ["loom_toml", i.loomSel, "loom file"], ["stagger_deg", i.apply, "stagger"], ["objective", i.objective, "objective"], ["min_clearance_mm", i.minClearance, "least clearance"]];
  const hit = map.find(([k]) => path === k || path.startsWith(k + ".") || path.startsWith(k + "["));
  return hit ? { inputs: [hit[1]], label: hit[2] } : null;
}

function source() {
  return loom.picker.source({});
}

function resetStagger() {
  // A search still running is for the loom and pattern no longer shown: its answer is dropped.
  newest.drop("loom-stagger");
  loom.stagger = null;
  loom.inputs.apply.checked = false; loom.inputs.apply.disabled = true; loom.save.disabled = true;
  document.querySelector("#loom-stagger-note").textContent = "";
}

// The first pick is counted from 1 here (as the pattern grid numbers them), from 0 by the API;
// the number of picks goes as typed: the API refuses what it cannot draw, naming the field.
// The view's examples and last answer, for tests and the console.
loomkin.loomView = () => ({ examples: loom.examples, result: loom.result });

loomkin.loomRequest = () => {
  const i = loom.inputs, q = source();
  q.from_pick = +i.fromPick.value - 1;
  q.picks = i.picks.value.trim() === "" ? NaN : +i.picks.value;
  q.step_deg = 1;
  if (i.apply.checked && loom.stagger) q.stagger_deg = loom.stagger.result.best.stagger_deg;
  return q;
};

function evaluate() {
  if (loom.inflight) { loom.queued = true; return; }
  const q = loomkin.loomRequest();
  // A first pick that is no pick number is refused here, in the page's numbering.
  const refuse = (input, label, text) => {
    const e = new Error(`${input.value || "(empty)"} ${text}`);
    e.field = label;
    showFieldError("loom", e, () => ({ inputs: [input], label }));
  };
  if (!Number.isInteger(q.from_pick) || q.from_pick < 0) { refuse(loom.inputs.fromPick, "first pick", "is not a pick number: a whole number from 1"); return; }
  if (!Number.isInteger(q.picks)) { refuse(loom.inputs.picks, "picks", `is not a whole number: allowed ${loom.inputs.picks.min} … ${loom.inputs.picks.max}`); return; }
  loom.inflight = true;
  const t0 = performance.now();
  api("/loom/evaluate", q)
    .then((r) => { clearFieldErrors(); loom.result = r; render(r); status(`loom evaluated in ${(performance.now() - t0).toFixed(0)} ms`); })
    .catch((e) => showFieldError("loom", e, loomField))
    .finally(() => { loom.inflight = false; if (loom.queued) { loom.queued = false; evaluate(); } });
}

function render(r) {
  const rep = r.report, t = r.timing;
  const first = t.angle_deg[0], last = t.angle_deg[t.angle_deg.length - 1];
  document.querySelector("#loom-to-pick").textContent = String(Math.round(last / 360));
  for (const ch of [loom.lifts, loom.timing]) { ch.opts.x.range = [first, last]; ch.opts.x.step = last - first > 1440 ? 180 : 90; }
  const shown = t.moving_frames.length ? t.moving_frames : t.lift_mm.map((_, i) => i);
  // Many frames: name the front and back frames only (the colours follow the pattern grid).
  const named = (i, k) => shown.length <= 8 || k === 0 || k === shown.length - 1;
  loom.lifts.setSeries(shown.map((i, k) => ({ label: named(i, k) ? `frame ${i + 1}${k === 0 ? " (front)" : k === shown.length - 1 ? " (back)" : ""}` : "", x: t.angle_deg, y: t.lift_mm[i], color: FRAME_COLOURS[i % FRAME_COLOURS.length], width: 1.4 })));
  // Timing: clear shed against the carrier; insertion (black) and the common clear window (pink) as bars under the axis.
  const bars = (spans, y, label, color) => spans.map((s, k) => ({ label: k ? "" : label, x: [s[0], s[1]], y: [y, y], color, width: 4, hover: false }));
  const hc = t.carrier_height_mm;
  loom.timing.bands = t.clear_window_deg;
  loom.timing.setSeries([
    { label: "clear shed at the carrier", x: t.angle_deg, y: t.clear_mm, color: PALETTE[0] },
    { label: "carrier height", x: [first, last], y: [hc, hc], color: "#c2410c", dash: [6, 4], hover: false },
    { label: "shed open to the carrier", x: t.angle_deg, y: t.open.map((o) => (o ? hc : 0)), color: "#15803d", width: 1.2 },
    ...bars(t.insertion_deg, -0.06 * Math.max(...t.clear_mm, hc), "insertion (entry → exit)", "#111827"),
    ...bars(t.pick_window_deg, -0.12 * Math.max(...t.clear_mm, hc), "each pick's clear window", "#db2777"),
    { label: "beat-up", mode: "markers", radius: 4, x: t.beat_up_deg, y: t.beat_up_deg.map(() => 0), color: "#f59e0b", hover: false },
  ]);
  const tq = [{ label: r.stagger_deg.some((s) => s !== 0) ? "this stagger" : "no stagger", x: r.torque.angle_deg, y: r.torque.torque_n_m, color: PALETTE[0], width: 1.2 }];
  if (loom.stagger) {
    const s = loom.stagger;
    tq.length = 0;
    tq.push({ label: "no stagger", x: s.torque_none.angle_deg, y: s.torque_none.torque_n_m, color: "#9ca3af", width: 1.2 },
      { label: "two groups 7.5°", x: s.torque_two_groups.angle_deg, y: s.torque_two_groups.torque_n_m, color: "#d97706", width: 1.2, dash: [5, 3] },
      { label: "optimised stagger", x: s.torque_best.angle_deg, y: s.torque_best.torque_n_m, color: PALETTE[0], width: 1.4 });
  }
  loom.torque.opts.x.range = [0, r.torque.angle_deg[r.torque.angle_deg.length - 1]];
  loom.torque.bands = [[first, last]];
  loom.torque.setSeries(tq);
  const rows = [
    ["loom", `${rep.loom || "loom file"} at ${num(rep.speed_rpm)} rpm`],
    ["pattern", `${r.pattern.picks} picks on ${r.pattern.shafts} shafts`],
    ["shedding law", `${rep.law} over ${num(rep.motion_deg)}°`],
    ["peak shedding torque", `${num(rep.peak_torque_n_m, 2)} N·m at ${num(rep.peak_angle_deg, 1)}°`, "loom-peak-torque"],
    ["RMS torque", `${num(rep.rms_torque_n_m, 2)} N·m`],
    ["shed clears the carrier", `${num(rep.window_open_deg, 2)}° → ${num(rep.window_close_deg, 2)}° (${num(rep.window_deg, 2)}°)`, "loom-window"],
    ["insertion (entry → exit)", `${num(rep.insertion_deg[0], 1)}° → ${num(rep.insertion_deg[1], 1)}°`],
    ["least clearance", `${num(rep.min_clearance_mm, 2)} mm`],
    ["highest loom speed", `${num(rep.max_speed_rpm, 1)} rpm (carrier ${num(rep.mean_speed_m_s, 2)} m/s)`],
    ["largest strain", `frame ${rep.max_strain_frame}`],
  ];
  document.querySelector("#loom-summary tbody").replaceChildren(...rows.map(([k, v, id]) => {
    const td = el("td", { textContent: v, id: id || "" });
    if (id === "loom-window" && rep.min_clearance_mm < 0) td.style.color = "#b91c1c";
    return el("tr", {}, el("th", { textContent: k }), td);
  }));
  document.querySelector("#loom-frames tbody").replaceChildren(...rep.frames.map((f) => el("tr", {},
    ...[String(f.frame), num(f.distance_mm, 1), num(f.stroke_mm, 2), num(f.shed_angle_deg, 3), f.max_strain.toExponential(3), String(f.moves)].map((v) => el("td", { textContent: v })))));
  drawGrid();
}

// The pattern grid: picks down, frames across (front frame left), raised cells filled; the picks of
// the timing diagram outlined.
function drawGrid() {
  const r = loom.result, cv = loom.grid;
  if (!r || !cv) return;
  const g = r.pattern, maxRows = Math.min(g.picks, 96);
  const w = cv.clientWidth || 300;
  const cell = Math.max(3, Math.min(16, Math.floor((w - 50) / g.shafts), Math.floor(360 / maxRows)));
  const h = 34 + cell * maxRows + 6;
  cv.style.height = h + "px";
  const dpr = loom.gridChart.pixelScale || window.devicePixelRatio || 1;
  const c = loom.gridChart.ctx;
  if (c === cv.getContext("2d")) { cv.width = Math.round(w * dpr); cv.height = Math.round(h * dpr); }
  c.setTransform(dpr, 0, 0, dpr, 0, 0);
  c.clearRect(0, 0, w, h);
  c.font = "600 13px system-ui, sans-serif"; c.fillStyle = "#111827"; c.textBaseline = "middle";
  c.fillText(`Pattern: ${g.picks} picks × ${g.shafts} frames` + (g.picks > maxRows ? ` (first ${maxRows} drawn)` : ""), 6, 12);
  const x0 = 40, y0 = 28;
  c.font = "11px system-ui, sans-serif"; c.fillStyle = "#4b5563"; c.textAlign = "right";
  for (let p = 0; p < maxRows; p++) {
    if (maxRows <= 24 || p % 4 === 0) c.fillText(String(p + 1), x0 - 4, y0 + cell * (p + 0.5));
    for (let i = 0; i < g.shafts; i++) {
      c.fillStyle = g.rows[p][i] ? FRAME_COLOURS[i % FRAME_COLOURS.length] : "#f3f4f6";
      c.fillRect(x0 + i * cell, y0 + p * cell, cell - (cell > 4 ? 1 : 0), cell - (cell > 4 ? 1 : 0));
    }
    c.fillStyle = "#4b5563";
  }
  const t = r.timing;
  const p0 = Math.round(t.angle_deg[0] / 360), p1 = Math.round(t.angle_deg[t.angle_deg.length - 1] / 360);
  if (p0 < maxRows) {
    c.strokeStyle = "#f59e0b"; c.lineWidth = 2;
    c.strokeRect(x0 - 1, y0 + p0 * cell - 1, g.shafts * cell + 1, (Math.min(p1, maxRows) - p0) * cell + 1);
  }
}

async function runStagger() {
  const btn = document.querySelector("#loom-optimise");
  btn.disabled = true;
  status("optimising the stagger…");
  const q = source();
  q.objective = loom.inputs.objective.value;
  // The least clearance as typed: the API refuses what is out of range, naming the field.
  const mc = loom.inputs.minClearance.value.trim();
  if (mc !== "") q.min_clearance_mm = +mc;
  // The stagger is of the loom and pattern sent: when another is chosen while the search runs, its
  // answer (or refusal) is not shown, nor drawn with the new one's frames.
  const current = newest("loom-stagger");
  try {
    const s = await api("/loom/stagger", q);
    if (!current()) { btn.disabled = false; return; }
    loom.stagger = s;
    loom.inputs.apply.disabled = false; loom.inputs.apply.checked = true; loom.save.disabled = !s.loom_toml;
    const b = s.result.best;
    document.querySelector("#loom-stagger-note").textContent =
      `${s.note}; window ${b.window_kept ? "kept" : "LOST"} (least clearance ${num(b.min_clearance_mm, 2)} mm). Stagger (°, front first): ${b.stagger_deg.map((v) => num(v, 2)).join(", ")}`;
    status("stagger optimised");
    evaluate();
    loom.history.commit();
  } catch (e) { if (current()) showFieldError("stagger", e, loomField); }
  btn.disabled = false;
}

register("loom", "Loom", initLoom);
})();
