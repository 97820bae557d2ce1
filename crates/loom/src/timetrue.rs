//! Time-true cams for the loom's frames (`loomkin drive correct`): each frame's shedding law
//! corrected for the main shaft's real speed ω(φ), so that every frame moves in time as the law
//! designed for a constant speed prescribes (loomkin-drive's [`loomkin_drive::timetrue`] holds the
//! mapping and its equations).
//!
//! Every move keeps its middle (the crossing, timed against the beat-up on the shaft) at its
//! angle and is reshaped around it: `ψ(φ) = c + ω̄·(t(φ) − t(c))` for a move centred at `c`.
//! Corrected cams change the frames' reduced inertia and load, hence ω(φ) itself: the correction is
//! repeated against the speed the corrected cams give until the timing moves by less than
//! [`TIMING_TOL_DEG`] (a fixed point; the ripple's effect on itself is second order, so a few
//! rounds suffice). The timing error of a cam is the largest `|ψ(φ) − phase(φ)|` over its moves,
//! `phase` being the angle of the design law the cam's follower is at: `φ` for the design cams
//! (`max_timing_error_deg_before`), the time-true angle they were built for for the corrected ones,
//! measured against the speed those give (`…_after`).
//!
//! A cam sley's cam turns once a pick, so one profile serves every pick of the repeat: it is
//! corrected for the **pick-mean** speed profile ([`SleyCorrection`], docs/drive.md), anchored at
//! the beat-up, and its `…_after` is the worst pick against that mean correction.

use crate::{FrameKin, Loom, LoomError, LoomShaft, Motion, Pattern, Result};
use loomkin_drive::{CorrectedMove, Motor, Span, Table, TimeMap, correct_move, solve, time_excitation};
use loomkin_dynamics::{Follower, Response, Start};
use loomkin_laws::{CycleSpec, LawSpec};
use serde::Serialize;

/// The timing change below which the correction has converged, deg of the shaft.
pub const TIMING_TOL_DEG: f64 = 1e-6;

/// Rounds of correction at most.
pub const MAX_ROUNDS: usize = 12;

/// One corrected move of a frame.
#[derive(Debug, Clone)]
struct FrameMove {
    rising: bool,
    /// The design move's middle, deg (the anchor).
    centre_deg: f64,
    cam: CorrectedMove,
}

/// The frames driven by time-true cams: every move of every frame over the repeat.
#[derive(Debug, Clone)]
pub struct CorrectedFrames {
    period_deg: f64,
    stroke_m: Vec<f64>,
    /// Per frame, its moves in order of start.
    moves: Vec<Vec<FrameMove>>,
    /// Per frame, whether it is up before its first move (frames that never move: their level).
    up0: Vec<bool>,
}

impl CorrectedFrames {
    /// The frames of `motion` with every move corrected for the shaft of `map`.
    pub fn new(motion: &Motion, map: &TimeMap) -> Result<Self> {
        let phi = motion.motion_deg();
        let mut moves = Vec::with_capacity(motion.frames());
        let mut up0 = Vec::with_capacity(motion.frames());
        for i in 0..motion.frames() {
            let design = motion.moves(i);
            up0.push(design.first().map_or(motion.is_up(i, 0), |m| !m.rising));
            let mut out: Vec<FrameMove> = Vec::with_capacity(design.len());
            for m in &design {
                let centre = m.start_deg + phi / 2.0;
                let cam = correct_move(
                    map,
                    motion.law().law(m.rising),
                    m.start_deg.to_radians(),
                    phi.to_radians(),
                    centre.to_radians(),
                )?;
                out.push(FrameMove { rising: m.rising, centre_deg: centre, cam });
            }
            // Consecutive moves (the last against the first one repeat on) must not overlap.
            let period = motion.repeat_deg().to_radians();
            for k in 0..out.len() {
                let a = &out[k].cam;
                let (b_start, wrap) =
                    if k + 1 < out.len() { (out[k + 1].cam.start_rad, 0.0) } else { (out[0].cam.start_rad, period) };
                if out.len() > 1 && a.start_rad + a.length_rad > b_start + wrap + 1e-12 {
                    return Err(LoomError::Infeasible {
                        field: "shedding.motion_deg".into(),
                        reason: format!(
                            "frame {}: corrected for the shaft's speed ripple, two moves overlap: a shorter motion angle leaves room",
                            i + 1
                        ),
                    });
                }
            }
            moves.push(out);
        }
        Ok(Self {
            period_deg: motion.repeat_deg(),
            stroke_m: (0..motion.frames()).map(|i| motion.stroke_m(i)).collect(),
            moves,
            up0,
        })
    }

