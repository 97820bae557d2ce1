//! The check of a servo axis moving a cycle: peak and RMS torque, peak speed, the torque–speed
//! operating points against the motor envelope, the inertia ratio, pass or fail with margins.

use crate::{Axis, Result};
use loomkin_cams::profile::Jet;
use loomkin_laws::{Cycle, Segment};
use serde::Serialize;
use std::f64::consts::PI;

/// One check: a value against its limit; the margin is `(limit − value)/limit` (negative: fails).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// `peak_torque`, `rms_torque`, `peak_speed`, `torque_speed_envelope` or `inertia_ratio`.
    pub name: &'static str,
    /// The value over the cycle.
    pub value: f64,
    /// The limit.
    pub limit: f64,
    /// Unit of value and limit (`N·m`, `rpm`, or empty).
    pub unit: &'static str,
    /// `(limit − value)/limit`.
    pub margin: f64,
    /// `value ≤ limit`.
    pub pass: bool,
}

impl Check {
    fn new(name: &'static str, value: f64, limit: f64, unit: &'static str) -> Self {
        Self { name, value, limit, unit, margin: (limit - value) / limit, pass: value <= limit }
    }
}

/// The result of [`check_axis`]. Extremes are located exactly on the closed form (roots of the
/// derivative bracketed per law segment and refined), not sampled.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AxisReport {
    /// Main-shaft speed (rpm).
    pub speed_rpm: f64,
    /// Duration of one cycle (s).
    pub cycle_time_s: f64,
    /// Largest |motor torque| (N·m).
    pub peak_torque_nm: f64,
    /// Main-shaft angle of the peak torque (deg).
    pub peak_torque_at_deg: f64,
    /// RMS motor torque over the cycle (N·m).
    pub rms_torque_nm: f64,
    /// Largest |motor speed| (rpm).
    pub peak_motor_speed_rpm: f64,
    /// Main-shaft angle of the peak motor speed (deg).
    pub peak_motor_speed_at_deg: f64,
    /// Largest ratio |T| / peak-torque line at the speed of that instant.
    pub envelope_ratio: f64,
    /// Main-shaft angle where it occurs (deg).
    pub envelope_ratio_at_deg: f64,
    /// Load inertia reflected to the motor over the rotor inertia.
    pub inertia_ratio: f64,
    /// The checks.
    pub checks: Vec<Check>,
    /// Every check passes.
    pub pass: bool,
}

/// One operating point of the motor over the cycle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OperatingPoint {
    /// Main-shaft angle (deg).
    pub angle_deg: f64,
    /// Motor speed (rpm).
    pub motor_speed_rpm: f64,
    /// Motor torque (N·m).
    pub torque_nm: f64,
}

/// `T = α s'' + β s' + γ s + ε + μ sgn(h s')` and `n = κ s'` on one moving cycle segment, with the
/// law's `s(x)`, `x` the fraction of the segment.
#[derive(Debug, Clone, Copy)]
struct Model {
    alpha: f64,
    beta: f64,
    gamma: f64,
    eps: f64,
    mu: f64,
    /// Sign of the stroke.
    sign: f64,
    kappa: f64,
}

impl Model {
    fn dwell(axis: &Axis, y: f64) -> Self {
        let k = axis.motor_rad_per_unit();
        let ke = k * axis.load.efficiency;
        Self {
            alpha: 0.0,
            beta: 0.0,
            gamma: 0.0,
            eps: (axis.load.spring_n_m * y + axis.load.constant_force_n) / ke,
            mu: 0.0,
            sign: 0.0,
            kappa: 0.0,
        }
    }

    fn moving(axis: &Axis, base: f64, h: f64, len_rad: f64, omega: f64) -> Self {
        let k = axis.motor_rad_per_unit();
        let ke = k * axis.load.efficiency;
        let r = omega / len_rad; // dx/dt
        let a_eff = (axis.motor.rotor_inertia_kg_m2 + axis.load.extra_inertia_kg_m2) * k + axis.load_mass() / ke;
        let l = &axis.load;
        Self {
            alpha: a_eff * h * r * r,
            beta: l.viscous_n_s_m * h * r / ke,
            gamma: l.spring_n_m * h / ke,
            eps: (l.spring_n_m * base + l.constant_force_n) / ke,
            mu: l.friction_n / ke,
            sign: h.signum(),
            kappa: loomkin_units::rpm_from_rad_per_s(k * h * r),
        }
    }

