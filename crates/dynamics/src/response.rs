//! The response of a single-mass follower to a cycle, and what a designer reads from it.

use crate::Result;
use crate::excitation::Excitation;
use crate::follower::Follower;
use crate::oscillator::free_roots;
use crate::peaks::{Extremes, grid_size};
use crate::trajectory::{Channel, Solved, Start, trajectory};
use loomkin_laws::Cycle;
use loomkin_numeric::{extremes, extremes_of};
use loomkin_units::{Cost, Field, Range, ShaftSpeed};
use serde::Serialize;

/// VDI 2149 Blatt 1: a rigid-body model is acceptable only when `f_n ≥ 10·f_shaft`.
pub const VDI_2149_MIN_RATIO: f64 = 10.0;

/// The exact response of a follower to a cycle at a speed.
#[derive(Debug, Clone)]
pub struct Response {
    /// The excitation (the cycle in time).
    pub exc: Excitation,
    /// The follower.
    pub follower: Follower,
    /// The channel of the error `y = x − s`.
    pub channel: Channel,
    /// The solved pieces, in time order.
    pub pieces: Vec<Solved>,
}

/// A place and a value: `value` at main-shaft angle `angle_deg` (counted from the cycle's start, across cycles).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Located {
    /// The value (SI unless named otherwise).
    pub value: f64,
    /// Where (deg of main-shaft rotation from the start of the computation, plus the cycle's start angle).
    pub angle_deg: f64,
}

/// Residual vibration at the start of one dwell.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DwellResidual {
    /// Index of the cycle segment.
    pub segment: usize,
    /// Cycle number (0-based).
    pub cycle: usize,
    /// Angle at the start of the dwell (deg).
    pub angle_deg: f64,
    /// `A = √(δ² + ((δ' + ζω_nδ)/ω_d)²)` (m or rad), δ measured from the dwell's static equilibrium.
    pub amplitude_si: f64,
}

/// The figures a designer reads.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Residual vibration of every dwell, in time order.
    pub dwells: Vec<DwellResidual>,
    /// The largest residual amplitude over the dwells (SI; 0 when the cycle has no dwell).
    pub residual_amplitude_si: f64,
    /// The same in % of the largest stroke.
    pub residual_pct_of_stroke: f64,
    /// Largest |x − s| (SI) and where.
    pub peak_dynamic_error: Located,
    /// Largest |x''| (SI/s²) and where.
    pub peak_acceleration: Located,
    /// Largest |s''| of the input, for comparison (SI/s²).
    pub peak_input_acceleration: Located,
    /// Largest train force |F| = |k(s − x) + c(s' − x')| (N), when a mass is given.
    pub peak_force_n: Option<Located>,
    /// Smallest train (contact) force (N), when a mass is given.
    pub min_contact_force_n: Option<Located>,
    /// True when a force-closed follower would lose contact (min contact force < 0).
    pub loses_contact: bool,
    /// VDI 2149 rigidity ratio `f_n / f_shaft`.
    pub rigidity_ratio: f64,
    /// True when the rigidity ratio is below [`VDI_2149_MIN_RATIO`].
    pub rigidity_warning: bool,
}

impl Response {
    /// `cycles`: cycles computed from rest, 1 … 10⁴ (a response holds its pieces, some per segment
    /// and cycle); 1.
    pub const CYCLES: Field = Field::count(
        "cycles",
        Range::closed(1.0, 1e4, ""),
        "Cycles computed from rest at 0° of the cycle: 1 … 10⁴ (the response holds every cycle's pieces); \
         1 when left out.",
    )
    .with_default(1.0);
    /// `points`: samples per cycle of a response, 2 … 10⁶; 721 (every half degree of a turn).
    pub const POINTS: Field = Field::count(
        "points",
        Range::closed(2.0, 1e6, ""),
        "Samples per cycle: 2 … 10⁶; 721 (every half degree of a turn) when left out.",
    )
    .with_default(721.0);

