// loomkin workbench: the servo shedding view — one servo motor per heald frame on a shared DC bus
// ([shedding] drive = "servo"): the frames × picks lift grid from the pattern, every frame's motor
// torque and the bus power over the repeat, the per-frame table (peak and RMS torque, peak speed,
// the motor check with its least margin), and Optimise: `loom servo --optimize` (every frame's
// stagger and motion angle for the least peak bus power or RMS torque), shown before → after.
// Every number comes from POST /api/loom/servo/view (the figures of `loomkin loom servo --json`);
// the page only draws them. Written for loomkin.
(() => {
"use strict";

const { Chart, addTools } = window.LoomkinCharts;
const { api, status, el, num, convert, loomkin, register } = window.LoomkinApp;
const { viewHistory, showFieldError, clearFieldErrors, applyLimits, refuseField, loomPatternPicker, newest, FRAME_COLOURS } = window.LoomkinShared;

const es = { inflight: false, queued: false, result: null, optimum: null, picker: null };
const ROUTE = "/loom/servo/view";
const EXAMPLE = "servo-shedding-loom.toml";
const CHECK_NAMES = { peak_torque: "peak torque", rms_torque: "RMS torque", peak_speed: "peak speed", torque_speed_envelope: "torque–speed envelope", inertia_ratio: "inertia ratio" };

async function initEshed() {
  const panel = document.querySelector("#eshed-panel");
  const root = document.querySelector("#eshed-root");
  let ex;
  try { ex = await api("/loom/examples"); } catch (e) { status("servo shedding: " + e.message, true); return; }
  es.examples = ex;
  const picker = loomPatternPicker(ex, { loom: "eshed-loom", pattern: "eshed-pattern", loomUpload: "eshed-loom-upload", patternUpload: "eshed-pattern-upload" },
    EXAMPLE, () => changed());
  es.picker = picker;
  const { loomSel, patSel } = picker;
  const objective = el("select", { id: "eshed-objective" }, el("option", { value: "peak", textContent: "peak bus power" }), el("option", { value: "rms", textContent: "worst frame's RMS torque" }));
  const optimise = el("button", { type: "button", id: "eshed-optimise", textContent: "Optimise" });
  // The least clearance the search keeps (--min-clearance-mm): the request schema's limits (the
  // library's descriptor); blank, the library's default.
  const minClear = el("input", { type: "number", step: "any", id: "eshed-min-clearance", className: "short" });
  applyLimits(minClear, "/api/loom/servo/view", "min_clearance_mm");
  minClear.setAttribute("aria-label", "least clearance kept (mm)");
  const shown = el("select", { id: "eshed-shown", disabled: true }, el("option", { value: "after", textContent: "the optimum" }), el("option", { value: "before", textContent: "the loom file's design" }));
  const gain = el("table", { className: "data", id: "eshed-gain" }, el("caption", { textContent: "Before → after" }), el("tbody"));
  gain.hidden = true;
  panel.append(
    el("h2", { textContent: "Loom and pattern" }),
    el("p", { className: "hint", textContent: "A loom file with [shedding] drive = \"servo\": each frame's motor follows its own law over the repeat, a move on every change of the pattern. 0° = beat-up of the first pick." }),
    ...picker.nodes,
    el("h2", { textContent: "Optimise" }),
    el("p", { className: "hint", textContent: "Every frame's stagger (within ±shedding.max_stagger_deg) and motion angle, keeping the carrier's insertion clear in every pick (loom servo --optimize). It runs for seconds; cancel it from the progress line." }),
    el("div", { className: "row" }, "least clearance kept", minClear, "mm"),
    el("div", { className: "row wrap" }, objective, optimise),
    el("label", { className: "wide" }, "draw", shown),
    gain);

  const summary = el("table", { className: "data", id: "eshed-summary" }, el("caption", { textContent: "Bus" }), el("tbody"));
  const gridWrap = el("div", { className: "chart", id: "eshed-grid" });
  const gridCanvas = el("canvas", { role: "img", ariaLabel: "lift plan: frames by picks, raised cells filled" });
  gridWrap.append(gridCanvas);
  es.gridChart = { wrap: gridWrap, canvas: gridCanvas, ctx: gridCanvas.getContext("2d"), hoverX: null,
    draw: () => drawGrid(), resetView: () => drawGrid(), fileStem: () => "servo-lift-plan",
    toSVG: () => window.LoomkinCharts.renderSVG(es.gridChart), toCSV: liftCSV };
  addTools(es.gridChart, ["png", "svg", "csv"]);
  root.append(el("div", { className: "results" }, summary, gridWrap));
  const charts = el("div", { className: "charts" });
  root.append(charts);
  const ang = { label: "main-shaft angle over the repeat (0 = beat-up of pick 1)", unit: "°" };
  es.torque = new Chart(charts, { id: "eshed-torque", title: "Motor torque of each frame", height: 260, x: { ...ang }, y: { label: "torque", unit: "N·m", includeZero: true } });
  es.bus = new Chart(charts, { id: "eshed-bus", title: "Power on the DC bus", height: 240, x: { ...ang }, y: { label: "bus power", unit: "W", includeZero: true } });
  const frames = el("table", { className: "data", id: "eshed-frames" }, el("caption", { textContent: "Frames (front first)" }),
    el("thead", {}, el("tr", {}, ...["frame", "moves", "motion (°)", "peak torque (N·m)", "RMS torque (N·m)", "peak speed (rpm)", "peak power (W)", "motor", "least margin"].map((t) => el("th", { textContent: t })))), el("tbody"));
  root.append(frames);
  Object.assign(loomkin.charts, { eshed_torque: es.torque, eshed_bus: es.bus });
  if (window.ResizeObserver) new ResizeObserver(() => drawGrid()).observe(gridCanvas);
  es.inputs = { loomSel, patSel, objective, minClear, optimise, shown };

  const commit = () => es.history.commit();
  const changed = () => { resetOptimum(); evaluate(); commit(); };
  objective.addEventListener("change", commit);
  minClear.addEventListener("change", commit);
  optimise.addEventListener("click", runOptimise);
  shown.addEventListener("change", () => { if (es.optimum) render(); });

  es.history = viewHistory("eshed", () => {
    const st = {
      ...picker.state(),
      objective: objective.value,
      min_clearance_mm: minClear.value,
    };
    return st;
  }, (st) => {
    const moved = picker.restore(st);
    if (st.objective) objective.value = st.objective;
    minClear.value = st.min_clearance_mm || "";
    if (moved || !es.result) { resetOptimum(); evaluate(); }
  });
  evaluate();
  es.history.ready();
}

// The request the view sends (for tests and the console): the loom and the pattern; `optimize`,
// the objective and the least clearance (when one is typed) for the search.
loomkin.eshedRequest = (optimize) => {
  const i = es.inputs, q = {};
  es.picker.source(q);
  if (optimize) {
    q.optimize = true; q.objective = i.objective.value;
    if (i.minClear.value !== "") q.min_clearance_mm = +i.minClear.value;
  }
  return q;
};
loomkin.eshedView = () => ({ result: es.result, optimum: es.optimum });

function eshedField(path) {
  const i = es.inputs;
  const map = [["pattern", i.patSel, "weave pattern"], ["loom_toml", i.loomSel, "loom file"], ["objective", i.objective, "objective"],
    ["min_clearance_mm", i.minClear, "least clearance kept"],
    ["shedding", i.loomSel, "loom file"]];
  const hit = map.find(([k]) => path === k || path.startsWith(k + ".") || path.startsWith(k + "["));
  return hit ? { inputs: [hit[1]], label: hit[2] } : null;
}

// The pattern's lifts as CSV: one row per frame, 1 where it is raised at each pick.
function liftCSV() {
  const g = es.result && es.result.lifts;
  if (!g) return "frame\n";
  const lines = [["frame", ...Array.from({ length: g.picks }, (_, p) => `pick ${p + 1} raised (0/1)`)].join(",")];
  g.up.forEach((row, i) => lines.push([i + 1, ...row.map((b) => (b ? 1 : 0))].join(",")));
  return lines.join("\n") + "\n";
}

function resetOptimum() {
  es.optimum = null;
  // A search still running is for the loom and pattern no longer shown: its answer is dropped.
  newest.drop("eshed-optimise");
  es.inputs.shown.disabled = true;
  document.querySelector("#eshed-gain").hidden = true;
}

function evaluate() {
  if (es.inflight) { es.queued = true; return; }
  const q = loomkin.eshedRequest(false);
  es.inflight = true;
  const t0 = performance.now();
  api(ROUTE, q)
    .then((r) => { clearFieldErrors(); es.result = r; render(); status(`servo shedding evaluated in ${(performance.now() - t0).toFixed(0)} ms`); })
    .catch((e) => showFieldError("servo shedding", e, eshedField))
    .finally(() => { es.inflight = false; if (es.queued) { es.queued = false; evaluate(); } });
}

// The search: one in flight (the button and the loom and pattern wait for it); the server stops
// it when the page cancels it (the progress line) or goes away.
async function runOptimise() {
  const i = es.inputs;
  // A field that holds no number is refused here; a number out of range by the API, naming the
  // field (the library's range and message).
  if (i.minClear.validity && i.minClear.validity.badInput) { refuseField("servo shedding", i.minClear, "least clearance kept: is not a number"); return; }
  const current = newest("eshed-optimise");
  const q = loomkin.eshedRequest(true);
  for (const x of [i.optimise, i.loomSel, i.patSel, i.objective, i.minClear]) x.disabled = true;
  status("servo shedding: optimising every frame's stagger and motion angle…");
  const t0 = performance.now();
  try {
    const r = await api(ROUTE, q);
    if (current()) {
      clearFieldErrors();
      es.optimum = r;
      i.shown.disabled = false; i.shown.value = "after";
      render();
      es.history.commit();
      status(`servo shedding optimised in ${convert(performance.now() - t0, "ms", "s").toFixed(1)} s (${r.result.evaluations} evaluations)`);
    }
  } catch (e) { if (current()) showFieldError("servo shedding", e, eshedField); }
  for (const x of [i.optimise, i.loomSel, i.patSel, i.objective, i.minClear]) x.disabled = false;
}

// The answer drawn: the optimum's (or the design before it, as chosen) when there is one.
function render() {
  const base = es.result;
  if (!base) return;
  const opt = es.optimum, before = opt && es.inputs.shown.value === "before";
  const rep = opt ? opt.result : base.result;
  const curves = opt ? (before ? opt.curves_before : opt.curves) : base.curves;
  const frames = before ? base.result.frames : rep.frames;
  const bus = before ? base.result : rep;
  const period = rep.repeat_deg;
  for (const ch of [es.torque, es.bus]) { ch.opts.x.range = [0, period]; ch.opts.x.step = period > 1440 ? 360 : 90; }
  const n = curves.torque_n_m.length;
  const named = (i) => n <= 8 || i === 0 || i === n - 1;
  es.torque.setSeries(curves.torque_n_m.map((t, i) => ({ label: named(i) ? `frame ${i + 1}${n > 8 ? (i === 0 ? " (front)" : " (back)") : ""}` : "", x: curves.angle_deg, y: t, color: FRAME_COLOURS[i % FRAME_COLOURS.length], width: 1.1 })));
  const series = [];
  if (opt) {
    const other = before ? opt.curves : opt.curves_before;
    series.push({ label: before ? "the optimum" : "the loom file's design", x: other.angle_deg, y: other.bus_power_w, color: "#9ca3af", width: 1.1 });
  }
  series.push({ label: opt ? (before ? "the loom file's design" : "the optimum") : "bus", x: curves.angle_deg, y: curves.bus_power_w, color: "#111827", width: 1.5 },
    { label: `peak ${num(bus.peak_bus_power_w, 1)} W at ${num(bus.peak_bus_power_at_deg, 1)}°`, mode: "markers", radius: 5, x: [bus.peak_bus_power_at_deg], y: [bus.peak_bus_power_w], color: "#dc2626" });
  es.bus.hlines = bus.braking_resistor_max_w !== undefined && bus.braking_resistor_max_w !== null ? [{ y: -bus.braking_resistor_max_w, label: `braking resistor limit −${num(bus.braking_resistor_max_w, 1)} W` }] : [];
  es.bus.setSeries(series);
  const cs = bus.clear_shed;
  const rows = [
    ["loom", `${base.loom || "loom file"}: ${frames.length} frames at ${num(rep.speed_rpm)} rpm`],
    ["repeat", `${rep.picks} picks (${num(period)}°, ${num(rep.repeat_s, 4)} s)${rep.pass_through ? ", consecutive changes without a stop" : ""}`],
    ["peak bus power", `${num(bus.peak_bus_power_w, 1)} W at ${num(bus.peak_bus_power_at_deg, 2)}° (${num(bus.peak_bus_current_a, 2)} A)`, "eshed-peak-bus"],
    ["mean bus power", `${num(bus.mean_bus_power_w, 1)} W`],
    ["regenerated", `${num(bus.regenerated_energy_j, 3)} J per repeat`],
    ["to the braking resistor", `${num(bus.braking_energy_j, 3)} J per repeat (peak ${num(bus.peak_braking_power_w, 1)} W)`],
    ["motors", bus.motors_ok ? "every frame's motor passes" : "a frame's motor FAILS", "eshed-motors"],
  ];
  if (cs) rows.push(["shed clears the carrier", `${num(cs.window_open_deg, 2)}° → ${num(cs.window_close_deg, 2)}° (${num(cs.window_deg, 2)}°), least clearance ${num(cs.min_clearance_mm, 2)} mm`]);
  if (opt) rows.push(["drawn", before ? "the loom file's design" : "the optimum"]);
  document.querySelector("#eshed-summary tbody").replaceChildren(...rows.map(([k, v, id]) => {
    const td = el("td", { textContent: v, id: id || "" });
    if (id === "eshed-motors" && !bus.motors_ok) td.style.color = "#b91c1c";
    return el("tr", {}, el("th", { textContent: k }), td);
  }));
  document.querySelector("#eshed-frames tbody").replaceChildren(...frames.map((f) => {
    const worst = f.checks.reduce((a, c) => (a === null || c.margin < a.margin ? c : a), null);
    const tr = el("tr", {}, ...[String(f.frame), String(f.moves), num(f.motion_deg, 2), num(f.peak_torque_n_m, 3), num(f.rms_torque_n_m, 3), num(f.peak_speed_rpm, 1), num(f.peak_power_w, 1),
      f.motor_ok ? "ok" : "FAILS", worst ? `${num(100 * worst.margin, 1)} % ${CHECK_NAMES[worst.name] || worst.name}` : ""].map((v) => el("td", { textContent: v })));
    if (!f.motor_ok) tr.style.color = "#b91c1c";
    return tr;
  }));
  const gain = document.querySelector("#eshed-gain");
  gain.hidden = !opt;
  if (opt) {
    const o = opt.result;
    const g = [
      ["peak bus power", `${num(o.peak_bus_power_w_before, 1)} → ${num(o.peak_bus_power_w_after, 1)} W`, "eshed-gain-peak"],
      ["worst RMS torque", `${num(o.worst_rms_torque_n_m_before, 3)} → ${num(o.worst_rms_torque_n_m_after, 3)} N·m`],
      ["clear-shed window", `${num(o.window_deg_before, 2)} → ${num(o.window_deg_after, 2)}°`],
      ["least clearance", `${num(o.min_clearance_mm_before, 2)} → ${num(o.min_clearance_mm_after, 2)} mm`],
      ["least clearance kept", `${num(o.min_clearance_kept_mm)} mm`, "eshed-gain-kept"],
      ["search", `${o.evaluations} evaluations, ${o.clearance_checks} clearance checks`],
      ["stagger (°)", o.stagger_deg.map((v) => num(v, 2)).join(", ")],
      ["motion angle (°)", o.motion_deg.map((v) => num(v, 2)).join(", ")],
    ];
    gain.querySelector("tbody").replaceChildren(...g.map(([k, v, id]) => el("tr", {}, el("th", { textContent: k }), el("td", { textContent: v, id: id || "" }))));
  }
  drawGrid();
}

// The lift plan: frames down (front frame at the top), picks across, raised cells filled.
function drawGrid() {
  const r = es.result, cv = es.gridChart && es.gridChart.canvas;
  if (!r || !cv) return;
  const g = r.lifts, maxCols = Math.min(g.picks, 200);
  const w = cv.clientWidth || 300;
  const x0 = 40, y0 = 28;
  const cell = Math.max(2, Math.min(16, Math.floor((w - x0 - 6) / maxCols), Math.floor(300 / g.frames)));
  const h = y0 + cell * g.frames + 8;
  cv.style.height = h + "px";
  const dpr = es.gridChart.pixelScale || window.devicePixelRatio || 1;
  const c = es.gridChart.ctx;
  if (c === cv.getContext("2d")) { cv.width = Math.round(w * dpr); cv.height = Math.round(h * dpr); }
  c.setTransform(dpr, 0, 0, dpr, 0, 0);
  c.clearRect(0, 0, w, h);
  c.font = "600 13px system-ui, sans-serif"; c.fillStyle = "#111827"; c.textBaseline = "middle"; c.textAlign = "left";
  c.fillText(`Lift plan: ${g.frames} frames × ${g.picks} picks` + (g.picks > maxCols ? ` (first ${maxCols} drawn)` : ""), 6, 12);
  c.font = "11px system-ui, sans-serif"; c.textAlign = "right";
  for (let i = 0; i < g.frames; i++) {
    c.fillStyle = "#4b5563";
    if (g.frames <= 12 || i % 4 === 0) c.fillText(String(i + 1), x0 - 4, y0 + cell * (i + 0.5));
    for (let p = 0; p < maxCols; p++) {
      c.fillStyle = g.up[i][p] ? FRAME_COLOURS[i % FRAME_COLOURS.length] : "#f3f4f6";
      c.fillRect(x0 + p * cell, y0 + i * cell, cell - (cell > 4 ? 1 : 0), cell - (cell > 4 ? 1 : 0));
    }
  }
}

register("eshed", "Servo shed", initEshed);
})();