    /// (T, T', T'') and (n, n', n'') from the law's derivatives `d` (orders 0…5) and the sign of
    /// the velocity on the piece.
    fn eval(&self, d: &[f64; 6], vsign: f64) -> ([f64; 3], [f64; 3]) {
        let t = [
            self.alpha * d[2] + self.beta * d[1] + self.gamma * d[0] + self.eps + self.mu * vsign,
            self.alpha * d[3] + self.beta * d[2] + self.gamma * d[1],
            self.alpha * d[4] + self.beta * d[3] + self.gamma * d[2],
        ];
        let n = [self.kappa * d[1], self.kappa * d[2], self.kappa * d[3]];
        (t, n)
    }
}

/// What one moving segment contributes to the check, in order: a candidate peak torque, speed or
/// envelope ratio at the fraction `u` of the segment (`x0 + t` of its law segment), or a term of
/// `∫T² dt`.
#[derive(Debug, Clone, Copy)]
enum Event {
    Torque(f64, f64),
    Speed(f64, f64),
    Envelope(f64, f64),
    TorqueSquared(f64),
}

/// The events of moving segment `seg` (law `law`) of a cycle run at `omega` rad/s; with `all` false
/// only the terms of `∫T² dt` (the same values: the peaks are not searched).
fn moving_events(
    axis: &Axis,
    seg: &loomkin_laws::CycleSegment,
    law: &loomkin_laws::Law,
    omega: f64,
    all: bool,
) -> Vec<Event> {
    let envelope = |n: f64| axis.peak_envelope(n).unwrap_or_else(|| line_beyond(axis, n));
    let mut out = Vec::new();
    let m = Model::moving(axis, seg.base_si, seg.stroke_si, seg.length_rad, omega);
    // A crank and lever: the torque and speed from the model's series (not linear in the law).
    let crank = axis.load.crank_lever.is_some();
    let r = omega / seg.length_rad;
    for lseg in law.segments() {
        // Split the segment where the velocity changes sign (the Coulomb friction flips there).
        let mut cuts = vec![0.0];
        cuts.extend(lseg.derivative_roots(1).into_iter().filter(|&t| t > 0.0 && t < lseg.width()));
        cuts.push(lseg.width());
        for w in cuts.windows(2) {
            let (a, b) = (w[0], w[1]);
            if b <= a {
                continue;
            }
            let v_mid = lseg.deriv_local(1, 0.5 * (a + b));
            let vsign = if v_mid == 0.0 { 0.0 } else { m.sign * v_mid.signum() };
            let f = |t: f64| {
                if crank { crank_eval(axis, seg, lseg, t, r, vsign) } else { m.eval(&lseg.derivs_local(t), vsign) }
            };
            let u = |t: f64| lseg.x0() + t;
            let n_br = if crank { 2 * brackets(lseg, a, b) } else { brackets(lseg, a, b) };
            if all {
                let (v, at) = abs_max(a, b, n_br, |t| {
                    let (tq, _) = f(t);
                    (tq[0], tq[1], tq[2])
                });
                out.push(Event::Torque(v, u(at)));
                let (v, at) = abs_max(a, b, n_br, |t| {
                    let (_, n) = f(t);
                    (n[0], n[1], n[2])
                });
                out.push(Event::Speed(v, u(at)));
                // The ratio has a kink where the motor speed passes the rated or the maximum speed
                // (the peak line bends there): cut there, so that an interior maximum next to a
                // kink is bracketed by its own derivative's sign change.
                for piece in envelope_cuts(lseg, a, b, |t| f(t).1[0].abs(), &axis.motor).windows(2) {
                    let (v, at) = max_by(piece[0], piece[1], n_br, |t| {
                        let (tq, n) = f(t);
                        let (e, de) = envelope(n[0]);
                        let e = e.max(1e-12 * axis.motor.peak_torque_nm);
                        let q = tq[0].abs() / e;
                        let dq = (tq[0].signum() * tq[1] * e - tq[0].abs() * de * n[0].signum() * n[1]) / (e * e);
                        (q, dq)
                    });
                    out.push(Event::Envelope(v, u(at)));
                }
            }
            let t2 = if crank {
                // Not a polynomial: the rule on CRANK_PANELS equal parts.
                let w = (b - a) / CRANK_PANELS as f64;
                (0..CRANK_PANELS)
                    .map(|i| {
                        let lo = a + i as f64 * w;
                        let hi = if i + 1 == CRANK_PANELS { b } else { lo + w };
                        integral_t2(lseg, lo, hi, |t| f(t).0[0])
                    })
                    .sum()
            } else {
                integral_t2(lseg, a, b, |t| f(t).0[0])
            };
            out.push(Event::TorqueSquared(t2 * seg.length_rad / omega));
        }
    }
    out
}

