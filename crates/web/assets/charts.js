// loomkin charts: line charts on <canvas> with axes (quantity and unit), grid, legend,
// hover read-out and draggable points. Written for loomkin; no third-party code.
(() => {
"use strict";

// Rounding slack of tick arithmetic, as fractions of a tick step: a bound within TICK_SNAP of a
// whole step is on it (and a tick that near zero is 0); the last tick may overshoot by TICK_SLACK.
const TICK_SNAP = 1e-9, TICK_SLACK = 1e-6;

const PALETTE = ["#1f5fa8", "#c2410c", "#15803d", "#7c3aed", "#b91c1c", "#0e7490", "#a16207", "#be185d"];

// A "nice" tick step near range / count: 1, 2 or 5 times a power of ten.
function niceStep(range, count) {
  if (!(range > 0) || !isFinite(range)) return 1;
  const raw = range / Math.max(count, 1);
  const p = Math.pow(10, Math.floor(Math.log10(raw)));
  const f = raw / p;
  return (f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10) * p;
}

// Ticks covering [lo, hi], and the bounds widened to whole steps (a multiple of fixedStep when
// given, e.g. 90 for angles in degrees).
function niceTicks(lo, hi, count, fixedStep) {
  if (!isFinite(lo) || !isFinite(hi)) { lo = 0; hi = 1; }
  if (hi - lo < 1e-12 * Math.max(1, Math.abs(lo), Math.abs(hi))) {
    const d = Math.abs(lo) > 0 ? Math.abs(lo) * 0.1 : 1;
    lo -= d; hi += d;
  }
  let step = niceStep(hi - lo, count);
  if (fixedStep) step = fixedStep * Math.max(1, Math.round(step / fixedStep));
  const a = Math.floor(lo / step + TICK_SNAP) * step;
  const b = Math.ceil(hi / step - TICK_SNAP) * step;
  return { lo: a, hi: b, step, ticks: stepTicks(a, b, step) };
}

// The ticks first, first + step, … up to last (within TICK_SLACK), a tick near zero written as 0.
function stepTicks(first, last, step) {
  const ticks = [];
  for (let t = first; t <= last + step * TICK_SLACK; t += step) ticks.push(Math.abs(t) < step * TICK_SNAP ? 0 : t);
  return ticks;
}

// A number for a label: enough digits for the step, no trailing noise; never "NaN".
function fmtTick(v, step) {
  if (!isFinite(v)) return "–";
  if (Math.abs(v) < Math.abs(step) * TICK_SLACK) v = 0; // no "-0"
  const d = Math.max(0, Math.min(8, -Math.floor(Math.log10(step) + TICK_SNAP)));
  return v.toFixed(d);
}

// A read-out number with 4 significant digits.
function fmtValue(v) {
  if (!isFinite(v)) return "–";
  const a = Math.abs(v);
  if (a !== 0 && (a >= 1e6 || a < 1e-3)) return v.toExponential(3);
  return Number(v.toPrecision(4)).toString();
}

// Linear interpolation of series (xs ascending) at x.
function interp(xs, ys, x) {
  const n = xs.length;
  if (n === 0) return NaN;
  if (x <= xs[0]) return ys[0];
  if (x >= xs[n - 1]) return ys[n - 1];
  let lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    const m = (lo + hi) >> 1;
    if (xs[m] <= x) lo = m; else hi = m;
  }
  const t = (x - xs[lo]) / (xs[hi] - xs[lo] || 1);
  return ys[lo] + t * (ys[hi] - ys[lo]);
}

function axisTitle(q, u) {
  return u ? `${q} (${u})` : q;
}

class Chart {
  // opts: { title, x: {label, unit, range?}, y: {label, unit, range?}, height? }
  constructor(container, opts) {
    this.opts = opts;
    this.series = [];
    this.points = null;
    this.hoverX = null;
    this.drag = null;
    this.wrap = document.createElement("div");
    this.wrap.className = "chart";
    if (opts.id) this.wrap.id = opts.id;
    this.canvas = document.createElement("canvas");
    this.canvas.style.height = (opts.height || 220) + "px";
    this.canvas.setAttribute("role", "img");
    this.canvas.setAttribute("aria-label", opts.title || axisTitle(opts.y.label, opts.y.unit));
    this.wrap.appendChild(this.canvas);
    container.appendChild(this.wrap);
    this.ctx = this.canvas.getContext("2d");
    this.canvas.addEventListener("pointermove", (e) => this.onMove(e));
    this.canvas.addEventListener("pointerdown", (e) => this.onDown(e));
    this.canvas.addEventListener("pointerup", (e) => this.onUp(e));
    this.canvas.addEventListener("pointercancel", (e) => this.onUp(e));
    this.canvas.addEventListener("pointerleave", () => { if (!this.drag && !this.pan) { this.hoverX = null; this.draw(); } });
    this.canvas.addEventListener("wheel", (e) => this.onWheel(e), { passive: false });
    this.canvas.addEventListener("dblclick", () => this.resetView());
    this.view = null; // zoomed / panned ranges {x: [lo, hi], y: [lo, hi]}; null = fit the data
    this.freeX = false; // dragging a point moves its X too (else only with Shift held)
    addTools(this, ["png", "svg", "csv"]);
    if (window.ResizeObserver) new ResizeObserver(() => this.draw()).observe(this.canvas);
  }

  // Back to the ranges that fit the data (double-click, or the ⟲ button).
  resetView() {
    this.view = null;
    this.draw();
  }

  // The file name of downloads: the chart's id, else its title.
  fileStem() {
    return this.opts.id || (this.opts.title || "chart").toLowerCase().replace(/[^a-z0-9]+/g, "-").replace(/^-|-$/g, "");
  }

  // The curves as CSV, one column per quantity with its unit in the header. Series on one common
  // x grid share a row per x; otherwise (e.g. a point cloud) one row per point: series, x, y.
  toCSV() {
    const xu = this.opts.x.unit ? ` (${this.opts.x.unit})` : "", yu = this.opts.y.unit ? ` (${this.opts.y.unit})` : "";
    const xname = this.opts.x.label + xu;
    const ss = this.series.filter((s) => s.x && s.x.length);
    const cell = (v) => (typeof v === "number" ? (isFinite(v) ? String(v) : "") : csvQuote(String(v)));
    const lines = [];
    const same = ss.length > 0 && ss.every((s) => s.x.length === ss[0].x.length && s.x.every((v, i) => v === ss[0].x[i]));
    if (same) {
      lines.push([xname, ...ss.map((s, k) => `${s.label || this.opts.y.label || "y" + (k + 1)}${s.unit ? ` (${s.unit})` : yu}`)].map(csvQuote).join(","));
      for (let i = 0; i < ss[0].x.length; i++) lines.push([ss[0].x[i], ...ss.map((s) => s.y[i])].map(cell).join(","));
    } else {
      lines.push(["series", xname, this.opts.y.label + yu].map(csvQuote).join(","));
      for (const s of ss) for (let i = 0; i < s.x.length; i++) lines.push([s.label || "", s.x[i], s.y[i]].map(cell).join(","));
    }
    return lines.join("\n") + "\n";
  }

  // The chart as it is drawn (zoom included), as an SVG document.
  toSVG() {
    return renderSVG(this);
  }

  // series: [{label, color?, x: [], y: [], dash?: []}]
  setSeries(series) {
    this.series = series.map((s, i) => Object.assign({ color: PALETTE[i % PALETTE.length] }, s));
    this.draw();
  }

  // points: [{x, y, fixed?}]; handlers: {onDrag(i, x, y), onDragEnd(i)}
  setPoints(points, handlers) {
    this.points = points;
    if (handlers) this.handlers = handlers;
    this.draw();
  }

  setHandlers(handlers) {
    this.handlers = handlers;
  }

  // The data ranges, widened to nice ticks; fixed ranges are kept.
  layout() {
    const dpr = this.pixelScale || window.devicePixelRatio || 1;
    const w = this.canvas.clientWidth || 600, h = this.canvas.clientHeight || 220;
    if (this.canvas.width !== Math.round(w * dpr) || this.canvas.height !== Math.round(h * dpr)) {
      this.canvas.width = Math.round(w * dpr);
      this.canvas.height = Math.round(h * dpr);
    }
    let xlo = Infinity, xhi = -Infinity, ylo = Infinity, yhi = -Infinity;
    const logY = !!this.opts.y.log;
    for (const s of this.series) {
      for (let i = 0; i < s.x.length; i++) {
        const x = s.x[i], y = logY ? log10(s.y[i]) : s.y[i];
        if (!isFinite(x) || !isFinite(y)) continue;
        if (x < xlo) xlo = x; if (x > xhi) xhi = x;
        if (y < ylo) ylo = y; if (y > yhi) yhi = y;
      }
    }
    for (const p of this.points || []) {
      if (p.y < ylo) ylo = p.y; if (p.y > yhi) yhi = p.y;
    }
    if (this.opts.x.range) [xlo, xhi] = this.opts.x.range;
    if (this.opts.y.range && !logY) [ylo, yhi] = this.opts.y.range;
    if (this.opts.y.includeZero && !logY) { ylo = Math.min(ylo, 0); yhi = Math.max(yhi, 0); }
    if (!this.opts.y.range && !logY && isFinite(ylo) && isFinite(yhi)) {
      // 2 % headroom away from zero, so that no curve runs hidden along the frame.
      const pad = 0.02 * (yhi - ylo);
      if (yhi > 0) yhi += pad;
      if (ylo < 0) ylo -= pad;
    }
    const left = 64, right = 14, bottom = 42;
    const legend = this.legendLayout(left, w - right);
    const top = 30 + 17 * (legend.rows - 1);
    const pw = Math.max(w - left - right, 10), ph = Math.max(h - top - bottom, 10);
    let xt = this.opts.x.range ? { lo: xlo, hi: xhi, ...niceTicksIn(xlo, xhi, pw / 80, this.opts.x.step) } : niceTicks(xlo, xhi, pw / 80, this.opts.x.step);
    let yt = logY ? logTicks(ylo, yhi) : this.opts.y.range ? { lo: ylo, hi: yhi, ...niceTicksIn(ylo, yhi, ph / 40) } : niceTicks(ylo, yhi, ph / 40, this.opts.y.step);
    this.home = { x: [xt.lo, xt.hi], y: [yt.lo, yt.hi] };
    if (this.view) {
      const [a, b] = this.view.x, [c, d] = this.view.y;
      xt = { lo: a, hi: b, ...niceTicksIn(a, b, pw / 80, this.opts.x.step) };
      yt = logY
        ? { lo: c, hi: d, step: 1, ticks: logTicks(c, d).ticks.filter((t) => t >= c - 1e-9 && t <= d + 1e-9) }
        : { lo: c, hi: d, ...niceTicksIn(c, d, ph / 40, this.opts.y.step) };
    }
    if (logY) yt.log = true;
    return { dpr, w, h, left, top, pw, ph, xt, yt, legend };
  }

  // Data (x, y) to canvas pixels; on a log axis y is the value itself (its log10 is placed).
  toPx(L, x, y) {
    const ty = L.yt.log ? log10(y) : y;
    return [L.left + (x - L.xt.lo) / (L.xt.hi - L.xt.lo) * L.pw, L.top + (L.yt.hi - ty) / (L.yt.hi - L.yt.lo) * L.ph];
  }

  fromPx(L, px, py) {
    const ty = L.yt.hi - (py - L.top) / L.ph * (L.yt.hi - L.yt.lo);
    return [L.xt.lo + (px - L.left) / L.pw * (L.xt.hi - L.xt.lo), L.yt.log ? Math.pow(10, ty) : ty];
  }

  // Axis coordinates (log10 of y on a log axis) of a pixel, for zoom and pan.
  axisAt(L, px, py) {
    return [L.xt.lo + (px - L.left) / L.pw * (L.xt.hi - L.xt.lo), L.yt.hi - (py - L.top) / L.ph * (L.yt.hi - L.yt.lo)];
  }

  // Client (viewport) coordinates of point i, for tests and keyboard helpers.
  pointClientXY(i) {
    const L = this.L || this.layout();
    const p = this.points[i];
    const [px, py] = this.toPx(L, p.x, p.y);
    const r = this.canvas.getBoundingClientRect();
    return { x: r.left + px, y: r.top + py };
  }

  draw() {
    const L = this.layout();
    this.L = L;
    if (this.resetButton) this.resetButton.hidden = !this.view;
    const c = this.ctx;
    c.setTransform(L.dpr, 0, 0, L.dpr, 0, 0);
    c.clearRect(0, 0, L.w, L.h);
    c.font = "12px system-ui, sans-serif";
    // Grid and tick labels.
    c.strokeStyle = "#e3e6ea"; c.lineWidth = 1; c.fillStyle = "#4b5563";
    c.textAlign = "center"; c.textBaseline = "top";
    for (const t of L.xt.ticks) {
      const [px] = this.toPx(L, t, 0);
      c.beginPath(); c.moveTo(px + 0.5, L.top); c.lineTo(px + 0.5, L.top + L.ph); c.stroke();
      c.fillText(fmtTick(t, L.xt.step), px, L.top + L.ph + 4);
    }
    c.textAlign = "right"; c.textBaseline = "middle";
    for (const t of L.yt.ticks) {
      const py = L.top + (L.yt.hi - t) / (L.yt.hi - L.yt.lo) * L.ph;
      c.beginPath(); c.moveTo(L.left, py + 0.5); c.lineTo(L.left + L.pw, py + 0.5); c.stroke();
      c.fillText(L.yt.log ? fmtLogTick(t) : fmtTick(t, L.yt.step), L.left - 5, py);
    }
    // Zero line and frame.
    if (!L.yt.log && L.yt.lo < 0 && L.yt.hi > 0) {
      const [, py] = this.toPx(L, 0, 0);
      c.strokeStyle = "#9ca3af"; c.beginPath(); c.moveTo(L.left, py + 0.5); c.lineTo(L.left + L.pw, py + 0.5); c.stroke();
    }
    c.strokeStyle = "#6b7280"; c.strokeRect(L.left + 0.5, L.top + 0.5, L.pw, L.ph);
    // Axis titles: quantity (unit).
    c.fillStyle = "#111827"; c.textAlign = "center"; c.textBaseline = "bottom";
    c.fillText(axisTitle(this.opts.x.label, this.opts.x.unit), L.left + L.pw / 2, L.h - 2);
    c.save(); c.translate(13, L.top + L.ph / 2); c.rotate(-Math.PI / 2); c.textBaseline = "middle";
    c.fillText(axisTitle(this.opts.y.label, this.opts.y.unit) + (L.yt.log ? ", log scale" : ""), 0, 0); c.restore();
    // Series, clipped to the plot.
    c.save(); c.beginPath(); c.rect(L.left, L.top, L.pw, L.ph); c.clip();
    // Shaded spans of x (dwells), under the curves.
    if (this.bands) {
      c.fillStyle = "rgba(148, 163, 184, 0.2)";
      for (const [a, b] of this.bands) {
        const [p0] = this.toPx(L, a, 0), [p1] = this.toPx(L, b, 0);
        c.fillRect(p0, L.top, p1 - p0, L.ph);
      }
    }
    for (const s of this.series) {
      if (s.mode === "points" || s.mode === "markers") {
        c.fillStyle = s.color;
        const r = s.radius || 1.6;
        for (let i = 0; i < s.x.length; i++) {
          if (!isFinite(s.x[i]) || !isFinite(s.y[i])) continue;
          const [px, py] = this.toPx(L, s.x[i], s.y[i]);
          if (s.mode === "points") c.fillRect(px - r, py - r, 2 * r, 2 * r);
          else { c.beginPath(); c.arc(px, py, r, 0, 2 * Math.PI); c.fill(); c.strokeStyle = "#111827"; c.lineWidth = 1; c.stroke(); }
        }
        if (s.mode === "points") continue;
        if (!s.line) continue;
      }
      c.strokeStyle = s.color; c.lineWidth = s.width || 1.8; c.setLineDash(s.dash || []);
      c.beginPath();
      let pen = false;
      for (let i = 0; i < s.x.length; i++) {
        if (!isFinite(s.x[i]) || !isFinite(s.y[i])) { pen = false; continue; }
        const [px, py] = this.toPx(L, s.x[i], s.y[i]);
        if (pen) c.lineTo(px, py); else c.moveTo(px, py);
        pen = true;
      }
      c.stroke();
    }
    c.setLineDash([]);
    // Definition points.
    if (this.points) {
      this.points.forEach((p, i) => {
        const [px, py] = this.toPx(L, p.x, p.y);
        c.beginPath(); c.arc(px, py, this.drag && this.drag.i === i ? 7 : 5.5, 0, 2 * Math.PI);
        c.fillStyle = p.fixed ? "#9ca3af" : "#f59e0b"; c.fill();
        c.strokeStyle = "#111827"; c.lineWidth = 1.2; c.stroke();
      });
    }
    // Horizontal reference lines (limits): [{y, color?, label?}].
    for (const hl of this.hlines || []) {
      const [, py] = this.toPx(L, 0, hl.y);
      if (!isFinite(py)) continue;
      c.strokeStyle = hl.color || "#b91c1c"; c.lineWidth = 1.5; c.setLineDash([7, 4]);
      c.beginPath(); c.moveTo(L.left, py); c.lineTo(L.left + L.pw, py); c.stroke(); c.setLineDash([]);
      if (hl.label) {
        // Above a line at or over zero, below a negative one — unless that side has no room for the
        // text inside the plot (a line near the top or the bottom edge), then on the other side.
        const LABEL_PX = 16;
        let above = hl.y >= 0;
        if (above && py - LABEL_PX < L.top) above = false;
        else if (!above && py + LABEL_PX > L.top + L.ph) above = true;
        c.fillStyle = hl.color || "#b91c1c"; c.font = "12px system-ui, sans-serif"; c.textAlign = "right"; c.textBaseline = above ? "bottom" : "top";
        c.fillText(hl.label, L.left + L.pw - 4, py + (above ? -2 : 2));
      }
    }
    if (this.markerX !== undefined && this.markerX !== null) {
      const [mx] = this.toPx(L, this.markerX, 0);
      c.strokeStyle = "#f59e0b"; c.lineWidth = 2; c.beginPath(); c.moveTo(mx, L.top); c.lineTo(mx, L.top + L.ph); c.stroke();
    }
    c.restore();
    this.drawLegend(L);
    if (this.hoverX !== null) this.drawHover(L);
  }

  // Positions of the title and legend entries, wrapped onto as many rows as needed.
  legendLayout(x0, x1) {
    const c = this.ctx;
    const items = [];
    let x = x0, row = 0;
    if (this.opts.title) {
      c.font = "600 13px system-ui, sans-serif";
      items.push({ title: this.opts.title, x, row });
      x += c.measureText(this.opts.title).width + 18;
    }
    c.font = "12px system-ui, sans-serif";
    for (const s of this.series) {
      if (!s.label) continue;
      const wdt = 22 + c.measureText(s.label).width + 14;
      const end = row === 0 ? x1 - TOOLS_PX : x1; // the download buttons sit at the right of the first row
      if (x + wdt > end && x > x0) { row++; x = x0; }
      items.push({ s, x, row });
      x += wdt;
    }
    return { items, rows: row + 1 };
  }

  drawLegend(L) {
    const c = this.ctx;
    c.textAlign = "left"; c.textBaseline = "middle";
    for (const it of L.legend.items) {
      const y = 13 + 17 * it.row;
      if (it.title) {
        c.fillStyle = "#111827"; c.font = "600 13px system-ui, sans-serif";
        c.fillText(it.title, it.x, y);
        continue;
      }
      const s = it.s;
      c.font = "12px system-ui, sans-serif";
      if (s.mode === "points" || s.mode === "markers") {
        c.fillStyle = s.color; c.beginPath(); c.arc(it.x + 9, y, 4, 0, 2 * Math.PI); c.fill();
      } else {
        c.strokeStyle = s.color; c.lineWidth = 2.5; c.setLineDash(s.dash || []);
        c.beginPath(); c.moveTo(it.x, y); c.lineTo(it.x + 18, y); c.stroke(); c.setLineDash([]);
      }
      c.fillStyle = "#1f2937"; c.fillText(s.label, it.x + 22, y);
    }
  }

  drawHover(L) {
    const c = this.ctx;
    const x = this.hoverX;
    const [px] = this.toPx(L, x, 0);
    c.strokeStyle = "rgba(17,24,39,0.45)"; c.lineWidth = 1; c.setLineDash([4, 3]);
    c.beginPath(); c.moveTo(px + 0.5, L.top); c.lineTo(px + 0.5, L.top + L.ph); c.stroke(); c.setLineDash([]);
    const lines = [[null, `${this.opts.x.label} = ${fmtValue(x)}${this.opts.x.unit ? " " + this.opts.x.unit : ""}`]];
    for (const s of this.series) {
      if (s.mode === "points" || s.hover === false) continue;
      const y = interp(s.x, s.y, x);
      if (!isFinite(y)) continue;
      const [, py] = this.toPx(L, x, y);
      c.fillStyle = s.color; c.beginPath(); c.arc(px, py, 3, 0, 2 * Math.PI); c.fill();
      lines.push([s.color, `${s.label || this.opts.y.label} = ${fmtValue(y)}${this.opts.y.unit ? " " + this.opts.y.unit : ""}`]);
    }
    c.font = "12px system-ui, sans-serif";
    const bw = Math.max(...lines.map(([, t]) => c.measureText(t).width)) + 26, bh = lines.length * 16 + 8;
    let bx = px + 10, by = L.top + 6;
    if (bx + bw > L.left + L.pw) bx = px - 10 - bw;
    c.fillStyle = "rgba(255,255,255,0.93)"; c.strokeStyle = "#9ca3af";
    c.fillRect(bx, by, bw, bh); c.strokeRect(bx + 0.5, by + 0.5, bw, bh);
    c.textAlign = "left"; c.textBaseline = "middle";
    lines.forEach(([col, t], k) => {
      const ty = by + 12 + k * 16;
      if (col) { c.fillStyle = col; c.fillRect(bx + 6, ty - 4, 10, 8); }
      c.fillStyle = "#111827"; c.fillText(t, bx + (col ? 20 : 6), ty);
    });
  }

  eventXY(e) {
    const r = this.canvas.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  }

  nearestPoint(px, py) {
    if (!this.points || !this.L) return -1;
    let best = -1, bd = 12 * 12;
    this.points.forEach((p, i) => {
      if (p.fixed) return;
      const [qx, qy] = this.toPx(this.L, p.x, p.y);
      const d = (qx - px) ** 2 + (qy - py) ** 2;
      if (d < bd) { bd = d; best = i; }
    });
    return best;
  }

  onDown(e) {
    if (e.button !== undefined && e.button !== 0) return;
    const [px, py] = this.eventXY(e);
    const i = this.nearestPoint(px, py);
    if (i < 0) {
      // Pan if the pointer moves, a click (handlers.onClick) if it does not.
      if (!this.L) return;
      this.pan = { px, py, moved: false, x: [this.L.xt.lo, this.L.xt.hi], y: [this.L.yt.lo, this.L.yt.hi] };
      try { this.canvas.setPointerCapture(e.pointerId); } catch (_) { /* synthetic pointers */ }
      return;
    }
    this.drag = { i, x0: this.points[i].x };
    try { this.canvas.setPointerCapture(e.pointerId); } catch (_) { /* synthetic pointers */ }
    e.preventDefault();
    this.draw();
  }

  onMove(e) {
    const [px, py] = this.eventXY(e);
    const L = this.L || this.layout();
    const [x, y] = this.fromPx(L, px, py);
    if (this.pan) {
      const dx = px - this.pan.px, dy = py - this.pan.py;
      if (!this.pan.moved && dx * dx + dy * dy < 16) return;
      this.pan.moved = true;
      const sx = (this.pan.x[1] - this.pan.x[0]) / L.pw * dx, sy = (this.pan.y[1] - this.pan.y[0]) / L.ph * dy;
      this.view = { x: [this.pan.x[0] - sx, this.pan.x[1] - sx], y: [this.pan.y[0] + sy, this.pan.y[1] + sy] };
      this.canvas.style.cursor = "grabbing";
      this.hoverX = null;
      this.draw();
      return;
    }
    if (this.drag) {
      // Y only, unless Shift is held or the chart lets X move (the page's lock toggle).
      const nx = e.shiftKey || this.freeX ? x : this.drag.x0;
      if (this.handlers && this.handlers.onDrag) this.handlers.onDrag(this.drag.i, nx, y);
      this.hoverX = null;
      this.draw();
      return;
    }
    this.canvas.style.cursor = this.nearestPoint(px, py) >= 0 ? "grab" : "crosshair";
    this.hoverX = px >= L.left && px <= L.left + L.pw ? x : null;
    this.draw();
  }

  onUp(e) {
    if (this.pan) {
      const p = this.pan;
      this.pan = null;
      try { this.canvas.releasePointerCapture(e.pointerId); } catch (_) { /* not captured */ }
      this.canvas.style.cursor = "crosshair";
      if (!p.moved && e.type === "pointerup" && this.handlers && this.handlers.onClick && this.L) {
        const [x, y] = this.fromPx(this.L, p.px, p.py);
        this.handlers.onClick(x, y, p.px, p.py);
      }
      return;
    }
    if (!this.drag) return;
    const i = this.drag.i;
    this.drag = null;
    try { this.canvas.releasePointerCapture(e.pointerId); } catch (_) { /* not captured */ }
    if (this.handlers && this.handlers.onDragEnd) this.handlers.onDragEnd(i);
    this.draw();
  }
}

// Wheel: zoom about the pointer by 1.25 per notch (x and y; Shift: x only, Alt: y only).
Chart.prototype.onWheel = function (e) {
  const L = this.L;
  if (!L) return;
  e.preventDefault();
  const [px, py] = this.eventXY(e);
  const [ax, ay] = this.axisAt(L, px, py);
  const k = e.deltaY > 0 ? 1.25 : 1 / 1.25;
  const zx = e.altKey ? 1 : k, zy = e.shiftKey ? 1 : k;
  this.view = {
    x: [ax - (ax - L.xt.lo) * zx, ax + (L.xt.hi - ax) * zx],
    y: [ay - (ay - L.yt.lo) * zy, ay + (L.yt.hi - ay) * zy],
  };
  this.draw();
};

// Zoom to given ranges (tests, the page); y in axis units (log10 on a log axis).
Chart.prototype.zoomTo = function (x, y) {
  const L = this.L || this.layout();
  this.view = { x: x || [L.xt.lo, L.xt.hi], y: y || [L.yt.lo, L.yt.hi] };
  this.draw();
};

function log10(v) {
  return v > 0 ? Math.log10(v) : NaN;
}

// Decade ticks for a log axis over [lo, hi] (log10 values); 2 and 5 between when few decades.
function logTicks(lo, hi) {
  if (!isFinite(lo) || !isFinite(hi)) { lo = 0; hi = 1; }
  const a = Math.floor(lo + 1e-9), b = Math.max(Math.ceil(hi - 1e-9), a + 1);
  const ticks = [];
  for (let d = a; d <= b; d++) {
    ticks.push(d);
    if (b - a <= 3 && d < b) ticks.push(d + Math.log10(2), d + Math.log10(5));
  }
  return { lo: a, hi: b, step: 1, ticks };
}

// A log-axis tick: 10ⁿ for whole decades beyond 10⁴ or below 10⁻², else the number.
function fmtLogTick(t) {
  const n = Math.round(t);
  if (Math.abs(t - n) < 1e-9 && (n > 4 || n < -2)) {
    const sup = { "-": "⁻", 0: "⁰", 1: "¹", 2: "²", 3: "³", 4: "⁴", 5: "⁵", 6: "⁶", 7: "⁷", 8: "⁸", 9: "⁹" };
    return "10" + String(n).split("").map((ch) => sup[ch]).join("");
  }
  return fmtValue(Math.pow(10, t));
}

function csvQuote(t) {
  return /[",\n]/.test(t) ? `"${t.replace(/"/g, '""')}"` : t;
}

// ---------------------------------------------------------------- downloads

// Saves text or a Blob as a file (a link clicked). Tests replace LoomkinCharts.download to see
// what would be saved.
function download(filename, data, type) {
  const blob = data instanceof Blob ? data : new Blob([data], { type: type || "text/plain" });
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = filename;
  document.body.appendChild(a);
  a.click();
  setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
}

const TOOLS_PX = 64;

// The buttons over a chart's top-right corner: "save" (a menu of PNG, SVG and CSV downloads)
// and, once zoomed or panned, the reset.
function addTools(chart, kinds) {
  const bar = document.createElement("div");
  bar.className = "chart-tools";
  const mk = (parent, text, tool, title, fn) => {
    const b = document.createElement("button");
    b.type = "button"; b.textContent = text; b.title = title; b.dataset.tool = tool;
    b.addEventListener("click", () => { if (parent === menu) menu.hidden = true; fn(); });
    parent.appendChild(b);
    return b;
  };
  const menu = document.createElement("div");
  menu.className = "chart-menu";
  menu.hidden = true;
  const dl = (ext, data, type) => window.LoomkinCharts.download(`${chart.fileStem()}.${ext}`, data, type);
  const reset = mk(bar, "⟲", "reset", "reset zoom and pan (or double-click the chart)", () => chart.resetView());
  reset.hidden = true;
  mk(bar, "save ▾", "save", "save the chart: PNG, SVG or CSV", () => { menu.hidden = !menu.hidden; });
  if (kinds.includes("png")) mk(menu, `PNG picture (${PNG_SCALE}×)`, "png", `the chart as drawn, on white, at ${PNG_SCALE}× its size on screen`, () => renderPNG(chart, PNG_SCALE, (b) => dl("png", b, "image/png")));
  if (kinds.includes("svg")) mk(menu, "SVG drawing", "svg", "the chart as an SVG drawing", () => dl("svg", chart.toSVG(), "image/svg+xml"));
  if (kinds.includes("csv")) mk(menu, "CSV data", "csv", "the curves as CSV (units in the header)", () => dl("csv", chart.toCSV(), "text/csv"));
  bar.appendChild(menu);
  chart.wrap.style.position = "relative";
  chart.wrap.appendChild(bar);
  chart.tools = bar;
  chart.resetButton = reset;
}

// ---------------------------------------------------------------- SVG output

// A stand-in for the canvas 2D context that records the drawing as SVG elements: the charts draw
// into it with their own draw() code, so the SVG is the picture on screen, in CSS pixels.
class SvgContext {
  constructor(real, w, h) {
    this.real = real;
    this.w = w; this.h = h;
    this.out = [];
    this.defs = [];
    this.m = [1, 0, 0, 1, 0, 0];
    this.stack = [];
    this.open = 0;
    this.d = "";
    this.dash = [];
    Object.assign(this, { fillStyle: "#000", strokeStyle: "#000", lineWidth: 1, font: "12px sans-serif", textAlign: "start", textBaseline: "alphabetic" });
  }
  setTransform() { this.m = [1, 0, 0, 1, 0, 0]; }
  translate(x, y) { const m = this.m; this.m = [m[0], m[1], m[2], m[3], m[4] + m[0] * x + m[2] * y, m[5] + m[1] * x + m[3] * y]; }
  rotate(t) {
    const [a, b, c, d, e, f] = this.m, cs = Math.cos(t), sn = Math.sin(t);
    this.m = [a * cs + c * sn, b * cs + d * sn, c * cs - a * sn, d * cs - b * sn, e, f];
  }
  P(x, y) { const m = this.m; return [m[0] * x + m[2] * y + m[4], m[1] * x + m[3] * y + m[5]]; }
  save() { this.stack.push({ m: this.m.slice(), open: this.open, dash: this.dash, s: [this.fillStyle, this.strokeStyle, this.lineWidth, this.font, this.textAlign, this.textBaseline] }); this.open = 0; }
  restore() {
    const st = this.stack.pop();
    if (!st) return;
    for (; this.open > 0; this.open--) this.out.push("</g>");
    this.m = st.m; this.open = st.open; this.dash = st.dash;
    [this.fillStyle, this.strokeStyle, this.lineWidth, this.font, this.textAlign, this.textBaseline] = st.s;
  }
  clearRect() { /* the background is drawn once */ }
  setLineDash(d) { this.dash = d || []; }
  measureText(t) { this.real.font = this.font; return this.real.measureText(t); }
  beginPath() { this.d = ""; }
  moveTo(x, y) { const [a, b] = this.P(x, y); this.d += `M${r2(a)} ${r2(b)}`; }
  lineTo(x, y) { const [a, b] = this.P(x, y); this.d += `L${r2(a)} ${r2(b)}`; }
  closePath() { this.d += "Z"; }
  rect(x, y, w, h) { this.moveTo(x, y); this.lineTo(x + w, y); this.lineTo(x + w, y + h); this.lineTo(x, y + h); this.closePath(); }
  arc(x, y, r, a0, a1) {
    const n = Math.max(8, Math.ceil(Math.abs(a1 - a0) / (Math.PI / 16)));
    for (let k = 0; k <= n; k++) {
      const t = a0 + (a1 - a0) * k / n;
      if (k === 0 && this.d === "") this.moveTo(x + r * Math.cos(t), y + r * Math.sin(t)); else this.lineTo(x + r * Math.cos(t), y + r * Math.sin(t));
    }
  }
  stroke() {
    if (!this.d) return;
    const dash = this.dash.length ? ` stroke-dasharray="${this.dash.join(" ")}"` : "";
    this.out.push(`<path d="${this.d}" fill="none" stroke="${esc(this.strokeStyle)}" stroke-width="${this.lineWidth}"${dash}/>`);
  }
  fill() { if (this.d) this.out.push(`<path d="${this.d}" fill="${esc(this.fillStyle)}"/>`); }
  fillRect(x, y, w, h) { const d = this.d; this.beginPath(); this.rect(x, y, w, h); this.fill(); this.d = d; }
  strokeRect(x, y, w, h) { const d = this.d; this.beginPath(); this.rect(x, y, w, h); this.stroke(); this.d = d; }
  clip() {
    const id = `clip${this.defs.length}`;
    this.defs.push(`<clipPath id="${id}"><path d="${this.d}"/></clipPath>`);
    this.out.push(`<g clip-path="url(#${id})">`);
    this.open++;
  }
  fillText(t, x, y) {
    const anchor = { left: "start", start: "start", center: "middle", right: "end", end: "end" }[this.textAlign] || "start";
    const base = { top: "hanging", middle: "central", bottom: "text-after-edge" }[this.textBaseline] || "auto";
    const m = this.m.map(r2).join(" ");
    // Font as presentation attributes (no style attribute: the page's CSP refuses inline styles).
    const f = /^(?:(\d+|bold|normal)\s+)?([\d.]+)px\s+(.*)$/.exec(this.font) || [null, null, "12", "sans-serif"];
    const weight = f[1] ? ` font-weight="${f[1]}"` : "";
    this.out.push(`<text transform="matrix(${m})" x="${r2(x)}" y="${r2(y)}" fill="${esc(this.fillStyle)}" text-anchor="${anchor}" dominant-baseline="${base}" font-size="${f[2]}" font-family="${esc(f[3])}"${weight}>${esc(t)}</text>`);
  }
  svg() {
    while (this.stack.length) this.restore();
    return `<?xml version="1.0" encoding="UTF-8"?>\n<svg xmlns="http://www.w3.org/2000/svg" width="${this.w}" height="${this.h}" viewBox="0 0 ${this.w} ${this.h}">\n` +
      `<defs>${this.defs.join("")}</defs>\n<rect width="100%" height="100%" fill="#fff"/>\n${this.out.join("\n")}\n</svg>\n`;
  }
}

function r2(v) {
  return Math.round(v * 100) / 100;
}

function esc(t) {
  return String(t).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;").replace(/"/g, "&quot;");
}

// Pixels per CSS pixel of a PNG download: sharp on paper and on a high-density screen.
const PNG_SCALE = 2;

// Draws a Chart or Scene once at `scale` pixels per CSS pixel onto white (the canvas itself is
// transparent outside the lines) and passes the PNG Blob to `done`; the chart is drawn again as it was.
function renderPNG(chart, scale, done) {
  const hover = chart.hoverX;
  chart.pixelScale = scale;
  chart.hoverX = null;
  let out;
  try {
    chart.draw();
    out = document.createElement("canvas");
    out.width = chart.canvas.width; out.height = chart.canvas.height;
    const c = out.getContext("2d");
    c.fillStyle = "#fff";
    c.fillRect(0, 0, out.width, out.height);
    c.drawImage(chart.canvas, 0, 0);
  } finally {
    chart.pixelScale = null;
    chart.hoverX = hover;
    chart.draw();
  }
  out.toBlob(done, "image/png");
}

// Draws a Chart or Scene once into an SvgContext and returns the document.
function renderSVG(chart) {
  const real = chart.ctx, hover = chart.hoverX;
  const svg = new SvgContext(real, chart.canvas.clientWidth || 600, chart.canvas.clientHeight || 220);
  chart.ctx = svg;
  chart.hoverX = null;
  try { chart.draw(); } finally { chart.ctx = real; chart.hoverX = hover; chart.draw(); }
  return svg.svg();
}

// Ticks inside a fixed range [lo, hi] (the bounds are kept as given).
function niceTicksIn(lo, hi, count, fixedStep) {
  let step = niceStep(hi - lo, count);
  if (fixedStep) step = fixedStep * Math.max(1, Math.round(step / fixedStep));
  return { step, ticks: stepTicks(Math.ceil(lo / step - TICK_SNAP) * step, hi, step) };
}


// A drawing of a mechanism in the plane, equal scale on both axes, with a grid in mm.
// items: [{kind: "line", pts: [[x, y], …], color, width, dash, closed},
//         {kind: "circle", c: [x, y], r, color, fill, width}, {kind: "label", at: [x, y], text, color}]
class Scene {
  constructor(container, opts) {
    this.opts = opts;
    this.items = [];
    this.wrap = document.createElement("div");
    this.wrap.className = "chart";
    if (opts.id) this.wrap.id = opts.id;
    this.canvas = document.createElement("canvas");
    this.canvas.style.height = (opts.height || 420) + "px";
    this.canvas.setAttribute("role", "img");
    this.canvas.setAttribute("aria-label", opts.title || "mechanism");
    this.wrap.appendChild(this.canvas);
    container.appendChild(this.wrap);
    this.ctx = this.canvas.getContext("2d");
    this.view = null; // zoomed / panned bounds; null = this.bounds
    this.canvas.addEventListener("wheel", (e) => {
      if (!this.T) return;
      e.preventDefault();
      const [px, py] = this.eventXY(e), [x0, y0, x1, y1] = this.T.b, [ax, ay] = this.T.inv(px, py);
      const k = e.deltaY > 0 ? 1.25 : 1 / 1.25;
      this.view = [ax - (ax - x0) * k, ay - (ay - y0) * k, ax + (x1 - ax) * k, ay + (y1 - ay) * k];
      this.draw();
    }, { passive: false });
    this.canvas.addEventListener("pointerdown", (e) => {
      if (!this.T || e.button !== 0) return;
      const [px, py] = this.eventXY(e);
      this.pan = { px, py, b: this.T.b.slice(), k: this.T.k };
      try { this.canvas.setPointerCapture(e.pointerId); } catch (_) { /* synthetic pointers */ }
    });
    this.canvas.addEventListener("pointermove", (e) => {
      if (!this.pan) return;
      const [px, py] = this.eventXY(e), p = this.pan;
      const dx = (px - p.px) / p.k, dy = (py - p.py) / p.k;
      this.view = [p.b[0] - dx, p.b[1] + dy, p.b[2] - dx, p.b[3] + dy];
      this.draw();
    });
    const end = (e) => { if (this.pan) { this.pan = null; try { this.canvas.releasePointerCapture(e.pointerId); } catch (_) { /* not captured */ } } };
    this.canvas.addEventListener("pointerup", end);
    this.canvas.addEventListener("pointercancel", end);
    this.canvas.addEventListener("dblclick", () => this.resetView());
    addTools(this, ["png", "svg", "csv"]);
    if (window.ResizeObserver) new ResizeObserver(() => this.draw()).observe(this.canvas);
  }

  eventXY(e) {
    const r = this.canvas.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  }

  resetView() {
    this.view = null;
    this.draw();
  }

  fileStem() {
    return this.opts.id || "drawing";
  }

  toSVG() {
    return renderSVG(this);
  }

  // Every line and circle of the drawing in display units (mm): item, point, x, y (circles: centre and radius).
  toCSV() {
    const u = this.opts.unit ? `_${this.opts.unit}` : "", sc = this.opts.scale || 1;
    const lines = [`item,point,x${u},y${u},r${u}`];
    let n = 0;
    for (const it of this.items) {
      const name = csvQuote(it.legend || it.name || it.kind + n);
      if (it.kind === "line") it.pts.forEach((p, i) => lines.push(`${name},${i},${p[0] * sc},${p[1] * sc},`));
      else if (it.kind === "circle") lines.push(`${name},0,${it.c[0] * sc},${it.c[1] * sc},${it.r * sc}`);
      n++;
    }
    return lines.join("\n") + "\n";
  }

  // bounds: [xmin, ymin, xmax, ymax] in data units, kept fixed while the items change.
  setItems(items, bounds) {
    this.items = items;
    if (bounds) this.bounds = bounds;
    this.draw();
  }

  draw() {
    const dpr = this.pixelScale || window.devicePixelRatio || 1;
    const w = this.canvas.clientWidth || 600, h = this.canvas.clientHeight || 420;
    this.canvas.width = Math.round(w * dpr); this.canvas.height = Math.round(h * dpr);
    const c = this.ctx;
    c.setTransform(dpr, 0, 0, dpr, 0, 0);
    c.clearRect(0, 0, w, h);
    if (this.resetButton) this.resetButton.hidden = !this.view;
    if (!this.bounds) return;
    const [x0, y0, x1, y1] = this.view || this.bounds;
    // Legend entries wrapped onto rows; the download buttons sit at the right of the first row.
    c.font = "12px system-ui, sans-serif";
    const legend = [];
    {
      let lx = 56, row = 0;
      if (this.opts.title) { c.font = "600 13px system-ui, sans-serif"; legend.push({ title: this.opts.title, x: lx, row }); lx += c.measureText(this.opts.title).width + 18; c.font = "12px system-ui, sans-serif"; }
      for (const it of this.items) {
        if (!it.legend) continue;
        const wd = 22 + c.measureText(it.legend).width + 14;
        if (lx + wd > w - 12 - (row === 0 ? TOOLS_PX : 0) && lx > 56) { row++; lx = 56; }
        legend.push({ it, x: lx, row }); lx += wd;
      }
      this.legendRows = row + 1;
    }
    const left = 56, right = 12, top = 28 + 17 * (this.legendRows - 1), bottom = 38;
    const pw = w - left - right, ph = h - top - bottom;
    const k = Math.min(pw / (x1 - x0), ph / (y1 - y0));
    const cx = left + pw / 2 - k * (x0 + x1) / 2, cy = top + ph / 2 + k * (y0 + y1) / 2;
    const P = ([x, y]) => [cx + k * x, cy - k * y];
    this.T = { k, b: [(left - cx) / k, (cy - top - ph) / k, (left + pw - cx) / k, (cy - top) / k], inv: (px, py) => [(px - cx) / k, (cy - py) / k] };
    const scale = this.opts.scale || 1, unit = this.opts.unit || "";
    // Grid and axes in display units.
    const gx0 = (left - cx) / k, gx1 = (left + pw - cx) / k, gy0 = (cy - top - ph) / k, gy1 = (cy - top) / k;
    const step = niceStep((gx1 - gx0) * scale, pw / 80) / scale;
    c.font = "12px system-ui, sans-serif"; c.strokeStyle = "#e3e6ea"; c.fillStyle = "#4b5563"; c.lineWidth = 1;
    c.textAlign = "center"; c.textBaseline = "top";
    for (let t = Math.ceil(gx0 / step) * step; t <= gx1; t += step) {
      const [px] = P([t, 0]);
      c.beginPath(); c.moveTo(px + 0.5, top); c.lineTo(px + 0.5, top + ph); c.stroke();
      c.fillText(fmtTick(t * scale, step * scale), px, top + ph + 4);
    }
    c.textAlign = "right"; c.textBaseline = "middle";
    for (let t = Math.ceil(gy0 / step) * step; t <= gy1; t += step) {
      const [, py] = P([0, t]);
      c.beginPath(); c.moveTo(left, py + 0.5); c.lineTo(left + pw, py + 0.5); c.stroke();
      c.fillText(fmtTick(t * scale, step * scale), left - 5, py);
    }
    c.strokeStyle = "#6b7280"; c.strokeRect(left + 0.5, top + 0.5, pw, ph);
    c.fillStyle = "#111827"; c.textAlign = "center"; c.textBaseline = "bottom";
    c.fillText(axisTitle("x", unit), left + pw / 2, h - 2);
    c.save(); c.translate(13, top + ph / 2); c.rotate(-Math.PI / 2); c.textBaseline = "middle"; c.fillText(axisTitle("y", unit), 0, 0); c.restore();
    c.save(); c.beginPath(); c.rect(left, top, pw, ph); c.clip();
    for (const it of this.items) {
      if (it.kind === "line" && it.pts.length) {
        c.strokeStyle = it.color || "#111827"; c.lineWidth = it.width || 1.5; c.setLineDash(it.dash || []);
        c.beginPath();
        it.pts.forEach((p, i) => { const [px, py] = P(p); if (i) c.lineTo(px, py); else c.moveTo(px, py); });
        if (it.closed) c.closePath();
        c.stroke(); c.setLineDash([]);
      } else if (it.kind === "circle") {
        const [px, py] = P(it.c);
        c.beginPath(); c.arc(px, py, Math.max(it.r * k, it.minPx || 0), 0, 2 * Math.PI);
        if (it.fill) { c.fillStyle = it.fill; c.fill(); }
        c.strokeStyle = it.color || "#111827"; c.lineWidth = it.width || 1.5; c.stroke();
      } else if (it.kind === "label") {
        const [px, py] = P(it.at);
        c.fillStyle = it.color || "#111827"; c.font = "600 13px system-ui, sans-serif"; c.textAlign = "left"; c.textBaseline = "bottom";
        c.fillText(it.text, px + 6, py - 4);
      }
    }
    c.restore();
    // Legend.
    c.textAlign = "left"; c.textBaseline = "middle";
    for (const e of legend) {
      const y = 13 + 17 * e.row;
      if (e.title) { c.font = "600 13px system-ui, sans-serif"; c.fillStyle = "#111827"; c.fillText(e.title, e.x, y); continue; }
      c.font = "12px system-ui, sans-serif";
      c.strokeStyle = e.it.color; c.lineWidth = 2.5; c.setLineDash(e.it.dash || []);
      c.beginPath(); c.moveTo(e.x, y); c.lineTo(e.x + 18, y); c.stroke(); c.setLineDash([]);
      c.fillStyle = "#1f2937"; c.fillText(e.it.legend, e.x + 22, y);
    }
  }
}

window.LoomkinCharts = { Chart, Scene, PALETTE, fmtValue, interp, niceTicks, download, addTools, SvgContext, renderSVG, renderPNG, PNG_SCALE };
})();
