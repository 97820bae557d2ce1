// loomkin workbench: the cam view — a cycle, a catalogue law or a shedding law to a disc cam, its
// pressure angle and curvature against their limits, the DXF drawing and controller cam tables.
// Written for loomkin.
(() => {
"use strict";

const { Chart, Scene, PALETTE } = window.LoomkinCharts;
const { api, status, download, el, num, loomkin, register } = window.LoomkinApp;
const { sliderWithNumber, viewHistory, showFieldError, clearFieldErrors, applyLimits } = window.LoomkinShared;

const cam = { inflight: false, queued: false, result: null, fileText: null };

function field(label, input, hint) {
  const l = el("label", {}, label, input);
  if (hint) l.title = hint;
  return l;
}

// A numeric field whose limits are those of the request key `path` of `route` in the schema.
function numberInput(id, value, route, path, attrs) {
  const input = el("input", Object.assign({ type: "number", step: "any", value: String(value), id }, attrs || {}));
  applyLimits(input, route, path);
  return input;
}

const PROFILE = "/api/cam/profile";

async function initCam() {
  const panel = document.querySelector("#cam-panel");
  const root = document.querySelector("#cam-root");
  let ex;
  try { ex = await api("/cam/examples"); } catch (e) { status("cam: " + e.message, true); return; }
  cam.examples = ex;

  // Motion.
  const source = el("select", { id: "cam-source" });
  for (const c of ex.cycles) source.append(el("option", { value: "example:" + c.name, textContent: "cycle " + c.name }));
  source.append(el("option", { value: "law", textContent: "a catalogue law: rise–dwell–return–dwell" }),
    el("option", { value: "shed", textContent: "a shedding law: the frame's cycle over 720°" }),
    el("option", { value: "file", textContent: "a cycle file (TOML) …" }));
  const law = el("select", { id: "cam-law" });
  try { for (const l of (await api("/laws")).laws) law.append(el("option", { value: l.name, textContent: l.name })); } catch (e) { status("laws: " + e.message, true); }
  law.value = "modified-sine";
  const stroke = numberInput("cam-stroke", 60, PROFILE, "source.law.stroke_mm");
  const motion = numberInput("cam-motion", 120, PROFILE, "source.law.motion_deg");
  const strokeLabel = el("span", { textContent: "stroke (mm)" });
  const lawBox = el("div", { className: "grid2", hidden: true }, field("law", law),
    el("label", {}, strokeLabel, stroke), field("motion angle, rise and return (°)", motion));
  const preset = el("select", { id: "cam-shed-preset" });
  for (const p of ex.shed_presets) preset.append(el("option", { value: p, textContent: p }));
  const shedStroke = numberInput("cam-shed-stroke", 100, PROFILE, "source.shed.stroke_mm");
  const shedMotion = numberInput("cam-shed-motion", "", PROFILE, "source.shed.motion_deg", { placeholder: "preset's" });
  const shedBox = el("div", { className: "grid2", hidden: true }, field("preset", preset),
    field("frame stroke (mm)", shedStroke), field("motion angle (°)", shedMotion));
  const file = el("input", { type: "file", accept: ".toml,text/plain", id: "cam-file" });
  const fileName = el("span", { className: "hint", textContent: "" });
  const fileBox = el("div", { hidden: true }, el("label", { className: "file" }, "load a cycle file", file), fileName);

  // Follower and size.
  const follower = el("select", { id: "cam-follower" },
    el("option", { value: "translating", textContent: "translating roller" }),
    el("option", { value: "oscillating", textContent: "oscillating (swinging) roller" }),
    el("option", { value: "flat", textContent: "flat-faced translating" }));
  const closure = el("select", { id: "cam-closure" },
    el("option", { value: "single", textContent: "single cam (spring)" }),
    el("option", { value: "conjugate", textContent: "conjugate pair" }),
    el("option", { value: "groove", textContent: "groove cam" }));
  const sizeBy = el("select", { id: "cam-size-by" },
    el("option", { value: "pressure", textContent: "least prime circle for a pressure angle" }),
    el("option", { value: "radius", textContent: "a given prime circle" }));
  const pressure = numberInput("cam-max-pressure", 30, PROFILE, "design.max_pressure_deg");
  const prime = numberInput("cam-prime", 120, PROFILE, "design.prime_radius_mm");
  const roller = numberInput("cam-roller", 15, PROFILE, "design.roller_radius_mm");
  const offset = numberInput("cam-offset", 0, PROFILE, "design.offset_mm");
  const arm = numberInput("cam-arm", 160, PROFILE, "design.arm_mm");
  const pivot = numberInput("cam-pivot", 190, PROFILE, "design.pivot_mm");
  const pressureLabel = field("largest pressure angle (°)", pressure);
  const primeLabel = field("prime circle radius Rp (mm)", prime, "least radius of the pitch curve: base circle + roller");
  const rollerLabel = field("roller radius (mm)", roller);
  const offsetLabel = field("offset ε (mm)", offset, "line of motion offset to the right of the cam centre");
  const armLabel = field("arm length L (mm)", arm);
  const pivotLabel = field("pivot distance d (mm)", pivot);

  // Downloads.
  const tol = numberInput("cam-chord-tol", "", "/api/cam/dxf", "chord_tol_mm", { className: "short" });
  const bore = numberInput("cam-bore", "", "/api/cam/dxf", "bore_mm", { className: "short", placeholder: "0.4·Rb" });
  const dxfBtn = el("button", { type: "button", id: "cam-dxf", textContent: "DXF drawing" });
  const format = el("select", { id: "cam-format" });
  for (const f of ex.formats) format.append(el("option", { value: f, textContent: f }));
  const spacing = el("select", { id: "cam-spacing" },
    el("option", { value: "step", textContent: "step (°)" }), el("option", { value: "tolerance", textContent: "tolerance" }));
  const spacingValue = numberInput("cam-spacing-value", 1, "/api/cam/table", "step_deg", { className: "short" });
  const tableBtn = el("button", { type: "button", id: "cam-table", textContent: "Cam table" });
  const fileNote = el("p", { className: "hint", id: "cam-download-note" });

  panel.append(
    el("h2", { textContent: "Motion" }),
    el("p", { className: "hint", textContent: "The cam turns counter-clockwise once per cycle, at the main-shaft angle of the cycle; 0° is marked on the drawing." }),
    el("label", { className: "wide" }, "source", source), lawBox, shedBox, fileBox,
    el("h2", { textContent: "Follower" }),
    el("div", { className: "grid2" }, field("follower", follower), field("closure", closure),
      rollerLabel, offsetLabel, armLabel, pivotLabel),
    el("h2", { textContent: "Size" }),
    el("label", { className: "wide" }, "size by", sizeBy),
    el("div", { className: "grid2" }, pressureLabel, primeLabel),
    el("h2", { textContent: "Downloads" }),
    el("div", { className: "row wrap" }, dxfBtn, el("label", {}, "chord tol. (mm) ", tol), el("label", {}, "bore Ø (mm) ", bore)),
    el("div", { className: "row wrap" }, tableBtn, format, spacing, spacingValue),
    fileNote);

  const table = el("table", { className: "data", id: "cam-summary" }, el("caption", { textContent: "Cam" }), el("tbody"));
  const top = el("div", { className: "results" });
  root.append(top);
  cam.scene = new Scene(top, { id: "cam-scene", title: "Cam (cam frame)", height: 420, unit: "mm" });
  top.append(table);
  // The angle: a slider and a numeric field (any angle of the cycle, e.g. 123.25°).
  const angleW = sliderWithNumber("cam-angle", "main-shaft angle: the follower's contact on the drawing and the charts", "°", 0, 360, 0.5, 0,
    (v) => { cam.angleDeg = v; drawAngle(v); }, () => cam.history.commit());
  cam.angleDeg = 0;
  root.append(angleW.label);
  const grid = el("div", { className: "grid-charts" });
  root.append(grid);
  const ax = () => ({ label: "main-shaft angle", unit: "°", range: [0, cam.period || 360], step: (cam.period || 360) > 360 ? 90 : 30 });
  cam.lift = new Chart(grid, { id: "cam-lift", title: "Follower motion", height: 200, x: ax(), y: { label: "lift", unit: "mm", includeZero: true } });
  cam.pressure = new Chart(grid, { id: "cam-pressure", title: "Pressure angle (limit dashed)", height: 220, x: ax(), y: { label: "pressure angle", unit: "°", includeZero: true } });
  cam.curv = new Chart(grid, { id: "cam-curvature", title: "Curvature, convex > 0", height: 220, x: ax(), y: { label: "curvature", unit: "1/mm", includeZero: true } });
  Object.assign(loomkin.charts, { cam_lift: cam.lift, cam_pressure: cam.pressure, cam_curvature: cam.curv });

  cam.inputs = { source, law, stroke, motion, preset, shedStroke, shedMotion, follower, closure, sizeBy, pressure, prime, roller, offset, arm, pivot, tol, bore, format, spacing, spacingValue };
  const layout = () => {
    lawBox.hidden = source.value !== "law"; shedBox.hidden = source.value !== "shed"; fileBox.hidden = source.value !== "file";
    const f = follower.value;
    rollerLabel.hidden = f === "flat"; offsetLabel.hidden = f !== "translating";
    armLabel.hidden = f !== "oscillating"; pivotLabel.hidden = f !== "oscillating";
    strokeLabel.textContent = f === "oscillating" ? "swing (°)" : "stroke (mm)";
    const byPressure = sizeBy.value === "pressure" && f !== "flat";
    pressureLabel.hidden = !byPressure; primeLabel.hidden = byPressure;
    sizeBy.disabled = f === "flat";
    spacingValue.title = spacing.value === "step" ? "master step, deg (points also on every joint)" : "largest re-interpolation error, slave unit";
  };
  cam.layout = layout;
  // Every edit is recorded for undo and written into the address (#cam/<state>).
  const commit = () => cam.history.commit();
  const changed = () => { layout(); compute(); commit(); };
  source.addEventListener("change", () => {
    if (source.value === "example:sley-cycle.toml" && follower.value !== "oscillating") { follower.value = "oscillating"; sizeBy.value = "pressure"; pressure.value = "40"; roller.value = "10"; }
    if (source.value === "file" && !cam.fileText) { layout(); file.click(); return; }
    changed();
  });
  for (const e of [law, stroke, motion, preset, shedStroke, shedMotion, follower, closure, sizeBy, pressure, prime, roller, offset, arm, pivot]) e.addEventListener("change", changed);
  // The download settings are part of the state too (no recomputation).
  for (const e of [tol, bore, format, spacingValue]) e.addEventListener("change", commit);
  spacing.addEventListener("change", () => {
    spacingValue.value = spacing.value === "step" ? "1" : "0.001";
    applyLimits(spacingValue, "/api/cam/table", spacing.value === "step" ? "step_deg" : "tolerance");
    layout(); commit();
  });
  file.addEventListener("change", async () => {
    const f = file.files[0]; if (!f) return;
    cam.fileText = await f.text(); cam.fileName = f.name; fileName.textContent = f.name; source.value = "file"; changed();
  });
  cam.angleW = angleW;
  dxfBtn.addEventListener("click", downloadDxf);
  tableBtn.addEventListener("click", downloadTable);
  // The state: every field of the panel and the angle. A loaded cycle file stays in the page only
  // (not in the address): a state naming it without the file shows the first example.
  const firstExample = "example:" + ex.cycles[0].name;
  cam.history = viewHistory("cam", () => {
    const st = {};
    for (const [k, e] of Object.entries(cam.inputs)) st[k] = e.value;
    if (st.source === "file" && !cam.fileText) st.source = firstExample;
    st.angle_deg = cam.angleDeg;
    return st;
  }, (st) => {
    for (const [k, e] of Object.entries(cam.inputs)) if (st[k] !== undefined) e.value = st[k];
    const known = [...source.options].some((o) => o.value === source.value);
    if (!known || (source.value === "file" && !cam.fileText)) source.value = firstExample;
    if (st.angle_deg !== undefined) { angleW.set(st.angle_deg); cam.angleDeg = st.angle_deg; }
    layout();
    compute();
  });
  layout();
  compute();
  cam.history.ready();
}

// The input a refused request names (its JSON path), with the label the panel gives it.
function camField(path) {
  const i = cam.inputs;
  const map = [
    ["source.law.stroke_mm", i.stroke, "stroke"], ["source.law.stroke_deg", i.stroke, "swing"], ["source.law.motion_deg", i.motion, "motion angle"],
    ["source.law", i.law, "law"], ["source.shed.stroke_mm", i.shedStroke, "frame stroke"], ["source.shed.motion_deg", i.shedMotion, "motion angle"],
    ["source.shed", i.preset, "preset"], ["source", i.source, "source"],
    ["design.roller_radius_mm", i.roller, "roller radius"], ["design.offset_mm", i.offset, "offset ε"], ["design.arm_mm", i.arm, "arm length L"],
    ["design.pivot_mm", i.pivot, "pivot distance d"], ["design.max_pressure_deg", i.pressure, "largest pressure angle"],
    ["design.prime_radius_mm", i.prime, "prime circle radius"], ["design.follower", i.follower, "follower"], ["design.closure", i.closure, "closure"],
    ["design", i.follower, "follower"], ["chord_tol_mm", i.tol, "chord tolerance"], ["bore_mm", i.bore, "bore"],
    ["step_deg", i.spacingValue, "table step"], ["tolerance", i.spacingValue, "table tolerance"], ["format", i.format, "table format"],
  ];
  const hit = map.find(([k]) => path === k || path.startsWith(k + ".") || path.startsWith(k + "["));
  return hit ? { inputs: [hit[1]], label: hit[2] } : null;
}

function camSource() {
  const i = cam.inputs, v = i.source.value;
  if (v.startsWith("example:")) { const c = cam.examples.cycles.find((c) => "example:" + c.name === v); return { cycle_toml: c.cycle_toml, name: c.name }; }
  if (v === "law") {
    const l = { law: { name: i.law.value, params: {} }, motion_deg: +i.motion.value };
    l[i.follower.value === "oscillating" ? "stroke_deg" : "stroke_mm"] = +i.stroke.value;
    return { law: l };
  }
  if (v === "shed") {
    const s = { preset: i.preset.value, stroke_mm: +i.shedStroke.value };
    if (i.shedMotion.value.trim() !== "") s.motion_deg = +i.shedMotion.value;
    return { shed: s };
  }
  if (v === "file" && cam.fileText) return { cycle_toml: cam.fileText, name: cam.fileName };
  return {};
}

function camDesign() {
  const i = cam.inputs, f = i.follower.value;
  const d = { follower: f, closure: i.closure.value };
  if (f !== "flat") d.roller_radius_mm = +i.roller.value;
  if (f === "translating") d.offset_mm = +i.offset.value;
  if (f === "oscillating") { d.arm_mm = +i.arm.value; d.pivot_mm = +i.pivot.value; }
  if (f !== "flat" && i.sizeBy.value === "pressure") d.max_pressure_deg = +i.pressure.value;
  else d.prime_radius_mm = +i.prime.value;
  return d;
}

loomkin.camRequest = () => ({ source: camSource(), design: camDesign(), step_deg: 0.5 });

function compute() {
  if (cam.inflight) { cam.queued = true; return; }
  cam.inflight = true;
  const q = loomkin.camRequest();
  const t0 = performance.now();
  api("/cam/profile", q)
    .then((r) => { clearFieldErrors(); cam.result = r; render(r); status(`cam computed in ${(performance.now() - t0).toFixed(0)} ms`); })
    .catch((e) => { cam.result = null; showFieldError("cam", e, camField); })
    .finally(() => { cam.inflight = false; if (cam.queued) { cam.queued = false; compute(); } });
}

function limitLine(label, period, y, color) {
  return { label, x: [0, period], y: [y, y], dash: [6, 4], color, width: 1.4, hover: false };
}

function render(r) {
  const rep = r.report, c = r.cam, u = rep.unit;
  cam.period = c.angle_deg[c.angle_deg.length - 1];
  for (const ch of [cam.lift, cam.pressure, cam.curv]) {
    ch.opts.x.range = [0, cam.period]; ch.opts.x.step = cam.period > 360 ? 90 : 30;
  }
  cam.angleW.setMax(cam.period);
  if (cam.angleDeg > cam.period) { cam.angleW.set(0); cam.angleDeg = 0; }
  cam.lift.opts.y.unit = u;
  cam.lift.setSeries([{ label: "lift s", x: c.angle_deg, y: c.lift, color: PALETTE[0] }]);
  const A = r.pressure_limit_deg;
  const pa = [{ label: "cam", x: c.angle_deg, y: c.pressure_angle_deg, color: PALETTE[0] }];
  if (r.counter) pa.push({ label: "counter-cam", x: r.counter.angle_deg, y: r.counter.pressure_angle_deg, color: PALETTE[1] });
  pa.push(limitLine(`±${num(A)}°`, cam.period, A, "#dc2626"), limitLine("", cam.period, -A, "#dc2626"));
  cam.pressure.setSeries(pa);
  const cu = [{ label: "pitch curve", x: c.angle_deg, y: c.curvature_pitch_per_mm, color: PALETTE[0], dash: [4, 3] },
    { label: "profile", x: c.angle_deg, y: c.curvature_profile_per_mm, color: "#111827" }];
  if (r.counter) cu.push({ label: "counter pitch", x: r.counter.angle_deg, y: r.counter.curvature_pitch_per_mm, color: PALETTE[1], dash: [4, 3] });
  if (r.curvature_limit_per_mm !== undefined) cu.push(limitLine(`undercut above 1/r = ${num(r.curvature_limit_per_mm, 4)}`, cam.period, r.curvature_limit_per_mm, "#dc2626"));
  cam.curv.setSeries(cu);
  cam.curv.opts.y.range = curvatureRange(cu);
  cam.curv.draw();
  // Drawing bounds: the whole cam with a margin for the roller.
  const d = r.drawing;
  const all = [...d.profile, ...d.pitch, ...d.counter_profile, ...d.counter_pitch];
  const xs = all.map((p) => p[0]), ys = all.map((p) => p[1]);
  const pad = Math.max(rep.roller_radius_mm, 0.05 * (Math.max(...xs) - Math.min(...xs)));
  cam.bounds = [Math.min(...xs, -d.base_radius_mm) - pad, Math.min(...ys, -d.base_radius_mm) - pad, Math.max(...xs, d.base_radius_mm) + pad, Math.max(...ys, d.base_radius_mm) + pad];
  const rows = [
    ["source", rep.source], ["follower", `${rep.follower}, ${rep.closure}`],
    ["prime circle Rp", `${num(rep.prime_radius_mm, 3)} mm` + (rep.sized_for_pressure_deg !== undefined ? ` (least for ${num(rep.sized_for_pressure_deg)}°)` : ""), "cam-prime-radius"],
    ["base circle Rb", `${num(rep.base_radius_mm, 3)} mm`],
    ["stroke", `${num(rep.stroke, 3)} ${u}`],
    ["largest pressure angle", `${num(rep.max_pressure_angle_deg, 3)}° at ${num(rep.max_pressure_angle_at_deg, 2)}°` + (rep.counter_max_pressure_angle_deg !== undefined ? `; counter-cam ${num(rep.counter_max_pressure_angle_deg, 3)}°` : ""), "cam-max-pressure-angle"],
    ["least convex radius, pitch curve", `${num(rep.min_convex_radius_pitch_mm, 3)} mm at ${num(rep.min_convex_radius_pitch_at_deg, 2)}°`],
  ];
  if (rep.roller_max_mm !== undefined) rows.push(["roller / largest without undercut", `${num(rep.roller_radius_mm, 3)} / ${num(rep.roller_max_mm, 3)} mm`]);
  if (rep.face_min_mm !== undefined) rows.push(["flat face from … to", `${num(rep.face_min_mm, 2)} … ${num(rep.face_max_mm, 2)} mm`], ["least radius of the profile", `${num(rep.min_radius_profile_mm, 3)} mm`]);
  rows.push(["undercut", rep.undercut ? rep.undercut_message : "no", "cam-undercut"]);
  document.querySelector("#cam-summary tbody").replaceChildren(...rows.map(([k, v, id]) => {
    const td = el("td", { textContent: v, id: id || "" });
    if (id === "cam-undercut" && rep.undercut) td.style.color = "#b91c1c";
    return el("tr", {}, el("th", { textContent: k }), td);
  }));
  drawAngle(cam.angleDeg);
}

// The curvature axis: the curves and the limit, but not a spike to ±∞ at a near-cusp.
function curvatureRange(series) {
  const v = series.flatMap((s) => s.y).filter((y) => isFinite(y)).sort((a, b) => a - b);
  if (!v.length) return undefined;
  const q = (p) => v[Math.min(v.length - 1, Math.max(0, Math.round(p * (v.length - 1))))];
  let lo = Math.min(q(0.01), 0), hi = Math.max(q(0.99), 0);
  const lim = series.find((s) => s.label && s.label.startsWith("undercut above 1/r"));
  if (lim) hi = Math.max(hi, lim.y[0] * 1.15);
  const span = hi - lo || 1;
  return [lo - 0.05 * span, hi + 0.05 * span];
}

function drawAngle(deg) {
  const r = cam.result;
  if (!r) return;
  const c = r.cam, d = r.drawing;
  const k = Math.max(0, Math.min(c.angle_deg.length - 1, Math.round(deg / (c.angle_deg[1] - c.angle_deg[0]))));
  const p = [c.x_mm[k], c.y_mm[k]];
  const rr = r.report.roller_radius_mm;
  const close = (pts) => pts.length ? [...pts, pts[0]] : pts;
  const circle = (R) => Array.from({ length: 181 }, (_, i) => [R * Math.cos(i * Math.PI / 90), R * Math.sin(i * Math.PI / 90)]);
  const arm = 0.15 * d.base_radius_mm;
  const items = [
    { kind: "line", pts: close(d.profile), color: "#111827", width: 2, legend: "profile" },
    { kind: "line", pts: close(d.pitch), color: "#1f5fa8", width: 1.2, dash: [6, 4], legend: "pitch curve" },
  ];
  if (d.counter_profile.length) items.push({ kind: "line", pts: close(d.counter_profile), color: "#c2410c", width: 2, legend: r.report.closure === "groove" ? "groove outer wall" : "counter-cam" });
  if (d.counter_pitch.length) items.push({ kind: "line", pts: close(d.counter_pitch), color: "#c2410c", width: 1.2, dash: [6, 4] });
  items.push(
    { kind: "line", pts: circle(d.base_radius_mm), color: "#9ca3af", width: 1, dash: [3, 3], legend: "base circle" },
    { kind: "line", pts: [[0, 0], d.phase_point], color: "#15803d", width: 1.5, legend: "0°" },
    { kind: "line", pts: [[-arm, 0], [arm, 0]], color: "#6b7280", width: 1 },
    { kind: "line", pts: [[0, -arm], [0, arm]], color: "#6b7280", width: 1 },
    { kind: "circle", c: p, r: rr, minPx: 4, color: "#f59e0b", fill: "rgba(245,158,11,0.2)", legend: "" },
    { kind: "label", at: p, text: `${num(c.angle_deg[k], 1)}°` });
  if (r.counter) {
    const q = [r.counter.x_mm[k], r.counter.y_mm[k]];
    items.push({ kind: "circle", c: q, r: rr, minPx: 4, color: "#f59e0b", fill: "rgba(245,158,11,0.2)" });
  }
  cam.scene.setItems(items, cam.bounds);
  for (const ch of [cam.lift, cam.pressure, cam.curv]) { ch.markerX = c.angle_deg[k]; ch.draw(); }
}

async function downloadDxf() {
  const i = cam.inputs;
  const q = { source: camSource(), design: camDesign(), chord_tol_mm: +i.tol.value };
  if (i.bore.value.trim() !== "") q.bore_mm = +i.bore.value;
  try {
    const r = await api("/cam/dxf", q);
    download(r.filename, r.text, r.media_type);
    document.querySelector("#cam-download-note").textContent = `${r.filename}: ${r.note}`;
    status(`exported ${r.filename}`);
  } catch (e) { showFieldError("DXF", e, camField); }
}

async function downloadTable() {
  const i = cam.inputs;
  const q = { source: camSource(), format: i.format.value };
  q[i.spacing.value === "step" ? "step_deg" : "tolerance"] = +i.spacingValue.value;
  try {
    const r = await api("/cam/table", q);
    download(r.file.filename, r.file.text, r.file.media_type);
    document.querySelector("#cam-download-note").textContent = `${r.file.filename}: ${r.file.note}`;
    status(`exported ${r.file.filename}`);
  } catch (e) { showFieldError("cam table", e, camField); }
}

register("cam", "Cam", initCam);
})();
