// loomkin charts: line charts on <canvas> with axes (quantity and unit), grid, legend,
// hover read-out and draggable points. Written for loomkin; no third-party code.
(() => {
"use strict";

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
  const a = Math.floor(lo / step + 1e-9) * step;
  const b = Math.ceil(hi / step - 1e-9) * step;
  const ticks = [];
  for (let t = a; t <= b + step * 1e-6; t += step) ticks.push(Math.abs(t) < step * 1e-9 ? 0 : t);
  return { lo: a, hi: b, step, ticks };
}

// A number for a label: enough digits for the step, no trailing noise; never "NaN".
function fmtTick(v, step) {
  if (!isFinite(v)) return "–";
  if (Math.abs(v) < Math.abs(step) * 1e-6) v = 0; // no "-0"
  const d = Math.max(0, Math.min(8, -Math.floor(Math.log10(step) + 1e-9)));
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
    this.canvas.addEventListener("pointerleave", () => { if (!this.drag) { this.hoverX = null; this.draw(); } });
    if (window.ResizeObserver) new ResizeObserver(() => this.draw()).observe(this.canvas);
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
    const dpr = window.devicePixelRatio || 1;
    const w = this.canvas.clientWidth || 600, h = this.canvas.clientHeight || 220;
    if (this.canvas.width !== Math.round(w * dpr) || this.canvas.height !== Math.round(h * dpr)) {
      this.canvas.width = Math.round(w * dpr);
      this.canvas.height = Math.round(h * dpr);
    }
    let xlo = Infinity, xhi = -Infinity, ylo = Infinity, yhi = -Infinity;
    for (const s of this.series) {
      for (let i = 0; i < s.x.length; i++) {
        const x = s.x[i], y = s.y[i];
        if (!isFinite(x) || !isFinite(y)) continue;
        if (x < xlo) xlo = x; if (x > xhi) xhi = x;
        if (y < ylo) ylo = y; if (y > yhi) yhi = y;
      }
    }
    for (const p of this.points || []) {
      if (p.y < ylo) ylo = p.y; if (p.y > yhi) yhi = p.y;
    }
    if (this.opts.x.range) [xlo, xhi] = this.opts.x.range;
    if (this.opts.y.range) [ylo, yhi] = this.opts.y.range;
    if (this.opts.y.includeZero) { ylo = Math.min(ylo, 0); yhi = Math.max(yhi, 0); }
    if (!this.opts.y.range && isFinite(ylo) && isFinite(yhi)) {
      // 2 % headroom away from zero, so that no curve runs hidden along the frame.
      const pad = 0.02 * (yhi - ylo);
      if (yhi > 0) yhi += pad;
      if (ylo < 0) ylo -= pad;
    }
    const left = 64, right = 14, bottom = 42;
    const legend = this.legendLayout(left, w - right);
    const top = 30 + 17 * (legend.rows - 1);
    const pw = Math.max(w - left - right, 10), ph = Math.max(h - top - bottom, 10);
    const xt = this.opts.x.range ? { lo: xlo, hi: xhi, ...niceTicksIn(xlo, xhi, pw / 80, this.opts.x.step) } : niceTicks(xlo, xhi, pw / 80);
    const yt = this.opts.y.range ? { lo: ylo, hi: yhi, ...niceTicksIn(ylo, yhi, ph / 40) } : niceTicks(ylo, yhi, ph / 40, this.opts.y.step);
    return { dpr, w, h, left, top, pw, ph, xt, yt, legend };
  }

  toPx(L, x, y) {
    return [L.left + (x - L.xt.lo) / (L.xt.hi - L.xt.lo) * L.pw, L.top + (L.yt.hi - y) / (L.yt.hi - L.yt.lo) * L.ph];
  }

  fromPx(L, px, py) {
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
      const [, py] = this.toPx(L, 0, t);
      c.beginPath(); c.moveTo(L.left, py + 0.5); c.lineTo(L.left + L.pw, py + 0.5); c.stroke();
      c.fillText(fmtTick(t, L.yt.step), L.left - 5, py);
    }
    // Zero line and frame.
    if (L.yt.lo < 0 && L.yt.hi > 0) {
      const [, py] = this.toPx(L, 0, 0);
      c.strokeStyle = "#9ca3af"; c.beginPath(); c.moveTo(L.left, py + 0.5); c.lineTo(L.left + L.pw, py + 0.5); c.stroke();
    }
    c.strokeStyle = "#6b7280"; c.strokeRect(L.left + 0.5, L.top + 0.5, L.pw, L.ph);
    // Axis titles: quantity (unit).
    c.fillStyle = "#111827"; c.textAlign = "center"; c.textBaseline = "bottom";
    c.fillText(axisTitle(this.opts.x.label, this.opts.x.unit), L.left + L.pw / 2, L.h - 2);
    c.save(); c.translate(13, L.top + L.ph / 2); c.rotate(-Math.PI / 2); c.textBaseline = "middle";
    c.fillText(axisTitle(this.opts.y.label, this.opts.y.unit), 0, 0); c.restore();
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
      if (x + wdt > x1 && x > x0) { row++; x = x0; }
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
    const [px, py] = this.eventXY(e);
    const i = this.nearestPoint(px, py);
    if (i < 0) {
      if (this.handlers && this.handlers.onClick && this.L) {
        const [x, y] = this.fromPx(this.L, px, py);
        this.handlers.onClick(x, y, px, py);
      }
      return;
    }
    this.drag = { i };
    try { this.canvas.setPointerCapture(e.pointerId); } catch (_) { /* synthetic pointers */ }
    e.preventDefault();
    this.draw();
  }

  onMove(e) {
    const [px, py] = this.eventXY(e);
    const L = this.L || this.layout();
    const [x, y] = this.fromPx(L, px, py);
    if (this.drag) {
      if (this.handlers && this.handlers.onDrag) this.handlers.onDrag(this.drag.i, x, y);
      this.hoverX = null;
      this.draw();
      return;
    }
    this.canvas.style.cursor = this.nearestPoint(px, py) >= 0 ? "grab" : "crosshair";
    this.hoverX = px >= L.left && px <= L.left + L.pw ? x : null;
    this.draw();
  }

  onUp(e) {
    if (!this.drag) return;
    const i = this.drag.i;
    this.drag = null;
    try { this.canvas.releasePointerCapture(e.pointerId); } catch (_) { /* not captured */ }
    if (this.handlers && this.handlers.onDragEnd) this.handlers.onDragEnd(i);
    this.draw();
  }
}