    /// Frames.
    pub fn frames(&self) -> usize {
        self.moves.len()
    }

    /// Frame `i`'s corrected moves: (start, length) in deg, rising.
    pub fn moves(&self, i: usize) -> Vec<(f64, f64, bool)> {
        self.moves[i].iter().map(|m| (m.cam.start_rad.to_degrees(), m.cam.length_rad.to_degrees(), m.rising)).collect()
    }

    fn level(&self, i: usize, up: bool) -> f64 {
        if up { self.stroke_m[i] / 2.0 } else { -self.stroke_m[i] / 2.0 }
    }

    /// Frame `i` at `theta_deg` (any angle; periodic over the repeat).
    pub fn frame(&self, i: usize, theta_deg: f64) -> FrameKin {
        let moves = &self.moves[i];
        let p = self.period_deg;
        let Some(first) = moves.first() else {
            return FrameKin { y_m: self.level(i, self.up0[i]), ..FrameKin::default() };
        };
        // Wrapped into [first start, first start + repeat).
        let s0 = first.cam.start_rad.to_degrees();
        let th = s0 + (theta_deg - s0).rem_euclid(p);
        let k = moves.partition_point(|m| m.cam.start_rad.to_degrees() <= th).max(1) - 1;
        let m = &moves[k];
        let (start, len) = (m.cam.start_rad.to_degrees(), m.cam.length_rad.to_degrees());
        if th <= start + len {
            let x = (th - start) / len;
            let kin = m.cam.law.eval(x);
            let h = self.stroke_m[i];
            let r = 1.0 / m.cam.length_rad;
            let sign = if m.rising { 1.0 } else { -1.0 };
            return FrameKin {
                y_m: -sign * h / 2.0 + sign * h * kin.s,
                dy: sign * h * kin.v * r,
                d2y: sign * h * kin.a * r * r,
                d3y: sign * h * kin.j * r * r * r,
            };
        }
        FrameKin { y_m: self.level(i, m.rising), ..FrameKin::default() }
    }

    /// Angles in `[0, repeat)` where some frame's corrected motion is not smooth (moves' ends and
    /// the laws' panel joints), deg.
    pub fn joints(&self) -> Vec<f64> {
        let p = self.period_deg;
        let mut out = vec![0.0, p];
        for frame in &self.moves {
            for m in frame {
                let (s, l) = (m.cam.start_rad.to_degrees(), m.cam.length_rad.to_degrees());
                out.push(s.rem_euclid(p));
                out.push((s + l).rem_euclid(p));
                out.extend(m.cam.law.joints().map(|x| (s + x * l).rem_euclid(p)));
            }
        }
        out.sort_by(f64::total_cmp);
        out.dedup_by(|a, b| (*a - *b).abs() <= 1e-9);
        out
    }

    /// Frame `i`'s time-true cam as a machine cycle of the law core (as [`Motion::cycle_spec`]:
    /// period the repeat, strokes in mm, starting at the first move, positions relative to the
    /// frame's place before it), with the loom's speed.
    pub fn cycle_spec(&self, i: usize, speed_rpm: f64) -> CycleSpec {
        let moves: Vec<(f64, f64, bool, &LawSpec)> = self.moves[i]
            .iter()
            .map(|m| (m.cam.start_rad.to_degrees(), m.cam.length_rad.to_degrees(), m.rising, &m.cam.spec))
            .collect();
        crate::motion::machine_cycle(&moves, self.period_deg, self.stroke_m[i] * 1e3, Some(speed_rpm))
    }
}