    /// Bytes a plot of a response holds per sample at its peak: the samples, the drawn columns,
    /// their pixel runs and the figure's text (SVG) or raster (PNG). Measured with `dyn response
    /// examples/heald-frame-cycle.toml --natural-hz 80 -o r.{svg,png}` at 500 and 1500 cycles of
    /// 721 points (the peak RSS's growth over the 720,000 samples between: 450 B for SVG, 428 B for
    /// PNG).
    pub const PLOT_BYTES_PER_SAMPLE: f64 = 450.0;
    /// CPU seconds a plot takes per sample (user time, measured as
    /// [`Response::PLOT_BYTES_PER_SAMPLE`]): 2.5 µs written as SVG, 10 µs as PNG (rasterised).
    pub const PLOT_CPU_S_PER_SAMPLE: [f64; 2] = [2.5e-6, 10e-6];
    /// Bytes a CSV table holds per sample (the samples are computed, then written: 119 B measured
    /// as [`Response::PLOT_BYTES_PER_SAMPLE`]).
    pub const CSV_BYTES_PER_SAMPLE: f64 = 120.0;
    /// CPU seconds per CSV row (0.69 µs measured as [`Response::CSV_BYTES_PER_SAMPLE`]).
    pub const CSV_CPU_S_PER_SAMPLE: f64 = 0.7e-6;

    /// The number of samples [`Response::samples`] gives for `points` per cycle over `cycles`
    /// cycles: `(points − 1)·cycles + 1` (as a float: it can pass `usize` at the ranges' ends).
    pub fn sample_count(points: usize, cycles: usize) -> f64 {
        (points.max(2) - 1) as f64 * cycles as f64 + 1.0
    }

    /// What a CSV table of `samples` samples needs ([`Response::CSV_BYTES_PER_SAMPLE`]).
    pub fn csv_cost(samples: f64) -> Cost {
        Cost::cpu_items(samples, Self::CSV_BYTES_PER_SAMPLE, Self::CSV_CPU_S_PER_SAMPLE)
    }

    /// What a plot of `samples` samples needs, rasterised (`png`) or not
    /// ([`Response::PLOT_BYTES_PER_SAMPLE`]).
    pub fn plot_cost(samples: f64, png: bool) -> Cost {
        Cost::cpu_items(samples, Self::PLOT_BYTES_PER_SAMPLE, Self::PLOT_CPU_S_PER_SAMPLE[usize::from(png)])
    }

    /// The response of `follower` to `cycle` at `speed` over `cycles` cycles (from rest or steady).
    pub fn new(cycle: &Cycle, speed: ShaftSpeed, follower: &Follower, start: Start, cycles: usize) -> Result<Self> {
        Self::from_excitation(Excitation::from_cycle(cycle, speed), follower, start, cycles)
    }

    /// The response to a prepared excitation.
    pub fn from_excitation(exc: Excitation, follower: &Follower, start: Start, cycles: usize) -> Result<Self> {
        let channel = follower.channel();
        let pieces = trajectory(&exc, &channel, start, cycles)?;
        Ok(Self { exc, follower: *follower, channel, pieces })
    }

    /// Angle (deg) of a global time `t` (s) from the start of the computation.
    pub fn angle_deg(&self, t: f64) -> f64 {
        self.exc.angle_deg(t)
    }

    /// Total computed time (s).
    pub fn duration_s(&self) -> f64 {
        self.pieces.last().map_or(0.0, |p| p.t0 + p.sol.duration())
    }

    /// `(s, s', s'', y, y', y'')` at global time `t` (clamped into the computed span).
    pub fn state(&self, t: f64) -> [f64; 6] {
        let t = t.clamp(0.0, self.duration_s());
        let i = self.pieces.partition_point(|p| p.t0 <= t).saturating_sub(1);
        let p = &self.pieces[i];
        let tl = (t - p.t0).clamp(0.0, p.sol.duration());
        let s = self.exc.pieces[p.piece].derivs(tl);
        let y = p.sol.derivs(tl);
        [s[0], s[1], s[2], y[0], y[1], y[2]]
    }

    /// `n ≥ 2` samples per cycle (both ends of the computation included):
    /// `(angle_deg, s, x, x − s, x'')` in SI.
    pub fn samples(&self, n_per_cycle: usize) -> Vec<[f64; 5]> {
        let cycles = self.pieces.last().map_or(1, |p| p.cycle + 1);
        let n = (n_per_cycle.max(2) - 1) * cycles + 1;
        let total = self.duration_s();
        (0..n)
            .map(|i| {
                let t = if i + 1 == n { total } else { total * i as f64 / (n - 1) as f64 };
                let st = self.state(t);
                [self.angle_deg(t), st[0], st[0] + st[3], st[3], st[2] + st[5]]
            })
            .collect()
    }