/// Panels of the Gauss–Legendre rule per piece of `∫T² dt` with a crank and lever (its torque is
/// not a polynomial of the law: the RMS of 8 panels of 8 points and of 64 differ by 1e-16 relative on
/// the crank-lever test's modified-sine cycle).
const CRANK_PANELS: usize = 8;

/// `(T, dT/dx, d²T/dx²)` and `(n, dn/dx, d²n/dx²)` (rpm) of a crank and lever at local coordinate `t`
/// of law segment `lseg` of cycle segment `seg` (`x` its fraction, `r = dx/dt`), the Coulomb
/// friction of sign `vsign` (the piece's).
fn crank_eval(
    axis: &Axis,
    seg: &loomkin_laws::CycleSegment,
    lseg: &Segment,
    t: f64,
    r: f64,
    vsign: f64,
) -> ([f64; 3], [f64; 3]) {
    let d = lseg.derivs_local(t);
    let mut dt = [0.0; 6];
    let mut scale = seg.stroke_si;
    for k in 0..6 {
        dt[k] = scale * d[k];
        scale *= r;
    }
    dt[0] += seg.base_si;
    let nan = Jet::cst(f64::NAN);
    let (tq, al) = axis.motor_series_signed(Jet::from_derivs(dt), vsign).unwrap_or((nan, nan));
    let rpm = loomkin_units::rpm_from_rad_per_s;
    ([tq.v(), tq.d(1) / r, tq.d(2) / (r * r)], [rpm(al.d(1)), rpm(al.d(2)) / r, rpm(al.d(3)) / (r * r)])
}

/// The slave's lowest and highest positions over `cycle` (SI).
fn position_range(cycle: &Cycle) -> (f64, f64) {
    cycle.segments.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
        let (a, b) = (s.base_si, s.base_si + s.stroke_si);
        (lo.min(a).min(b), hi.max(a).max(b))
    })
}

/// What one segment of a cycle gives the check: a dwell's constant torque, or a moving segment's
/// events in order.
enum SegmentEvents<'a> {
    Dwell(f64),
    Moving(&'a [Event]),
}

/// The checked speed (rpm) of `axis` moving `cycle` at `speed_rpm`, after the checks every walk
/// of the cycle needs (the axis against the cycle's unit, a crank and lever's stroke without a
/// dead centre, the speed's range).
fn checked_speed(axis: &Axis, cycle: &Cycle, speed_rpm: f64) -> Result<f64> {
    axis.validate(cycle.unit)?;
    if let Some(cl) = &axis.load.crank_lever {
        let (lo, hi) = position_range(cycle);
        cl.check_stroke(lo, hi, "load.crank_lever")?;
    }
    Ok(loomkin_units::ShaftSpeed::from_rpm(speed_rpm)?.rpm())
}