// Ticks inside a fixed range [lo, hi] (the bounds are kept as given).
function niceTicksIn(lo, hi, count, fixedStep) {
  let step = niceStep(hi - lo, count);
  if (fixedStep) step = fixedStep * Math.max(1, Math.round(step / fixedStep));
  const ticks = [];
  for (let t = Math.ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-6; t += step) ticks.push(Math.abs(t) < step * 1e-9 ? 0 : t);
  return { step, ticks };
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
    if (window.ResizeObserver) new ResizeObserver(() => this.draw()).observe(this.canvas);
  }

  // bounds: [xmin, ymin, xmax, ymax] in data units, kept fixed while the items change.
  setItems(items, bounds) {
    this.items = items;
    if (bounds) this.bounds = bounds;
    this.draw();
  }

  draw() {
    const dpr = window.devicePixelRatio || 1;
    const w = this.canvas.clientWidth || 600, h = this.canvas.clientHeight || 420;
    this.canvas.width = Math.round(w * dpr); this.canvas.height = Math.round(h * dpr);
    const c = this.ctx;
    c.setTransform(dpr, 0, 0, dpr, 0, 0);
    c.clearRect(0, 0, w, h);
    if (!this.bounds) return;
    const [x0, y0, x1, y1] = this.bounds;
    const left = 56, right = 12, top = 28, bottom = 38;
    const pw = w - left - right, ph = h - top - bottom;
    const k = Math.min(pw / (x1 - x0), ph / (y1 - y0));
    const cx = left + pw / 2 - k * (x0 + x1) / 2, cy = top + ph / 2 + k * (y0 + y1) / 2;
    const P = ([x, y]) => [cx + k * x, cy - k * y];
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
    c.textAlign = "left"; c.textBaseline = "middle"; c.font = "12px system-ui, sans-serif";
    let lx = left;
    if (this.opts.title) { c.font = "600 13px system-ui, sans-serif"; c.fillStyle = "#111827"; c.fillText(this.opts.title, lx, 13); lx += c.measureText(this.opts.title).width + 18; c.font = "12px system-ui, sans-serif"; }
    for (const it of this.items) {
      if (!it.legend) continue;
      c.strokeStyle = it.color; c.lineWidth = 2.5; c.setLineDash(it.dash || []);
      c.beginPath(); c.moveTo(lx, 13); c.lineTo(lx + 18, 13); c.stroke(); c.setLineDash([]);
      c.fillStyle = "#1f2937"; c.fillText(it.legend, lx + 22, 13); lx += 22 + c.measureText(it.legend).width + 14;
    }
  }
}

window.LoomkinCharts = { Chart, Scene, PALETTE, fmtValue, interp, niceTicks };
})();