    /// Residual amplitude at the start of every dwell, including the dwell at the start of the next cycle
    /// that the last motion runs into (when the cycle starts with a dwell).
    pub fn dwell_residuals(&self) -> Vec<DwellResidual> {
        let osc = &self.channel.osc;
        let mut out = Vec::new();
        for (k, p) in self.pieces.iter().enumerate() {
            let ep = &self.exc.pieces[p.piece];
            // A dwell made of one piece; a dwell continuing the previous piece's dwell is the same dwell.
            let continues = k > 0 && self.exc.pieces[self.pieces[k - 1].piece].dwell;
            if !ep.dwell || continues {
                continue;
            }
            let (y, v) = p.sol.state(0.0);
            let d = y - self.channel.rest(ep.poly[0]);
            out.push(DwellResidual {
                segment: ep.segment,
                cycle: p.cycle,
                angle_deg: self.angle_deg(p.t0),
                amplitude_si: osc.amplitude(d, v),
            });
        }
        // The dwell the last motion runs into: the first piece of the next cycle.
        if let (Some(first), Some(last)) = (self.exc.pieces.first(), self.pieces.last())
            && first.dwell
            && !self.exc.pieces[last.piece].dwell
        {
            let (y, v) = last.sol.end();
            // Across the joint x and x' are continuous (see `trajectory`).
            let (ds, dv) = self.exc.joint_jump(last.piece);
            let (y, v) = (y + ds, v + dv);
            let d = y - self.channel.rest(first.poly[0]);
            let t = last.t0 + last.sol.duration();
            out.push(DwellResidual {
                segment: first.segment,
                cycle: last.cycle + 1,
                angle_deg: self.angle_deg(t),
                amplitude_si: osc.amplitude(d, v),
            });
        }
        out
    }

    /// Every figure of the [`Summary`], peaks located exactly (roots of the derivative on the closed form).
    pub fn summary(&self) -> Summary {
        self.summary_of(true)
    }

    /// Extremes of error, acceleration (when `accel`), input acceleration (when `accel`) and train force.
    fn extremes(&self, accel: bool) -> [Extremes; 4] {
        let osc = self.channel.osc;
        let (zw, w2) = (2.0 * osc.zeta() * osc.omega_n(), osc.omega_n() * osc.omega_n());
        let mut out = [Extremes::EMPTY; 4];
        let train = self.follower.train();
        for p in &self.pieces {
            let ep = &self.exc.pieces[p.piece];
            let dur = p.sol.duration();
            if let Some((y_eq, a, b)) = p.sol.constant_plus_free() {
                // Constant forcing (a dwell, or a stretch of constant input acceleration such as the
                // middle of a modified trapezoid): a constant plus a free vibration, whose extremes
                // are at the ends and at the first two roots of its derivative (the envelope only
                // decays), in closed form. The input's acceleration s'' is then constant and adds to
                // the follower's: x'' = s'' + y''.
                let s2 = ep.derivs(0.0)[2];
                let z2 = -zw * b - w2 * a;
                let z3 = -zw * z2 - w2 * b;
                let mut take = |k: usize, c: f64, u0: f64, u1: f64| {
                    let mut e = Extremes::EMPTY;
                    for t in [0.0, dur].into_iter().chain(free_roots(&osc, u1, -zw * u1 - w2 * u0, dur, 2)) {
                        e.take(c + osc.free(u0, u1, t).0, t);
                    }
                    out[k].merge(&e, p.t0);
                };
                take(0, y_eq, a, b);
                if accel {
                    take(1, s2, z2, z3);
                    take(2, s2, 0.0, 0.0);
                }
                if let Some((k, c)) = train {
                    take(3, -k * y_eq, -(k * a + c * b), -(k * b + c * z2));
                }
                continue;
            }
            let w_sine = ep.accel_sine.map_or(0.0, |h| h.omega);
            let n = grid_size(dur, osc.omega_d().max(w_sine));
            let (k, c) = train.unwrap_or((0.0, 0.0));
            let [e_err, e_force] = extremes_of(0.0, dur, n, |t| {
                let y = p.sol.derivs_n::<4>(t);
                [[y[0], y[1], y[2]], [-k * y[0] - c * y[1], -k * y[1] - c * y[2], -k * y[2] - c * y[3]]]
            });
            out[0].merge(&e_err, p.t0);
            if train.is_some() {
                out[3].merge(&e_force, p.t0);
            }
            if accel {
                out[1].merge(
                    &extremes(0.0, dur, n, |t| {
                        let (y, s) = (p.sol.derivs(t), ep.derivs(t));
                        [y[2] + s[2], y[3] + s[3], y[4] + s[4]]
                    }),
                    p.t0,
                );
                out[2].merge(
                    &extremes(0.0, dur, grid_size(dur, w_sine), |t| {
                        let s = ep.derivs(t);
                        [s[2], s[3], s[4]]
                    }),
                    p.t0,
                );
            }
        }
        out
    }