/// What a check works out per distinct move (law, stroke, base and length), kept from one check to
/// the next of the same axis at the same speed: a search that changes a long cycle a little at a
/// time (the servo-shedding optimiser) meets the same moves again. The results are bit for bit
/// those without it. Beyond [`CheckMemo::MOVES`] moves (or [`CheckMemo::LAWS`] laws) it forgets
/// everything before the next check; another axis or speed starts it afresh.
#[derive(Debug, Clone, Default)]
pub struct CheckMemo {
    axis: Option<Axis>,
    omega: u64,
    laws: Vec<loomkin_laws::Law>,
    /// Per move: every event, or only the terms of `∫T² dt` (`all` false).
    moves: [MoveEvents; 2],
}

/// A move's events by its law (numbered in [`CheckMemo`]), base, stroke and length (bits).
type MoveEvents = loomkin_numeric::WordMap<(usize, u64, u64, u64), Vec<Event>>;

impl CheckMemo {
    /// Moves remembered (of each kind of walk) before the memo starts afresh.
    pub const MOVES: usize = 1 << 14;
    /// Distinct laws remembered before the memo starts afresh.
    pub const LAWS: usize = 256;

    /// Ready for `axis` at `omega` rad/s: emptied when either changed or when full.
    fn ready(&mut self, axis: &Axis, omega: f64) {
        let full = self.laws.len() > Self::LAWS || self.moves.iter().any(|m| m.len() > Self::MOVES);
        if full || self.axis.as_ref() != Some(axis) || self.omega != omega.to_bits() {
            *self = Self { axis: Some(axis.clone()), omega: omega.to_bits(), ..Default::default() };
        }
    }
}