/// One frame's correction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrameCorrection {
    /// `frame 1` … (front first).
    pub name: String,
    /// Moves of the frame over the repeat (a frame that never moves needs no cam correction).
    pub moves: usize,
    /// The design cam's largest timing error at the real speed, deg of the shaft.
    pub max_timing_error_deg_before: f64,
    /// The time-true cam's, at the speed it gives, deg.
    pub max_timing_error_deg_after: f64,
    /// Residual vibration of the design cam at the real speed: the largest over the frame's
    /// dwells, mm (with a follower given).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual_vibration_mm_before: Option<f64>,
    /// The time-true cam's at its speed, mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual_vibration_mm_after: Option<f64>,
    /// The design cam's at a constant speed (what the time-true cam aims at), mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual_vibration_constant_speed_mm: Option<f64>,
}

/// `loomkin drive correct --json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CorrectionReport {
    /// Picks in the repeat.
    pub picks: usize,
    /// The motor model.
    pub motor: &'static str,
    /// Mean speed of the shaft with the design cams, rpm.
    pub mean_speed_rpm: f64,
    /// Speed ripple with the design cams, %.
    pub speed_ripple_pct: f64,
    /// Speed ripple with the time-true cams, %.
    pub speed_ripple_pct_after: f64,
    /// Largest timing error over the cams (the frames and a cam sley), design cams, deg.
    pub max_timing_error_deg_before: f64,
    /// Largest over the time-true cams, deg (a cam sley's: its worst pick against the pick-mean
    /// correction).
    pub max_timing_error_deg_after: f64,
    /// Rounds of correction against the speed the corrected cams give.
    pub rounds: usize,
    /// The frames corrected (a cam sley is under `sley`); mechanisms on the shaft but not cams
    /// (a four-bar sley) are named in `not_corrected`.
    pub frames: Vec<FrameCorrection>,
    /// The cam sley's time-true cam, when the loom has one (one profile for every pick: corrected
    /// for the pick-mean speed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sley: Option<SleyTiming>,
    /// Mechanisms that are not cam-driven, hence not corrected.
    pub not_corrected: Vec<String>,
}

/// `drive correct --json`'s `sley`: the cam sley's timing before and after.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SleyTiming {
    /// `sley`.
    pub name: String,
    /// Moving segments of its cam law (a turn).
    pub moves: usize,
    /// The design cam's largest timing error at the real speed, over every pick, deg of the shaft.
    pub max_timing_error_deg_before: f64,
    /// The time-true cam's: the worst pick against the pick-mean correction, deg.
    pub max_timing_error_deg_after: f64,
    /// The design cam's largest pressure angle over its cams, deg.
    pub max_pressure_angle_deg_before: f64,
    /// The time-true cam's on the same follower and cam size (the prime circle the design was
    /// made with), deg ([`loomkin_drive::CamSley::cam_for`]).
    pub max_pressure_angle_deg_after: f64,
    /// The limit the cam was designed for, deg ([`loomkin_drive::CamSley::pressure_limit_deg`]).
    pub pressure_angle_limit_deg: f64,
    /// The design cam's least radius of curvature where a pitch curve is convex, mm (below the
    /// roller's radius the cam is undercut).
    pub min_curvature_radius_mm_before: f64,
    /// The time-true cam's, mm.
    pub min_curvature_radius_mm_after: f64,
    /// The follower's roller radius, mm.
    pub roller_radius_mm: f64,
    /// Where the time-true cam is undercut, deg of its cycle (left out when it is not).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub undercut_at_deg_after: Option<f64>,
}

impl SleyTiming {
    /// One line for the user when the time-true cam asks more of the follower it was designed for
    /// than that follower takes: a pressure angle past the limit, or an undercut.
    pub fn warning(&self) -> Option<String> {
        let mut parts = Vec::new();
        if self.max_pressure_angle_deg_after > self.pressure_angle_limit_deg * (1.0 + 1e-9) {
            parts.push(format!(
                "needs a pressure angle of {:.3}° on the follower it was designed for, past its limit of {}° \
                 (the design cam: {:.3}°): a larger cam (sley.prime_radius_mm or a smaller sley.max_pressure_deg)",
                self.max_pressure_angle_deg_after,
                loomkin_units::compact(self.pressure_angle_limit_deg),
                self.max_pressure_angle_deg_before
            ));
        }
        if let Some(at) = self.undercut_at_deg_after {
            parts.push(format!(
                "is undercut at {:.3}° of its cycle (least radius of curvature {:.3} mm, roller {} mm)",
                at,
                self.min_curvature_radius_mm_after,
                loomkin_units::compact(self.roller_radius_mm)
            ));
        }
        (!parts.is_empty()).then(|| format!("{}: the time-true cam {}", self.name, parts.join("; and it ")))
    }
}

