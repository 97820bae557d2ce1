// loomkin workbench: the drive view — the loom's main shaft: the reduced inertia J(φ) of every
// mechanism and the total, the shaft's speed ω(φ), the motor and load torques, a flywheel, the
// speed ripple against the loom's speed, and the loom seen from the side (crank, rod, sword and
// reed, the heald frames, the shed) animated over the main-shaft angle. Every number and every
// position comes from POST /api/drive/evaluate (the library's exact kinematics); the page only
// draws them. Written for loomkin.
(() => {
"use strict";

const { Chart, PALETTE, addTools } = window.LoomkinCharts;
const { api, status, el, num, convert, loomkin, register } = window.LoomkinApp;
const { viewHistory, showFieldError, clearFieldErrors, sliderWithNumber, newest, FRAME_COLOURS } = window.LoomkinShared;

const drv = { inflight: false, queued: false, result: null, side: null, k: 0, playing: false, last: null };
const ROUTE = "/api/drive/evaluate";
// The animation's pace: degrees of main shaft per second of the page's clock (a turn in 4 s).
const PLAY_DEG_PER_S = 90;
// Colours of the sley's links (the frames' are the loom view's).
const SLEY = "#374151", REED = "#b45309";

async function initDrive() {
  const panel = document.querySelector("#drive-panel");
  const root = document.querySelector("#drive-root");
  let ex;
  try { ex = await api("/loom/examples"); } catch (e) { status("drive: " + e.message, true); return; }
  drv.examples = ex;
  const loomSel = el("select", { id: "shaft-loom" });
  for (const l of ex.looms) loomSel.append(el("option", { value: l.name, textContent: l.name }));
  const patSel = el("select", { id: "shaft-pattern" });
  patSel.append(el("option", { value: "plain-default", textContent: "plain weave on the loom's frames" }));
  for (const p of ex.patterns) patSel.append(el("option", { value: p.name, textContent: p.name }));
  // The flywheel: the field takes the schema's range (the library's); the slider's span follows
  // the loom (a few times its mean inertia), set once the first answer is in.
  drv.flywheel = sliderWithNumber("shaft-flywheel", "flywheel", "kg·m²", 0, 1, 0.01, 0,
    () => evaluate(false), () => drv.history.commit(), { route: ROUTE, path: "flywheel_kg_m2" });
  drv.flywheel.field.value = "";
  const play = el("button", { type: "button", id: "shaft-play", textContent: "▶ Play" });
  const scrub = el("input", { type: "range", id: "shaft-scrub", min: "0", max: "0", step: "1", value: "0" });
  scrub.setAttribute("aria-label", "main-shaft angle");
  panel.append(
    el("h2", { textContent: "Loom and pattern" }),
    el("p", { className: "hint", textContent: "The loom file's [drive] table gives the rotating parts, the friction and the motor; the pattern the frames' moves over the repeat." }),
    el("label", { className: "wide" }, "loom file", loomSel),
    el("label", { className: "wide" }, "weave pattern", patSel),
    el("h2", { textContent: "Flywheel" }),
    el("p", { className: "hint", textContent: "Inertia added to the main shaft: the ripple falls as it grows." }),
    drv.flywheel.label,
    el("h2", { textContent: "Side view" }),
    el("p", { className: "hint", textContent: "Crank, rod, sword and reed, the heald eyes and the shed, at the main-shaft angle (0° = beat-up)." }),
    el("div", { className: "row wrap" }, play, el("span", { id: "shaft-angle", className: "hint" })),
    el("label", { className: "wide" }, "main-shaft angle over the repeat", scrub));

  const summary = el("table", { className: "data", id: "shaft-summary" }, el("caption", { textContent: "Main shaft" }), el("tbody"));
  const sideWrap = el("div", { className: "chart", id: "shaft-side-chart" });
  const sideCanvas = el("canvas", { id: "shaft-side", role: "img", ariaLabel: "the loom from the side: crank, rod, sword and reed, heald frames and the shed" });
  sideCanvas.style.height = "420px";
  sideWrap.append(sideCanvas);
  // The side view saves as the charts do: PNG, SVG (drawn by the same code) and CSV (the positions shown).
  drv.sideChart = { wrap: sideWrap, canvas: sideCanvas, ctx: sideCanvas.getContext("2d"), hoverX: null,
    draw: () => drawSide(), resetView: () => drawSide(), fileStem: () => "loom-side-view",
    toSVG: () => window.LoomkinCharts.renderSVG(drv.sideChart), toCSV: sideCSV };
  addTools(drv.sideChart, ["png", "svg", "csv"]);
  root.append(el("div", { className: "results" }, summary));
  if (window.ResizeObserver) new ResizeObserver(() => drawSide()).observe(sideCanvas);
  const charts = el("div", { className: "charts" });
  root.append(charts);
  charts.append(sideWrap);
  const ang = { label: "main-shaft angle over the repeat", unit: "°" };
  drv.j = new Chart(charts, { id: "shaft-inertia", title: "Reduced inertia J(φ) of each mechanism and the total", height: 240, x: { ...ang }, y: { label: "J", unit: "kg·m²", includeZero: true } });
  drv.speed = new Chart(charts, { id: "shaft-speed", title: "Main-shaft speed ω(φ)", height: 220, x: { ...ang }, y: { label: "speed", unit: "rpm" } });
  drv.torque = new Chart(charts, { id: "shaft-torque", title: "Motor and load torque at the main shaft", height: 220, x: { ...ang }, y: { label: "torque", unit: "N·m", includeZero: true } });
  drv.sweep = new Chart(charts, { id: "shaft-sweep", title: "Speed ripple against the loom's speed (this flywheel)", height: 220, x: { label: "loom speed", unit: "rpm" }, y: { label: "ripple", unit: "%", includeZero: true } });
  Object.assign(loomkin.charts, { shaft_inertia: drv.j, shaft_speed: drv.speed, shaft_torque: drv.torque, shaft_sweep: drv.sweep });
  drv.inputs = { loomSel, patSel, play, scrub };

  loomSel.addEventListener("change", () => { drv.flywheel.field.value = ""; evaluate(true); drv.history.commit(); });
  patSel.addEventListener("change", () => { evaluate(true); drv.history.commit(); });
  scrub.addEventListener("input", () => { stop(); show(+scrub.value); });
  play.addEventListener("click", () => (drv.playing ? stop() : start()));
  drv.history = viewHistory("drive", () => ({ loom: loomSel.value, pattern: patSel.value, flywheel_kg_m2: drv.flywheel.field.value }), (st) => {
    const before = loomSel.value + "\n" + patSel.value;
    loomSel.value = st.loom; if (!loomSel.value) loomSel.value = ex.looms[0].name;
    patSel.value = st.pattern; if (!patSel.value) patSel.value = "plain-default";
    drv.flywheel.field.value = st.flywheel_kg_m2 || "";
    evaluate(loomSel.value + "\n" + patSel.value !== before || !drv.side);
  });
  evaluate(true);
  drv.history.ready();
}

// The request the view sends (for tests and the console): the loom, the pattern, the flywheel
// (left out: the file's), and whether the side view is wanted.
loomkin.driveRequest = (side) => {
  const i = drv.inputs, q = {};
  q.loom_toml = drv.examples.looms.find((l) => l.name === i.loomSel.value).text;
  const pv = i.patSel.value;
  if (pv !== "plain-default") {
    const text = drv.examples.patterns.find((p) => p.name === pv).text;
    q.pattern = /\.wif$/.test(pv) ? { wif: text } : { lift_plan: text };
  }
  const f = drv.flywheel.field.value.trim();
  if (f !== "") q.flywheel_kg_m2 = +f;
  q.side = side !== false;
  return q;
};
loomkin.driveView = () => ({ result: drv.result, side: drv.side, k: drv.k });

function driveField(path) {
  const i = drv.inputs;
  const map = [["flywheel_kg_m2", drv.flywheel.field, "flywheel"], ["pattern", i.patSel, "weave pattern"], ["loom_toml", i.loomSel, "loom file"]];
  const hit = map.find(([k]) => path === k || path.startsWith(k + ".") || path.startsWith(k + "["));
  return hit ? { inputs: [hit[1]], label: hit[2] } : null;
}

// Asks for the figures; `side`: the side view too (a new loom or pattern; the flywheel leaves it).
function evaluate(side) {
  // Every state asked for, sent now or queued: an answer to an earlier one is drawn (the newest
  // follows) but fills no field (the flywheel left blank shows the file's value) with its loom's value.
  drv.current = newest("drive");
  drv.wantSide = drv.wantSide || side || !drv.side;
  if (drv.inflight) { drv.queued = true; return; }
  const withSide = drv.wantSide;
  drv.wantSide = false;
  const q = loomkin.driveRequest(withSide);
  const current = drv.current;
  drv.inflight = true;
  const t0 = performance.now();
  api("/drive/evaluate", q)
    .then((r) => {
      clearFieldErrors();
      drv.result = r;
      if (r.side) { drv.side = r.side; stop(); }
      render(r, current());
      status(`drive evaluated in ${(performance.now() - t0).toFixed(0)} ms`);
    })
    .catch((e) => { if (withSide) drv.wantSide = true; showFieldError("drive", e, driveField); })
    .finally(() => { drv.inflight = false; if (drv.queued) { drv.queued = false; evaluate(false); } });
}

// `isNewest`: the answer is to the state shown (no later one asked): it may fill the blank flywheel.
function render(r, isNewest) {
  const c = r.curves, rep = r.ripple, inr = r.inertia;
  const period = inr.repeat_deg;
  for (const ch of [drv.j, drv.speed, drv.torque]) { ch.opts.x.range = [0, period]; }
  const many = inr.mechanisms.length > 8;
  const series = inr.mechanisms.map((m, k) => ({
    label: !many || !m.name.startsWith("frame") || m.name === "frame 1" ? (many && m.name === "frame 1" ? "frames (each)" : m.name) : "",
    x: c.angle_deg, y: c.j_kg_m2[k], width: 1,
    color: m.name.startsWith("frame") ? FRAME_COLOURS[k % FRAME_COLOURS.length] : m.name === "sley" ? REED : "#6b7280",
  }));
  series.push({ label: rep.flywheel_kg_m2 > 0 ? "total with the flywheel" : "total", x: c.angle_deg, y: c.j_total_kg_m2, color: "#111827", width: 2 });
  drv.j.setSeries(series);
  drv.speed.hlines = [{ y: rep.mean_speed_rpm, color: "#6b7280", label: `mean ${num(rep.mean_speed_rpm, 2)} rpm` }];
  drv.speed.setSeries([{ label: "ω", x: c.angle_deg, y: c.speed_rpm, color: PALETTE[0], width: 1.4 }]);
  drv.torque.setSeries([
    { label: `${rep.motor} motor`, x: c.angle_deg, y: c.motor_torque_n_m, color: PALETTE[0], width: 1.4 },
    { label: "load", x: c.angle_deg, y: c.load_torque_n_m, color: "#dc2626", width: 1.2 },
  ]);
  const ok = r.sweep.speed_rpm.map((_, k) => r.sweep.speed_ripple_pct[k] !== null);
  drv.sweep.markerX = r.speed_rpm;
  drv.sweep.setSeries([{ label: "speed ripple", x: r.sweep.speed_rpm.filter((_, k) => ok[k]), y: r.sweep.speed_ripple_pct.filter((_, k) => ok[k]), color: PALETTE[0], width: 1.4 }]);
  // The flywheel slider's span: a few times the shaft's mean inertia, the value shown the answer's.
  const span = Math.max(4 * inr.j_mean_kg_m2, 2 * rep.flywheel_kg_m2);
  if (!drv.spanSet || +drv.flywheel.range.max < rep.flywheel_kg_m2) {
    drv.flywheel.setMax(+span.toPrecision(2));
    drv.flywheel.range.step = "any";
    drv.spanSet = true;
  }
  if (isNewest && drv.flywheel.field.value.trim() === "") drv.flywheel.set(rep.flywheel_kg_m2);
  const rows = [
    ["loom", `${r.loom || "loom file"} at ${num(r.speed_rpm)} rpm`],
    ["repeat", `${inr.picks} picks (${num(period)}°)`],
    ["motor", rep.motor],
    ["mean speed", `${num(rep.mean_speed_rpm, 3)} rpm`, "shaft-mean-speed"],
    ["speed", `${num(rep.min_speed_rpm, 3)} … ${num(rep.max_speed_rpm, 3)} rpm`],
    ["speed ripple", `${num(rep.speed_ripple_pct, 4)} %`, "shaft-ripple"],
    ["energy swing", `${num(rep.energy_swing_j, 3)} J`],
    ["motor torque", `peak ${num(rep.peak_motor_torque_n_m, 2)} N·m, RMS ${num(rep.rms_motor_torque_n_m, 2)} N·m`],
    ["J (total)", `${num(inr.j_min_kg_m2, 4)} … ${num(inr.j_max_kg_m2, 4)} kg·m², mean ${num(inr.j_mean_kg_m2, 4)}`],
    ["flywheel", `${num(rep.flywheel_kg_m2)} kg·m²`, "shaft-flywheel-used"],
  ];
  document.querySelector("#shaft-summary tbody").replaceChildren(...rows.map(([k, v, id]) => el("tr", {}, el("th", { textContent: k }), el("td", { textContent: v, id: id || "" }))));
  const s = drv.side;
  drv.inputs.scrub.max = String(s.angle_deg.length - 1);
  show(Math.min(drv.k, s.angle_deg.length - 1));
}

// Index k of the animation: the scrubber, the read-outs and the markers on the charts.
function show(k) {
  const s = drv.side, r = drv.result;
  if (!s || !r) return;
  drv.k = k;
  drv.inputs.scrub.value = String(k);
  const a = s.angle_deg[k];
  // The speed at this angle: the curve's nearest sample (the page interpolates nothing).
  const c = r.curves;
  let j = 0;
  while (j + 1 < c.angle_deg.length && Math.abs(c.angle_deg[j + 1] - a) <= Math.abs(c.angle_deg[j] - a)) j++;
  drv.speedAt = c.speed_rpm[j];
  const pick = Math.floor(a / 360) + 1, within = a - 360 * (pick - 1);
  const reed = s.sley ? `, reed ${num(s.sley.reed[k][0], 1)} mm behind the fell` : "";
  document.querySelector("#shaft-angle").textContent = `${num(a, 1)}° (pick ${pick}, ${num(within, 1)}°): ω ${num(drv.speedAt, 2)} rpm${reed}`;
  for (const ch of [drv.j, drv.speed, drv.torque]) { ch.markerX = a; ch.draw(); }
  drawSide();
}

function start() {
  if (!drv.side) return;
  drv.playing = true; drv.last = null;
  drv.inputs.play.textContent = "❚❚ Pause";
  const step = (t) => {
    if (!drv.playing) return;
    if (drv.last !== null) {
      const s = drv.side, n = s.angle_deg.length;
      const h = n > 1 ? s.angle_deg[1] - s.angle_deg[0] : 1;
      drv.acc = (drv.acc || 0) + convert(t - drv.last, "ms", "s") * PLAY_DEG_PER_S / h;
      const adv = Math.floor(drv.acc);
      if (adv > 0) { drv.acc -= adv; show((drv.k + adv) % n); }
    }
    drv.last = t;
    requestAnimationFrame(step);
  };
  requestAnimationFrame(step);
}

function stop() {
  drv.playing = false;
  if (drv.inputs) drv.inputs.play.textContent = "▶ Play";
}

// The positions drawn at the current angle, as CSV (mm behind and over the fell).
function sideCSV() {
  const s = drv.side, k = drv.k;
  if (!s) return "part,x behind the fell (mm),y over the fell (mm)\n";
  const rows = [["part", "x behind the fell (mm)", "y over the fell (mm)"]];
  if (s.sley) {
    rows.push(["crank centre", ...s.sley.crank_centre], ["crank pin", ...s.sley.crank_pin[k]], ["sword pin", ...s.sley.sword_pin[k]],
      ["rocking shaft", ...s.sley.rocking_shaft], ["reed", ...s.sley.reed[k]]);
  }
  s.heald_x_mm.forEach((x, i) => rows.push([`frame ${i + 1} heald eye`, x, s.heald_y_mm[i][k]]));
  rows.push(["back rest", ...s.back_rest_mm]);
  return `# main-shaft angle ${s.angle_deg[k]} deg\n` + rows.map((r) => r.join(",")).join("\n") + "\n";
}

// The side view: the fell at the origin, x to the right behind it (toward the back rest), y up;
// one scale for the whole animation (every position over the repeat fits).
function drawSide() {
  const s = drv.side, cv = drv.sideChart && drv.sideChart.canvas;
  if (!s || !cv) return;
  const w = cv.clientWidth || 600, h = cv.clientHeight || 420;
  const dpr = drv.sideChart.pixelScale || window.devicePixelRatio || 1;
  const c = drv.sideChart.ctx;
  if (c === cv.getContext("2d")) { cv.width = Math.round(w * dpr); cv.height = Math.round(h * dpr); }
  c.setTransform(dpr, 0, 0, dpr, 0, 0);
  c.clearRect(0, 0, w, h);
  if (!drv.bounds || drv.bounds.side !== s) {
    // The shed up to a little behind the back frame (the warp runs on to the back rest, clipped).
    const back = Math.max(...s.heald_x_mm, 0);
    const xs = [0, back + 0.25 * back], ys = [0];
    for (const row of s.heald_y_mm) { ys.push(Math.min(...row), Math.max(...row)); }
    if (s.sley) {
      for (const p of [s.sley.crank_centre, s.sley.rocking_shaft, ...s.sley.crank_pin, ...s.sley.sword_pin, ...s.sley.reed]) { xs.push(p[0]); ys.push(p[1]); }
    }
    drv.bounds = { side: s, x: [Math.min(...xs), Math.max(...xs)], y: [Math.min(...ys), Math.max(...ys)] };
  }
  const b = drv.bounds, top = 30, pad = 24;
  const scale = Math.min((w - 2 * pad) / (b.x[1] - b.x[0] || 1), (h - top - pad) / (b.y[1] - b.y[0] || 1));
  const ox = pad + ((w - 2 * pad) - scale * (b.x[1] - b.x[0])) / 2 - scale * b.x[0];
  const oy = top + ((h - top - pad) - scale * (b.y[1] - b.y[0])) / 2 + scale * b.y[1];
  const P = (p) => [ox + scale * p[0], oy - scale * p[1]];

  const line = (pts, color, width, dash) => {
    c.strokeStyle = color; c.lineWidth = width; c.setLineDash(dash || []);
    c.beginPath(); pts.forEach((p, i) => { const [x, y] = P(p); if (i) c.lineTo(x, y); else c.moveTo(x, y); }); c.stroke(); c.setLineDash([]);
  };
  const dot = (p, color, r) => { const [x, y] = P(p); c.fillStyle = color; c.beginPath(); c.arc(x, y, r, 0, 2 * Math.PI); c.fill(); };
  const k = drv.k, a = s.angle_deg[k];
  c.font = "600 13px system-ui, sans-serif"; c.fillStyle = "#111827"; c.textBaseline = "middle"; c.textAlign = "left";
  c.fillText(`The loom from the side at ${num(a, 1)}° (pick ${Math.floor(a / 360) + 1})`, 6, 12);
  c.save();
  c.beginPath(); c.rect(0, top - 6, w, h - top + 6); c.clip();
  // The cloth in front of the fell and the shed: every end from the fell through its frame's heald eye to the back rest.
  line([[b.x[0], 0], [0, 0]], "#9ca3af", 3);
  s.heald_x_mm.forEach((x, i) => line([[0, 0], [x, s.heald_y_mm[i][k]], s.back_rest_mm], FRAME_COLOURS[i % FRAME_COLOURS.length], 1));
  // The heald frames: a bar through each eye.
  s.heald_x_mm.forEach((x, i) => {
    const y = s.heald_y_mm[i][k], [px, py] = P([x, y]);
    c.fillStyle = FRAME_COLOURS[i % FRAME_COLOURS.length];
    c.fillRect(px - 1.5, py - 18, 3, 36);
  });
  dot([0, 0], "#111827", 3);
  if (s.sley) {
    const q = s.sley, reed = q.reed[k];
    // The crank's circle, the crank, the rod, the sword up to the reed and the reed above it.
    const r = Math.hypot(q.crank_pin[k][0] - q.crank_centre[0], q.crank_pin[k][1] - q.crank_centre[1]);
    const [cx, cy] = P(q.crank_centre);
    c.strokeStyle = "#d1d5db"; c.lineWidth = 1; c.setLineDash([4, 3]); c.beginPath(); c.arc(cx, cy, r * scale, 0, 2 * Math.PI); c.stroke(); c.setLineDash([]);
    line([q.crank_centre, q.crank_pin[k]], SLEY, 4);
    line([q.crank_pin[k], q.sword_pin[k]], SLEY, 3);
    line([q.rocking_shaft, reed], SLEY, 4);
    const len = Math.hypot(reed[0] - q.rocking_shaft[0], reed[1] - q.rocking_shaft[1]) || 1;
    const up = [(reed[0] - q.rocking_shaft[0]) / len, (reed[1] - q.rocking_shaft[1]) / len];
    const reach = Math.max(...s.heald_y_mm.map((row) => Math.max(...row)), 1);
    line([reed, [reed[0] + up[0] * reach, reed[1] + up[1] * reach]], REED, 5);
    for (const p of [q.crank_centre, q.rocking_shaft]) dot(p, "#111827", 5);
    for (const p of [q.crank_pin[k], q.sword_pin[k]]) dot(p, "#f59e0b", 4);
    dot(reed, REED, 4);
  }
  c.font = "11px system-ui, sans-serif"; c.fillStyle = "#4b5563"; c.textAlign = "right";
  const [fx, fy] = P([0, 0]);
  c.fillText("fell", fx - 6, fy - 8);
  c.textAlign = "left";
  c.fillText(`warp to the back rest, ${num(s.back_rest_mm[0], 0)} mm behind the fell →`, P([Math.max(...s.heald_x_mm, 0), 0])[0] + 8, fy + 22);
  c.restore();
}

register("drive", "Drive", initDrive);
})();