/// Calls `f` with every segment of `cycle` (run at `omega` rad/s) in order and what it gives the
/// check. A segment of the same law, stroke, base and length as an earlier one (of this cycle or,
/// through `memo`, of an earlier check) gives the same values at the same fractions: worked out
/// once, replayed in order (bit for bit the same sums and maxima as working each out, so a long
/// cycle of repeated moves costs its distinct moves). `all`: every event of a move, else only its
/// terms of `∫T² dt`.
fn walk(
    axis: &Axis,
    cycle: &Cycle,
    omega: f64,
    all: bool,
    memo: &mut CheckMemo,
    mut f: impl FnMut(&loomkin_laws::CycleSegment, SegmentEvents<'_>),
) {
    memo.ready(axis, omega);
    // The laws of this cycle met so far (by address) and their numbers in the memo.
    let mut seen: Vec<(&loomkin_laws::Law, usize)> = Vec::new();
    for seg in &cycle.segments {
        let Some((_, law)) = &seg.law else {
            let t = if axis.load.crank_lever.is_some() {
                axis.torque_at(seg.base_si, 0.0, 0.0)
            } else {
                Model::dwell(axis, seg.base_si).eps
            };
            f(seg, SegmentEvents::Dwell(t));
            continue;
        };
        let law_id = match seen.iter().find(|(l, _)| std::ptr::eq(*l, law) || *l == law) {
            Some(&(_, id)) => id,
            None => {
                let id = match memo.laws.iter().position(|l| l == law) {
                    Some(id) => id,
                    None => {
                        memo.laws.push(law.clone());
                        memo.laws.len() - 1
                    }
                };
                seen.push((law, id));
                id
            }
        };
        let key = (law_id, seg.base_si.to_bits(), seg.stroke_si.to_bits(), seg.length_rad.to_bits());
        let events =
            memo.moves[usize::from(all)].entry(key).or_insert_with(|| moving_events(axis, seg, law, omega, all));
        f(seg, SegmentEvents::Moving(events));
    }
}

/// Checks `axis` moving `cycle` at `speed_rpm` (main shaft). A crank and lever must move the slave
/// over the cycle's positions without a dead centre ([`crate::CrankLever::check_stroke`]).
pub fn check_axis(axis: &Axis, cycle: &Cycle, speed_rpm: f64) -> Result<AxisReport> {
    check_axis_memo(axis, cycle, speed_rpm, &mut CheckMemo::default())
}

/// [`check_axis`], the moves' values remembered in `memo` from one check to the next (the same
/// report bit for bit).
pub fn check_axis_memo(axis: &Axis, cycle: &Cycle, speed_rpm: f64, memo: &mut CheckMemo) -> Result<AxisReport> {
    let speed_rpm = checked_speed(axis, cycle, speed_rpm)?;
    let omega = loomkin_units::rad_per_s_from_rpm(speed_rpm);
    let cycle_time_s = cycle.period_rad / omega;
    let mut pk_t = (0.0f64, 0.0f64);
    let mut pk_n = (0.0f64, 0.0f64);
    let mut env = (0.0f64, 0.0f64);
    let mut int_t2 = 0.0;
    let ratio = |t: f64, n: f64| {
        let e = axis.peak_envelope(n).map_or_else(|| line_beyond(axis, n).0, |(e, _)| e);
        t.abs() / e.max(1e-12 * axis.motor.peak_torque_nm)
    };
    walk(axis, cycle, omega, true, memo, |seg, events| {
        let start_deg = seg.start_rad.to_degrees();
        match events {
            SegmentEvents::Dwell(t) => {
                take(&mut pk_t, t.abs(), start_deg);
                take(&mut env, ratio(t, 0.0), start_deg);
                int_t2 += t * t * seg.length_rad / omega;
            }
            SegmentEvents::Moving(events) => {
                let len_deg = seg.length_rad.to_degrees();
                let deg = |u: f64| start_deg + len_deg * u;
                for e in events {
                    match *e {
                        Event::Torque(v, u) => take(&mut pk_t, v, deg(u)),
                        Event::Speed(v, u) => take(&mut pk_n, v, deg(u)),
                        Event::Envelope(v, u) => take(&mut env, v, deg(u)),
                        Event::TorqueSquared(x) => int_t2 += x,
                    }
                }
            }
        }
    });
    let rms = (int_t2 / cycle_time_s).sqrt();
    let mo = &axis.motor;
    let inertia_ratio = axis.inertia_ratio();
    let checks = vec![
        Check::new("peak_torque", pk_t.0, mo.peak_torque_nm, "N·m"),
        Check::new("rms_torque", rms, mo.rated_torque_nm, "N·m"),
        Check::new("peak_speed", pk_n.0, mo.max_speed_rpm, "rpm"),
        Check::new("torque_speed_envelope", env.0, 1.0, ""),
        Check::new("inertia_ratio", inertia_ratio, axis.limits.max_inertia_ratio, ""),
    ];
    let pass = checks.iter().all(|c| c.pass);
    Ok(AxisReport {
        speed_rpm,
        cycle_time_s,
        peak_torque_nm: pk_t.0,
        peak_torque_at_deg: pk_t.1,
        rms_torque_nm: rms,
        peak_motor_speed_rpm: pk_n.0,
        peak_motor_speed_at_deg: pk_n.1,
        envelope_ratio: env.0,
        envelope_ratio_at_deg: env.1,
        inertia_ratio,
        checks,
        pass,
    })
}

/// `∫T² dt` over each segment of `cycle` (N²·m²·s, in the cycle's order) when `axis` moves it at
/// `speed_rpm`: the terms [`check_axis`] sums for the RMS torque (`√(Σ/cycle time)`), on the same
/// closed form and quadrature — a dwell's constant torque times its duration, a move's exact
/// integral. What a study needs to weigh parts of a long cycle (the servo-shedding optimiser's
/// picks standing for classes of picks).
pub fn torque_squared_by_segment(axis: &Axis, cycle: &Cycle, speed_rpm: f64) -> Result<Vec<f64>> {
    torque_squared_by_segment_memo(axis, cycle, speed_rpm, &mut CheckMemo::default())
}

/// [`torque_squared_by_segment`], the moves' terms remembered in `memo` from one call to the next
/// (the same terms bit for bit).
pub fn torque_squared_by_segment_memo(
    axis: &Axis,
    cycle: &Cycle,
    speed_rpm: f64,
    memo: &mut CheckMemo,
) -> Result<Vec<f64>> {
    let omega = loomkin_units::rad_per_s_from_rpm(checked_speed(axis, cycle, speed_rpm)?);
    let mut out = Vec::with_capacity(cycle.segments.len());
    walk(axis, cycle, omega, false, memo, |seg, events| {
        out.push(match events {
            SegmentEvents::Dwell(t) => t * t * seg.length_rad / omega,
            SegmentEvents::Moving(events) => events
                .iter()
                .map(|e| if let Event::TorqueSquared(x) = *e { x } else { 0.0 })
                .fold(0.0, |acc, x| acc + x),
        });
    });
    Ok(out)
}

/// `n ≥ 2` operating points over the cycle, both ends included (the end as the left limit).
pub fn operating_points(axis: &Axis, cycle: &Cycle, speed_rpm: f64, n: usize) -> Result<Vec<OperatingPoint>> {
    axis.validate(cycle.unit)?;
    let speed_rpm = loomkin_units::ShaftSpeed::from_rpm(speed_rpm)?.rpm();
    Ok(cycle.sample(n.max(2), speed_rpm).into_iter().map(|p| operating_point(axis, p.angle_deg, &p.kin)).collect())
}

/// The operating point at one main-shaft angle (deg), e.g. where [`check_axis`] located the peak
/// torque (the same model as [`operating_points`]).
pub fn operating_point_at(axis: &Axis, cycle: &Cycle, speed_rpm: f64, angle_deg: f64) -> Result<OperatingPoint> {
    axis.validate(cycle.unit)?;
    let speed_rpm = loomkin_units::ShaftSpeed::from_rpm(speed_rpm)?.rpm();
    Ok(operating_point(axis, angle_deg, &cycle.eval(angle_deg.to_radians(), speed_rpm)))
}

fn operating_point(axis: &Axis, angle_deg: f64, q: &loomkin_laws::Kinematics) -> OperatingPoint {
    let w =
        if axis.load.crank_lever.is_some() { axis.motor_speed_at(q.s, q.v) } else { axis.motor_rad_per_unit() * q.v };
    OperatingPoint {
        angle_deg,
        motor_speed_rpm: loomkin_units::rpm_from_rad_per_s(w),
        torque_nm: axis.torque_at(q.s, q.v, q.a),
    }
}

/// A polyline of (speed in rpm, torque in N·m).
pub type Polyline = Vec<(f64, f64)>;

/// The motor's envelope for a plot: the continuous (S1) corner `[(0, T_r), (n_r, T_r)]` and the
/// peak line `[(0, T_p), (n_r, T_p), (n_max, T_max), (n_max, 0)]` (closed at the maximum speed).
pub fn envelope_lines(axis: &Axis) -> (Polyline, Polyline) {
    let m = &axis.motor;
    let t_max = m.torque_at_max_speed_nm.unwrap_or(m.rated_torque_nm);
    (
        vec![(0.0, m.rated_torque_nm), (m.rated_speed_rpm, m.rated_torque_nm)],
        vec![
            (0.0, m.peak_torque_nm),
            (m.rated_speed_rpm, m.peak_torque_nm),
            (m.max_speed_rpm, t_max),
            (m.max_speed_rpm, 0.0),
        ],
    )
}

/// The peak line continued beyond the maximum speed (for the ratio only; the speed check fails
/// there anyway), never below 1e-12 of the peak torque, and its slope (N·m per rpm; 0 where the
/// floor holds). The slope enters the ratio's derivative, whose roots locate the largest ratio:
/// with a slope of 0 there the largest ratio beyond the maximum speed was missed (5.780 instead of
/// 5.807 for the needle-rack axis at 2000 rev/min).
fn line_beyond(axis: &Axis, n: f64) -> (f64, f64) {
    let m = &axis.motor;
    let t_max = m.torque_at_max_speed_nm.unwrap_or(m.rated_torque_nm);
    let span = (m.max_speed_rpm - m.rated_speed_rpm).max(1e-12);
    let slope = (t_max - m.peak_torque_nm) / span;
    let line = t_max + slope * (n.abs() - m.max_speed_rpm);
    let floor = 1e-12 * m.peak_torque_nm;
    if line > floor { (line, slope) } else { (floor, 0.0) }
}

/// `[a, …, b]`: the points of `[a, b]` where the motor speed `|n(t)|` passes the rated or the
/// maximum speed, found by bisection on each stretch where the speed is monotone (between the
/// roots of the acceleration).
fn envelope_cuts(seg: &Segment, a: f64, b: f64, speed: impl Fn(f64) -> f64, motor: &crate::Motor) -> Vec<f64> {
    let mut mono = vec![a];
    mono.extend(seg.derivative_roots(2).into_iter().filter(|&t| t > a && t < b));
    mono.push(b);
    let mut cuts = vec![a];
    for w in mono.windows(2) {
        for level in [motor.rated_speed_rpm, motor.max_speed_rpm] {
            let g = |t: f64| speed(t) - level;
            let (g_lo, g_hi) = (g(w[0]), g(w[1]));
            if g_lo == 0.0 || g_hi == 0.0 || g_lo.signum() == g_hi.signum() {
                continue;
            }
            cuts.push(loomkin_numeric::bisect(w[0], w[1], |t| g(t).signum() == g_lo.signum()));
        }
        cuts.push(w[1]);
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    cuts
}

fn take(best: &mut (f64, f64), v: f64, at: f64) {
    if v > best.0 {
        *best = (v, at);
    }
}

/// Brackets for a function of a law segment's derivatives on `[a, b]`: twice the degree plus
/// three per half-period of its sine, plus 4.
fn brackets(seg: &Segment, a: f64, b: f64) -> usize {
    let osc = seg.sine().map_or(0.0, |s| (s.omega.abs() * (b - a) / PI).ceil());
    2 * (seg.degree() + 1) + 3 * osc as usize + 4
}

/// `∫ₐᵇ g(t)² dt` by 8-point Gauss–Legendre on `1 + 2·(half-periods)` panels (exact for the
/// polynomial segments, whose torque² has degree ≤ 14).
fn integral_t2(seg: &Segment, a: f64, b: f64, g: impl Fn(f64) -> f64) -> f64 {
    let osc = seg.sine().map_or(0.0, |s| (s.omega.abs() * (b - a) / PI).ceil()) as usize;
    let panels = 1 + 2 * osc;
    let h = (b - a) / panels as f64;
    let rule = loomkin_laws::gauss_legendre(8);
    let mut acc = 0.0;
    for i in 0..panels {
        let mid = a + (i as f64 + 0.5) * h;
        for &(x, w) in &rule {
            let v = g(mid + 0.5 * h * x);
            acc += 0.5 * h * w * v * v;
        }
    }
    acc
}

/// Largest `|g|` on `[a, b]` and where, for `f(t) = (g, g', g'')`: the ends and every root of `g'`
/// bracketed on `n` sub-intervals and refined by safeguarded Newton.
fn abs_max(a: f64, b: f64, n: usize, f: impl Fn(f64) -> (f64, f64, f64)) -> (f64, f64) {
    let gd = |t: f64| {
        let (g, d, _) = f(t);
        (g, d)
    };
    crate::poly::scan(
        a,
        b,
        n,
        gd,
        |t| f(t).0,
        |x0, x1, d0, _| {
            loomkin_numeric::refine_root(x0, x1, d0 < 0.0, |x| {
                let (_, d, dd) = f(x);
                (d, dd)
            })
        },
    )
}

/// Largest `q` on `[a, b]` and where, for `f(t) = (q, q')` (q' may jump): the ends and every sign
/// change of `q'` bracketed on `n` sub-intervals and located by bisection to rounding.
fn max_by(a: f64, b: f64, n: usize, f: impl Fn(f64) -> (f64, f64)) -> (f64, f64) {
    let (q0, mut d0) = f(a);
    let mut best = (q0, a);
    let h = (b - a) / n as f64;
    let mut x0 = a;
    for i in 1..=n {
        let x1 = if i == n { b } else { a + i as f64 * h };
        let (q1, d1) = f(x1);
        take(&mut best, q1, x1);
        if d0 > 0.0 && d1 < 0.0 {
            let r = loomkin_numeric::bisect(x0, x1, |t| f(t).1 > 0.0);
            take(&mut best, f(r).0, r);
        }
        (x0, d0) = (x1, d1);
    }
    best
}