/// The cam sley's cam corrected for the pick-mean speed ([`SleyCorrection::new`]).
#[derive(Debug, Clone)]
pub struct SleyCorrection {
    /// The corrected cam law: the rocking shaft's swing in the cycle's own angles (as the loom
    /// file's `[sley.cycle]`).
    pub cycle: CycleSpec,
    /// The pick-mean time map over one turn (main-shaft angles) it was corrected for.
    pub mean_map: TimeMap,
    /// The beat-up, rad of the main shaft: the angle the correction keeps.
    pub anchor_rad: f64,
    /// Before and after.
    pub timing: SleyTiming,
}

/// Nodes of the pick-mean time map over a turn.
const MEAN_MAP_NODES: usize = 3600;

impl SleyCorrection {
    /// The pick-mean time map of `map` (a repeat of `picks` turns): at each node of a turn the
    /// mean over the picks of the time from the pick's start, of `dt/dφ` and of `d²t/dφ²`.
    pub fn mean_map(map: &TimeMap, picks: usize) -> TimeMap {
        let tau = std::f64::consts::TAU;
        let n = MEAN_MAP_NODES;
        let count = picks.max(1) as f64;
        let (mut phi, mut t, mut w, mut dw) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for k in 0..=n {
            let x = if k == n { tau } else { tau * k as f64 / n as f64 };
            let (mut st, mut sd, mut sa) = (0.0, 0.0, 0.0);
            for p in 0..picks.max(1) {
                let base = tau * p as f64;
                let [tt, d, a] = map.time(base + x);
                st += tt - map.time(base)[0];
                sd += d;
                sa += a;
            }
            let (d, a) = (sd / count, sa / count);
            phi.push(x);
            t.push(st / count);
            w.push(1.0 / d);
            dw.push(-a / (d * d));
        }
        TimeMap::new(phi, t, w, dw)
    }