    /// The summary; acceleration peaks only when `accel` (a sweep skips them).
    pub(crate) fn summary_of(&self, accel: bool) -> Summary {
        let dwells = self.dwell_residuals();
        let residual = dwells.iter().map(|d| d.amplitude_si).fold(0.0, f64::max);
        let train = self.follower.train();
        let [err, acc, inp, force] = self.extremes(accel);
        let loc = |(v, t): (f64, f64)| Located { value: v, angle_deg: self.angle_deg(t) };
        let ratio = self.follower.natural_hz() / (self.exc.speed_rpm / 60.0);
        let min_force = train.map(|_| loc(force.min));
        Summary {
            dwells,
            residual_amplitude_si: residual,
            residual_pct_of_stroke: 100.0 * residual / self.exc.stroke_si,
            peak_dynamic_error: loc(err.peak_abs()),
            peak_acceleration: loc(if acc.is_empty() { (0.0, 0.0) } else { acc.peak_abs() }),
            peak_input_acceleration: loc(if inp.is_empty() { (0.0, 0.0) } else { inp.peak_abs() }),
            peak_force_n: train.map(|_| loc(force.peak_abs())),
            loses_contact: min_force.is_some_and(|f| f.value < 0.0),
            min_contact_force_n: min_force,
            rigidity_ratio: ratio,
            rigidity_warning: ratio < VDI_2149_MIN_RATIO,
        }
    }
}

#[cfg(test)]
mod peak_tests {
    use super::*;

    /// The located peaks of |x''| and |s''| bound a dense sampling of the same closed form from
    /// outside and are reached by it. The heald example's return is a modified trapezoid whose
    /// constant-acceleration middle is a piece of constant forcing: its x'' = s'' + y'' (a
    /// regression: the input's s'' was left out there, and the peak, 1009 m/s² at 330°, was missed).
    #[test]
    fn located_acceleration_peaks_bound_the_samples() {
        let text =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml"))
                .unwrap();
        let cycle = Cycle::from_toml(&text).unwrap();
        for (rpm, fn_hz, zeta, start) in
            [(600.0, 54.0, 0.05, Start::Rest), (300.0, 30.0, 0.0, Start::Rest), (450.0, 80.0, 0.1, Start::Steady)]
        {
            let f = Follower::new(fn_hz, zeta).unwrap();
            let r = Response::new(&cycle, ShaftSpeed::from_rpm(rpm).unwrap(), &f, start, 1).unwrap();
            let s = r.summary();
            let n = 40_001;
            let total = r.duration_s();
            let (mut xa, mut sa) = (0.0f64, 0.0f64);
            for i in 0..n {
                let st = r.state(total * i as f64 / (n - 1) as f64);
                xa = xa.max((st[2] + st[5]).abs());
                sa = sa.max(st[2].abs());
            }
            for (what, peak, sampled) in
                [("x''", s.peak_acceleration.value, xa), ("s''", s.peak_input_acceleration.value, sa)]
            {
                assert!(peak >= sampled * (1.0 - 1e-12), "{rpm} rpm: {what} peak {peak} below the samples' {sampled}");
                assert!(peak - sampled < 1e-4 * peak, "{rpm} rpm: {what} peak {peak} vs samples {sampled}");
            }
        }
    }
}
