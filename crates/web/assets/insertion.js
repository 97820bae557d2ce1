// loomkin workbench: the insertion view — the loom file's weft carrier (its [insertion] kind): the
// time budget (the highest loom speed, the carrier speed the loom's speed needs), the carrier across
// the reed against the main-shaft angle (the rapier's two heads and their transfer, the projectile's
// flight, the air jet's yarn tip), its clearance in the shed on the pattern's worst pick with the
// least value marked, and the air jet's relay plan. Every number comes from POST
// /api/insert/evaluate (the library's, as `loomkin insert … --json`); the page only draws them.
// Written for loomkin.
(() => {
"use strict";

const { Chart, PALETTE } = window.LoomkinCharts;
const { api, status, el, num, loomkin, register } = window.LoomkinApp;
const { viewHistory, showFieldError, clearFieldErrors, applyLimits, refuseField, loomPatternPicker } = window.LoomkinShared;

const ins = { inflight: false, queued: false, result: null, picker: null };
const ROUTE = "/api/insert/evaluate";
// The budget's inputs over the loom file's: request key, label, unit (the limits are the schema's).
const BUDGET_FIELDS = [
  ["reed_width_mm", "reed width", "mm"],
  ["carrier_length_mm", "carrier length", "mm"],
  ["window_deg", "insertion window", "°"],
  ["speed_m_s", "carrier mean speed", "m/s"],
  ["carrier_mass_g", "carrier mass", "g"],
];
const TRACK_COLOURS = { bringer: "#1d4ed8", taker: "#dc2626", projectile: "#1d4ed8", "yarn tip": "#1d4ed8", shuttle: "#1d4ed8" };

async function initInsertion() {
  const panel = document.querySelector("#insert-panel");
  const root = document.querySelector("#insert-root");
  let ex;
  try { ex = await api("/loom/examples"); } catch (e) { status("insertion: " + e.message, true); return; }
  ins.examples = ex;
  const picker = loomPatternPicker(ex, { loom: "insert-loom", pattern: "insert-pattern", loomUpload: "insert-loom-upload", patternUpload: "insert-pattern-upload" },
    null, () => changed());
  ins.picker = picker;
  const { loomSel, patSel } = picker;
  // A blank field takes the loom file's value (shown as its placeholder once an answer is in).
  const numField = (id, path) => {
    const f = el("input", { type: "number", step: "any", id, className: "short" });
    applyLimits(f, ROUTE, path);
    return f;
  };
  const speed = numField("insert-speed", "speed_rpm");
  const budget = {};
  for (const [key] of BUDGET_FIELDS) budget[key] = numField("insert-" + key.replace(/_/g, "-"), "budget." + key);
  const clearShed = el("input", { type: "checkbox", id: "insert-clear-shed" });
  panel.append(
    el("h2", { textContent: "Loom and pattern" }),
    el("p", { className: "hint", textContent: "The loom file's [insertion] kind names the carrier (shuttle, rapier, projectile, air jet); the clearance covers every pick of the pattern. 0° = beat-up." }),
    ...picker.nodes,
    el("div", { className: "row" }, "loom speed", speed, "rpm"),
    el("h2", { textContent: "Time budget" }),
    el("p", { className: "hint", textContent: "n = v̄·θ / (6·(W + L)): the highest loom speed for the reed width W, the carrier length L, the window θ and the carrier's mean speed v̄. A blank field takes the loom file's value." }),
    ...BUDGET_FIELDS.map(([key, label, unit]) => el("div", { className: "row" }, label, budget[key], unit)),
    el("label", { className: "check" }, clearShed, "window: the pattern's clear-shed window (as loom check finds it)"));

  const summary = el("table", { className: "data", id: "insert-summary" }, el("caption", { textContent: "Carrier" }), el("tbody"));
  const budgetTable = el("table", { className: "data", id: "insert-budget" }, el("caption", { textContent: "Time budget" }), el("tbody"));
  root.append(el("div", { className: "results" }, budgetTable, summary));
  const charts = el("div", { className: "charts" });
  root.append(charts);
  const ang = { label: "main-shaft angle in the pick's turn (0 = beat-up)", unit: "°" };
  ins.track = new Chart(charts, { id: "insert-track", title: "Carrier across the reed (in the shed shaded)", height: 260, x: { ...ang }, y: { label: "across the reed", unit: "mm", includeZero: true } });
  ins.clear = new Chart(charts, { id: "insert-clearance", title: "Clearance in the shed on the worst pick", height: 240, x: { ...ang }, y: { label: "clearance", unit: "mm", includeZero: true } });
  ins.relay = new Chart(charts, { id: "insert-relay", title: "Relay plan: each group's opening", height: 220, x: { ...ang }, y: { label: "relay group", unit: "", includeZero: true } });
  Object.assign(loomkin.charts, { insert_track: ins.track, insert_clearance: ins.clear, insert_relay: ins.relay });
  ins.inputs = { loomSel, patSel, speed, budget, clearShed };

  const commit = () => ins.history.commit();
  const changed = () => { evaluate(); commit(); };
  for (const f of [speed, ...Object.values(budget)]) f.addEventListener("change", changed);
  clearShed.addEventListener("change", changed);

  ins.history = viewHistory("insertion", () => {
    const st = {
      ...picker.state(),
      speed_rpm: speed.value, clear_shed_window: clearShed.checked, budget: {},
    };
    for (const [key] of BUDGET_FIELDS) st.budget[key] = budget[key].value;
    return st;
  }, (st) => {
    picker.restore(st);
    speed.value = st.speed_rpm || "";
    clearShed.checked = !!st.clear_shed_window;
    for (const [key] of BUDGET_FIELDS) budget[key].value = (st.budget || {})[key] || "";
    evaluate();
  });
  evaluate();
  ins.history.ready();
}

// The request the view sends (for tests and the console): blank fields are left out (the file's).
loomkin.insertRequest = () => {
  const i = ins.inputs, q = {};
  ins.picker.source(q);
  const given = (f) => f.value.trim() !== "";
  if (given(i.speed)) q.speed_rpm = +i.speed.value;
  q.budget = {};
  for (const [key] of BUDGET_FIELDS) if (given(i.budget[key])) q.budget[key] = +i.budget[key].value;
  q.clear_shed_window = i.clearShed.checked;
  return q;
};
loomkin.insertView = () => ({ result: ins.result });

// The input a refused request names.
function insertField(path) {
  const i = ins.inputs;
  const map = [["speed_rpm", i.speed, "loom speed"], ["pattern", i.patSel, "weave pattern"], ["loom_toml", i.loomSel, "loom file"],
    ...BUDGET_FIELDS.map(([key, label]) => ["budget." + key, i.budget[key], label])];
  const hit = map.find(([k]) => path === k || path.startsWith(k + ".") || path.startsWith(k + "["));
  return hit ? { inputs: [hit[1]], label: hit[2] } : null;
}

function evaluate() {
  // A field that holds no number is refused here; a number out of range is refused by the API,
  // naming the field (the library's range and message).
  const i = ins.inputs;
  for (const [f, label] of [[i.speed, "loom speed"], ...BUDGET_FIELDS.map(([key, label]) => [i.budget[key], label])]) {
    if (f.validity && f.validity.badInput) { refuseField("insertion", f, `${label}: is not a number`); return; }
  }
  if (ins.inflight) { ins.queued = true; return; }
  const q = loomkin.insertRequest();
  ins.inflight = true;
  const t0 = performance.now();
  api("/insert/evaluate", q)
    .then((r) => { clearFieldErrors(); ins.result = r; render(r); status(`insertion evaluated in ${(performance.now() - t0).toFixed(0)} ms`); })
    .catch((e) => showFieldError("insertion", e, insertField))
    .finally(() => { ins.inflight = false; if (ins.queued) { ins.queued = false; evaluate(); } });
}

const KIND_NAMES = { shuttle: "shuttle", rapier: "double rapier", projectile: "projectile", airjet: "air jet" };

function render(r) {
  const b = r.budget, c = r.check, t = r.timing;
  // The fields show the file's values as placeholders.
  const fileValue = { reed_width_mm: b.reed_width_mm, carrier_length_mm: b.carrier_length_mm, window_deg: b.window_deg, speed_m_s: b.speed_m_s };
  for (const [key] of BUDGET_FIELDS) ins.inputs.budget[key].placeholder = fileValue[key] !== undefined ? num(fileValue[key]) : "none";
  ins.inputs.speed.placeholder = num(r.speed_rpm);
  const source = { given: "given", entry_exit: "the file's entry to exit", clear_shed: "the pattern's clear-shed window" }[b.window_source] || b.window_source;
  const rows = [
    ["highest loom speed", `${num(b.max_picks_per_min, 2)} picks/min`, "insert-max-picks"],
    ["carrier speed needed", `${num(b.required_speed_m_s, 3)} m/s at ${num(b.speed_rpm, 2)} rpm`, "insert-required-speed"],
    ["reed width, carrier", `${num(b.reed_width_mm)} mm, ${num(b.carrier_length_mm)} mm`],
    ["window", `${num(b.window_deg, 3)}° (${source})`],
    ["carrier mean speed", `${num(b.speed_m_s, 3)} m/s`],
  ];
  if (b.energy_per_pick_j !== undefined) rows.push(["energy per pick", `${num(b.energy_per_pick_j, 4)} J (${num(b.carrier_mass_g)} g)`], ["drive power", `${num(b.drive_power_w, 2)} W`, "insert-drive-power"]);
  document.querySelector("#insert-budget tbody").replaceChildren(...rows.map(row));
  const s = [["loom", `${r.loom || "loom file"}: ${KIND_NAMES[r.kind] || r.kind} at ${num(r.speed_rpm)} rpm`, "insert-kind"],
    ["in the shed", `${num(t.in_shed_deg[0], 2)}° → ${num(t.in_shed_deg[1], 2)}°`]];
  if (r.kind === "rapier") {
    s.push(["transfer", `overlap ${num(c.transfer_overlap_mm, 3)} mm at ${num(c.transfer_deg, 2)}°, closing at ${num(c.transfer_relative_speed_m_s, 3)} m/s`],
      ["peak head speed", `${num(c.peak_head_speed_m_s, 3)} m/s`], ["peak head acceleration", `${num(c.peak_head_acceleration_m_s2, 1)} m/s²`]);
  } else if (r.kind === "projectile") {
    s.push(["launch", `${num(c.projectile_speed_m_s, 3)} m/s at ${num(c.launch_deg, 2)}°`],
      ["flight", `${num(c.flight_time_ms, 3)} ms; into the brake at ${num(c.arrival_deg, 2)}°`, "insert-arrival"]);
    if (c.fits_sley_dwell !== undefined) s.push(["sley back dwell", `${num(c.sley_back_dwell_deg[0], 1)}° → ${num(c.sley_back_dwell_deg[1], 1)}°: the flight ${c.fits_sley_dwell ? "fits" : "does NOT fit"}`]);
  } else if (r.kind === "airjet") {
    s.push(["flight", `${num(c.flight_time_ms, 3)} ms; the tip reaches the far selvedge at ${num(c.arrival_deg, 2)}°`, "insert-arrival"],
      ["tip speed at exit", `${num(c.tip_speed_at_exit_m_s, 3)} m/s`],
      ["relay air", `${c.relay_plan.length} of ${c.groups} groups open ${num(c.relay_open_ms, 3)} ms (${num(c.relay_open_deg, 2)}°) in all`, "insert-relay-open"]);
  }
  if (r.clearance) {
    s.push(["least clearance", `${num(c.min_clearance_mm, 3)} mm at pick ${c.worst_pick} of ${c.picks}, ${num(c.worst_angle_deg, 2)}°, ${num(c.worst_position_mm, 1)} mm across${c.min_clearance_mm < 0 ? ": it touches the warp" : ""}`, "insert-min-clearance"]);
  }
  document.querySelector("#insert-summary tbody").replaceChildren(...s.map(row));
  const bad = document.querySelector("#insert-min-clearance");
  if (bad && c.min_clearance_mm < 0) bad.style.color = "#b91c1c";

  // The carrier across the reed: every track, the selvedges, the span in the shed shaded, the transfer.
  const lo = Math.min(0, ...t.tracks.map((k) => k.angle_deg[0])), hi = Math.max(360, ...t.tracks.map((k) => k.angle_deg[k.angle_deg.length - 1]));
  for (const ch of [ins.track, ins.clear, ins.relay]) ch.opts.x.range = [lo, hi];
  ins.track.bands = [t.in_shed_deg];
  ins.track.hlines = [{ y: 0, color: "#009e73", label: "entering selvedge" }, { y: r.reed_width_mm, color: "#cc79a7", label: "far selvedge" }];
  const series = t.tracks.map((k) => ({ label: k.label, x: k.angle_deg, y: k.position_mm, color: TRACK_COLOURS[k.label] || PALETTE[0], width: 1.6 }));
  if (t.transfer) series.push({ label: `transfer: overlap ${num(c.transfer_overlap_mm, 1)} mm at ${num(t.transfer[0], 1)}°`, mode: "markers", radius: 5, x: [t.transfer[0]], y: [t.transfer[1]], color: "#f59e0b" });
  if (t.sley_back_dwell_deg) {
    const y = -0.06 * r.reed_width_mm;
    series.push({ label: "sley back dwell", x: t.sley_back_dwell_deg, y: [y, y], color: "#6b7280", width: 4, hover: false });
  }
  ins.track.setSeries(series);

  // The clearance on the worst pick, its least value marked (the located one, not the samples').
  const cw = document.querySelector("#insert-clearance");
  cw.hidden = !r.clearance;
  if (r.clearance) {
    const k = r.clearance;
    ins.clear.opts.title = `Clearance in the shed on pick ${k.pick}, the worst of the pattern`;
    ins.clear.bands = [t.in_shed_deg];
    ins.clear.hlines = [{ y: 0, label: "touching" }];
    ins.clear.setSeries([
      { label: "clearance", x: k.angle_deg, y: k.clearance_mm, color: PALETTE[0], width: 1.6 },
      { label: `least ${num(c.min_clearance_mm, 2)} mm at ${num(c.worst_angle_deg, 1)}°`, mode: "markers", radius: 5, x: [c.worst_angle_deg], y: [c.min_clearance_mm], color: "#dc2626" },
    ]);
  }
  // The air jet's relay plan: a bar per group from its opening to its closing.
  const rw = document.querySelector("#insert-relay");
  rw.hidden = !t.relay_plan.length;
  if (t.relay_plan.length) {
    ins.relay.bands = [t.in_shed_deg];
    ins.relay.setSeries(t.relay_plan.map((o, k) => ({ label: k ? "" : "open (open → close)", x: [o.open_deg, o.close_deg], y: [o.group, o.group], color: PALETTE[0], width: 5 })));
  }
}

function row([k, v, id]) {
  return el("tr", {}, el("th", { textContent: k }), el("td", { textContent: v, id: id || "" }));
}

register("insertion", "Insertion", initInsertion);
})();