    /// The cam of `sley` corrected for the pick-mean of `map` (the shaft over a repeat of `picks`
    /// picks): each moving segment of its law re-timed by [`correct_move`] about the beat-up, so
    /// that on the mean pick the reed moves in time as the law prescribes at the mean speed. The
    /// timing errors: `before`, the design cam against `design` (the speed it runs at), every pick;
    /// `after`, the corrected cam against `map`, every pick, each pick's time-true angle less the
    /// mean pick's.
    pub fn new(sley: &loomkin_drive::CamSley, design: &TimeMap, map: &TimeMap, picks: usize) -> Result<Self> {
        let tau = std::f64::consts::TAU;
        let mean = Self::mean_map(map, picks);
        let spec = &sley.table().cycle;
        let cycle = loomkin_laws::Cycle::new(spec).map_err(|e| LoomError::field("sley.cycle", e.to_string()))?;
        let shift = sley.phase_deg().to_radians();
        let anchor = sley.front_dead_centre_rad();
        // Each moving segment in the main shaft's angles, design and corrected.
        let mut segment = Vec::with_capacity(spec.segment.len());
        let mut moving: Vec<((f64, f64), (f64, f64))> = Vec::new();
        let mut first_start = None;
        for (seg, given) in cycle.segments.iter().zip(&spec.segment) {
            let (a, l) = (seg.start_rad + shift, seg.length_rad);
            let (start, length, law) = match &seg.law {
                Some((_, law)) => {
                    let c = correct_move(&mean, law, a, l, anchor)?;
                    moving.push(((a, a + l), (c.start_rad, c.start_rad + c.length_rad)));
                    (c.start_rad, c.length_rad, Some(c.spec))
                }
                None => {
                    let b = mean.time_true_inverse(a, anchor);
                    (b, mean.time_true_inverse(a + l, anchor) - b, None)
                }
            };
            first_start.get_or_insert(start - shift);
            let mut out = match &law {
                Some(law) => loomkin_laws::SegmentSpec::moving(given.kind, length.to_degrees(), law),
                None => loomkin_laws::SegmentSpec::dwell(length.to_degrees()),
            };
            out.stroke = given.stroke;
            segment.push(out);
        }
        if let (Some(first), Some(s0)) = (segment.first_mut(), first_start) {
            first.from_deg = Some(s0.to_degrees());
        }
        let corrected = CycleSpec { segment, ..spec.clone() };
        // Timing errors, every pick: the design cam follows φ, the corrected one the mean pick's ψ̄(φ).
        let mut before: f64 = 0.0;
        let mut after: f64 = 0.0;
        for p in 0..picks.max(1) {
            let base = tau * p as f64;
            for &((a, b), (ca, cb)) in &moving {
                before = before.max(max_abs(a, b, |x| design.time_true(base + x, base + anchor)[0] - base - x));
                after = after.max(max_abs(ca, cb, |x| {
                    map.time_true(base + x, base + anchor)[0] - base - mean.time_true(x, anchor)[0]
                }));
            }
        }
        // The time-true law on the follower and cam the design was made for.
        let cam_after = sley.cam_for(&corrected).map_err(|e| LoomError::field("sley.cycle", e.to_string()))?;
        let cam_before = sley.cam();
        let timing = SleyTiming {
            name: "sley".into(),
            moves: moving.len(),
            max_timing_error_deg_before: before.to_degrees(),
            max_timing_error_deg_after: after.to_degrees(),
            max_pressure_angle_deg_before: cam_before.max_pressure_angle().0,
            max_pressure_angle_deg_after: cam_after.max_pressure_angle().0,
            pressure_angle_limit_deg: sley.pressure_limit_deg(),
            min_curvature_radius_mm_before: cam_before.min_convex_radius_pitch().0,
            min_curvature_radius_mm_after: cam_after.min_convex_radius_pitch().0,
            roller_radius_mm: sley.table().roller_radius_mm,
            undercut_at_deg_after: cam_after.undercut_at_deg(),
        };
        Ok(Self { cycle: corrected, mean_map: mean, anchor_rad: anchor, timing })
    }
}

/// The correction of a loom's frames and its report.
#[derive(Debug, Clone)]
pub struct Correction {
    /// The time-true frames.
    pub frames: CorrectedFrames,
    /// The report.
    pub report: CorrectionReport,
    /// The shaft's time map with the design cams.
    pub design_map: TimeMap,
    /// The shaft's time map with the time-true cams.
    pub corrected_map: TimeMap,
    /// The cam sley's time-true cam, when the loom has a cam sley.
    pub sley: Option<SleyCorrection>,
}

impl Correction {
    /// `loomkin drive correct -o DIR`'s cycle files: `(file name, text)` for every frame that moves
    /// (`frame-01.toml` …), each a [`CorrectedFrames::cycle_spec`] at the mean speed corrected for,
    /// under a comment naming `title` (the loom), the frame and the motor.
    pub fn cycle_files(&self, title: &str) -> Result<Vec<(String, String)>> {
        let speed_rpm = loomkin_units::rpm_from_rad_per_s(self.corrected_map.mean_speed_rad_s());
        let mut out = Vec::new();
        for (i, f) in self.report.frames.iter().enumerate() {
            if f.moves == 0 {
                continue;
            }
            let spec = self.frames.cycle_spec(i, speed_rpm);
            let text = format!(
                "# {title}, {}: time-true cam (loomkin drive correct), {} motor; positions from the frame's place before the first move\n{}",
                f.name,
                self.report.motor,
                spec.to_toml()?
            );
            out.push((format!("frame-{:02}.toml", i + 1), text));
        }
        if let Some(sc) = &self.sley {
            let spec = CycleSpec { speed_rpm: Some(speed_rpm), ..sc.cycle.clone() };
            let text = format!(
                "# {title}, sley: time-true cam (loomkin drive correct) for the pick-mean speed, {} motor; the rocking shaft's swing, deg, in the cycle's angles of [sley.cycle]\n{}",
                self.report.motor,
                spec.to_toml()?
            );
            out.push(("sley.toml".into(), text));
        }
        Ok(out)
    }
}

/// The largest of `|f|` over `[a, b]`: a grid of about 0.25°, every local maximum refined
/// ([`loomkin_numeric::scan_max`]).
fn max_abs(a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let n = ((b - a) / 0.25_f64.to_radians()).ceil().max(2.0) as usize;
    loomkin_numeric::scan_max(a, b, n, |x| f(x).abs()).value
}

/// The frames' residual vibrations (mm) on the shaft of `map`, each frame's input given by `kin`.
fn residuals(
    frames: usize,
    spans: impl Fn(usize) -> Vec<Span>,
    kin: impl Fn(usize, f64) -> FrameKin,
    stroke: impl Fn(usize) -> f64,
    map: &TimeMap,
    follower: &Follower,
) -> Result<Vec<Option<f64>>> {
    (0..frames)
        .map(|i| {
            let sp = spans(i);
            if !sp.iter().any(|s| s.moving) {
                return Ok(None);
            }
            let exc = time_excitation(
                map,
                &sp,
                |_, phi| {
                    let k = kin(i, phi.to_degrees());
                    [k.y_m, k.dy, k.d2y]
                },
                stroke(i),
            );
            let r = Response::from_excitation(exc, follower, Start::Steady, 1)
                .map_err(|e| LoomError::field("natural_hz", e.to_string()))?;
            Ok(Some(r.summary().residual_amplitude_si * 1e3))
        })
        .collect()
}

/// The spans (moving, standing) of a frame over one repeat from its moves `(start, length)` in deg.
fn spans_of(moves: &[(f64, f64)], period_deg: f64) -> Vec<Span> {
    let mut out = Vec::new();
    let Some(first) = moves.first() else { return out };
    let end = first.0 + period_deg;
    for (k, (s, l)) in moves.iter().enumerate() {
        out.push(Span { start_rad: s.to_radians(), end_rad: (s + l).to_radians(), moving: true });
        let next = moves.get(k + 1).map_or(end, |m| m.0);
        if next > s + l + 1e-9 {
            out.push(Span { start_rad: (s + l).to_radians(), end_rad: next.to_radians(), moving: false });
        }
    }
    out
}

/// The time-true cams of `loom`'s frames weaving `pattern` on the shaft turned by `motor` with
/// `flywheel_kg_m2` added, on the ripple grid of `step_deg`; with a follower (the frames' elastic
/// model), the residual vibration of each before and after.
pub fn correct(
    loom: &Loom,
    motion: &Motion,
    pattern: &Pattern,
    motor: &Motor,
    flywheel_kg_m2: f64,
    step_deg: f64,
    follower: Option<&Follower>,
) -> Result<Correction> {
    let shaft = LoomShaft::new(loom, motion, pattern);
    let table = Table::new(&shaft, step_deg)?;
    let sol = solve(&table, motor, flywheel_kg_m2)?;
    let design_map = sol.time_map();
    let phi = motion.motion_deg();
    let n = motion.frames();
    // Before: the design cams' timing against the speed they give.
    let before: Vec<f64> = (0..n)
        .map(|i| {
            motion
                .moves(i)
                .iter()
                .map(|m| {
                    let c = (m.start_deg + phi / 2.0).to_radians();
                    max_abs(m.start_deg.to_radians(), (m.start_deg + phi).to_radians(), |x| {
                        design_map.time_true(x, c)[0] - x
                    })
                    .to_degrees()
                })
                .fold(0.0, f64::max)
        })
        .collect();
    // The fixed point: cams corrected for the speed the previous cams give.
    let mut map = design_map.clone();
    let mut rounds = 0;
    let (frames, after, corrected_map, ripple_after) = loop {
        rounds += 1;
        let frames = CorrectedFrames::new(motion, &map)?;
        let (next, ripple) = {
            let shaft = LoomShaft::new(loom, motion, pattern).with_corrected(&frames);
            let table = Table::new(&shaft, step_deg)?;
            let sol = solve(&table, motor, flywheel_kg_m2)?;
            (sol.time_map(), sol.report.speed_ripple_pct)
        };
        let after: Vec<f64> = (0..n)
            .map(|i| {
                frames.moves[i]
                    .iter()
                    .map(|m| {
                        let c = m.centre_deg.to_radians();
                        let (a, b) = (m.cam.start_rad, m.cam.start_rad + m.cam.length_rad);
                        max_abs(a, b, |x| next.time_true(x, c)[0] - map.time_true(x, c)[0]).to_degrees()
                    })
                    .fold(0.0, f64::max)
            })
            .collect();
        let worst = after.iter().copied().fold(0.0, f64::max);
        if worst <= TIMING_TOL_DEG || rounds >= MAX_ROUNDS {
            break (frames, after, next, ripple);
        }
        map = next;
    };
    let mut residual = [vec![None; n], vec![None; n], vec![None; n]];
    if let Some(f) = follower {
        let p = motion.repeat_deg();
        let design_spans = |i: usize| {
            let m: Vec<(f64, f64)> = motion.moves(i).iter().map(|m| (m.start_deg, phi)).collect();
            spans_of(&m, p)
        };
        let stroke = |i: usize| motion.stroke_m(i);
        residual[0] = residuals(n, design_spans, |i, th| motion.frame(i, th), stroke, &design_map, f)?;
        let corr_spans = |i: usize| {
            let m: Vec<(f64, f64)> = frames.moves(i).iter().map(|(s, l, _)| (*s, *l)).collect();
            spans_of(&m, p)
        };
        residual[1] = residuals(n, corr_spans, |i, th| frames.frame(i, th), stroke, &corrected_map, f)?;
        // The design cam at a constant speed: a uniform map.
        let w = design_map.mean_speed_rad_s();
        let period = design_map.period_rad();
        let uniform = TimeMap::new(vec![0.0, period], vec![0.0, period / w], vec![w, w], vec![0.0, 0.0]);
        residual[2] = residuals(n, design_spans, |i, th| motion.frame(i, th), stroke, &uniform, f)?;
    }
    let frame_reports: Vec<FrameCorrection> = (0..n)
        .map(|i| FrameCorrection {
            name: format!("frame {}", i + 1),
            moves: frames.moves[i].len(),
            max_timing_error_deg_before: before[i],
            max_timing_error_deg_after: after[i],
            residual_vibration_mm_before: residual[0][i],
            residual_vibration_mm_after: residual[1][i],
            residual_vibration_constant_speed_mm: residual[2][i],
        })
        .collect();
    let mut not_corrected = Vec::new();
    let sley = match &loom.sley {
        Some(loomkin_drive::Sley::FourBar(_)) => {
            not_corrected.push("sley (a four-bar linkage, not a cam)".to_string());
            None
        }
        // Against the speed the time-true frames give; the corrected sley cam is not fed back
        // into ω (docs/drive.md).
        Some(loomkin_drive::Sley::Cam(cam)) => {
            Some(SleyCorrection::new(cam, &design_map, &corrected_map, motion.picks())?)
        }
        None => None,
    };
    let sley_before = sley.as_ref().map_or(0.0, |s| s.timing.max_timing_error_deg_before);
    let sley_after = sley.as_ref().map_or(0.0, |s| s.timing.max_timing_error_deg_after);
    let report = CorrectionReport {
        picks: motion.picks(),
        motor: motor.name(),
        mean_speed_rpm: sol.report.mean_speed_rpm,
        speed_ripple_pct: sol.report.speed_ripple_pct,
        speed_ripple_pct_after: ripple_after,
        max_timing_error_deg_before: before.iter().copied().fold(sley_before, f64::max),
        max_timing_error_deg_after: after.iter().copied().fold(sley_after, f64::max),
        rounds,
        frames: frame_reports,
        sley: sley.as_ref().map(|s| s.timing.clone()),
        not_corrected,
    };
    Ok(Correction { frames, report, design_map, corrected_map, sley })
}
