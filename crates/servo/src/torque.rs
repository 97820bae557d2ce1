//! Motor torque, RMS torque and power of a drive moved through a law over one main-shaft turn.

use crate::drive::CYCLE_DEG;
use crate::{Drive, Result, poly};
use loomkin_laws::{Law, Segment};
use loomkin_units::ShaftSpeed;
use serde::Serialize;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// Which part of the main-shaft turn a point belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Phase {
    /// The forward stroke `u = H·u°(x)`.
    Rise,
    /// Standing at `u = H`.
    DwellAfterRise,
    /// The return stroke `u = H·(1 − u°(x))`.
    Return,
    /// Standing at `u = 0`.
    DwellAfterReturn,
}

/// One sample of the drive over the cycle, in SI units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DrivePoint {
    /// Main-shaft angle (deg), 0…360.
    pub angle_deg: f64,
    /// Time from the start of the rise (s).
    pub time_s: f64,
    /// The phase.
    pub phase: Phase,
    /// Rack position `u` (m).
    pub u_m: f64,
    /// Rack velocity `u̇` (m/s).
    pub v_m_s: f64,
    /// Rack acceleration `ü` (m/s²).
    pub a_m_s2: f64,
    /// Motor torque `M` (N·m).
    pub torque_nm: f64,
    /// Motor power `P = M·θ̇_m` (W).
    pub power_w: f64,
}

/// Peak and RMS values of the drive at one main-shaft speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TorqueSummary {
    /// Main-shaft speed (1/min).
    pub speed_rpm: f64,
    /// Largest |M| over the turn (N·m), located exactly on the closed form.
    pub peak_torque_nm: f64,
    /// Main-shaft angle of the peak torque (deg).
    pub peak_torque_angle_deg: f64,
    /// RMS torque over the whole turn, `√((1/T_c)∫M² dt)` (N·m), integrated exactly.
    pub rms_torque_nm: f64,
    /// Largest |P| = |M·θ̇_m| over the turn (W).
    pub peak_power_w: f64,
    /// Largest rack velocity (m/s).
    pub peak_velocity_m_s: f64,
    /// Largest |rack acceleration| (m/s²).
    pub peak_accel_m_s2: f64,
    /// Largest motor speed (1/min).
    pub peak_motor_speed_rpm: f64,
    /// Duration of the rise (s).
    pub rise_time_s: f64,
    /// Duration of one main-shaft turn (s).
    pub cycle_time_s: f64,
}

/// `M = α·a + β·v + γ·s + ε` and `θ̇_m = κ·v` in terms of the unit law on one phase.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PhaseModel {
    phase: Phase,
    start_deg: f64,
    length_deg: f64,
    /// Phase duration (s).
    duration_s: f64,
    /// Position at x = 0 and signed stroke (m).
    base_m: f64,
    stroke_m: f64,
    alpha: f64,
    beta: f64,
    gamma: f64,
    eps: f64,
    kappa: f64,
    moving: bool,
}

/// Checks the speed against the one main-shaft speed range ([`ShaftSpeed::RANGE`]).
fn check_speed(speed_rpm: f64) -> Result<f64> {
    Ok(ShaftSpeed::from_rpm(speed_rpm)?.rpm())
}

pub(crate) fn models(drive: &Drive, speed_rpm: f64) -> Result<[PhaseModel; 4]> {
    drive.validate()?;
    let speed_rpm = check_speed(speed_rpm)?;
    let lay = drive.layout()?;
    let deg_per_s = speed_rpm * 6.0;
    let h = drive.stroke_m;
    let ftt = drive.force_to_torque_m();
    let a_c = drive.inertia_coefficient();
    let b_c = ftt * drive.damping_n_s_m;
    let c_c = ftt * drive.spring_n_m;
    let e_c = ftt * (drive.spring_preload_n + drive.constant_force_n);
    let k_m = drive.motor_rad_per_m();
    let starts = lay.starts_deg();
    let lens = [lay.rise_deg, lay.dwell_after_rise_deg, lay.return_deg, lay.dwell_after_return_deg];
    let phases = [Phase::Rise, Phase::DwellAfterRise, Phase::Return, Phase::DwellAfterReturn];
    Ok(std::array::from_fn(|i| {
        let t = lens[i] / deg_per_s;
        let sign = match phases[i] {
            Phase::Rise => 1.0,
            Phase::Return => -1.0,
            _ => 0.0,
        };
        let base = if matches!(phases[i], Phase::DwellAfterRise | Phase::Return) { h } else { 0.0 };
        let moving = sign != 0.0;
        let hs = sign * h;
        PhaseModel {
            phase: phases[i],
            start_deg: starts[i],
            length_deg: lens[i],
            duration_s: t,
            base_m: base,
            stroke_m: hs,
            alpha: if moving { a_c * hs / (t * t) } else { 0.0 },
            beta: if moving { b_c * hs / t } else { 0.0 },
            gamma: c_c * hs,
            eps: e_c + c_c * base,
            kappa: if moving { k_m * hs / t } else { 0.0 },
            moving,
        }
    }))
}

/// `M(t) = α·s'' + β·s' + γ·s + ε` of one phase model on a polynomial segment, as one polynomial in
/// the local coordinate (lowest power first), and its degree.
fn torque_poly(seg: &Segment, m: &PhaseModel) -> ([f64; 8], usize) {
    let p = seg.displacement_poly();
    let mut mp = [0.0; 8];
    for k in 0..8 {
        let v = if k < 7 { (k + 1) as f64 * p[k + 1] } else { 0.0 };
        let a = if k < 6 { ((k + 1) * (k + 2)) as f64 * p[k + 2] } else { 0.0 };
        mp[k] = m.gamma * p[k] + m.beta * v + m.alpha * a;
    }
    mp[0] += m.eps;
    let deg = mp.iter().rposition(|&c| c != 0.0).unwrap_or(0);
    (mp, deg)
}

/// Sub-intervals of [`poly::abs_max`]'s scan for a torque polynomial of degree `deg`.
fn torque_scan(deg: usize) -> usize {
    2 * deg + 2
}

/// Peak |M| of one phase model on one law segment with a sinusoid, and its local t.
fn segment_peak(seg: &Segment, m: &PhaseModel) -> (f64, f64) {
    poly::abs_max_by(seg.width(), sine_scan(seg), |t| {
        let k = seg.eval_local(t);
        (m.alpha * k.a + m.beta * k.v + m.gamma * k.s + m.eps, m.alpha * k.j + m.beta * k.a + m.gamma * k.v)
    })
}

/// Sub-intervals of the torque peak scan of a segment with a sinusoid.
fn sine_scan(seg: &Segment) -> usize {
    2 * (seg.degree() + 1) + 4 * sine_half_periods(seg) + 4
}

/// Half periods of the sinusoid over the segment (rounded up).
fn sine_half_periods(seg: &Segment) -> usize {
    seg.sine().map_or(0.0, |s| (s.omega.abs() * seg.width() / PI).ceil()) as usize
}

/// Peak |P| (and its local t) and ∫M² dt_local of one phase model on one law segment; each 0 when
/// not asked for.
fn segment_power_rms(seg: &Segment, m: &PhaseModel, with_power: bool, with_rms: bool) -> (f64, f64, f64) {
    let w = seg.width();
    if seg.sine().is_none() {
        let p = seg.displacement_poly();
        let (mp, deg) = torque_poly(seg, m);
        let mp = &mp[..=deg];
        let (pp, tp) = if with_power {
            let mut v = [0.0; 7];
            for (k, c) in v.iter_mut().enumerate() {
                *c = (k + 1) as f64 * p[k + 1] * m.kappa;
            }
            let mut pw = [0.0; 14];
            let len = mp.len() + v.len() - 1;
            poly::mul_into(mp, &v, &mut pw[..len]);
            poly::abs_max(&pw[..len], w, 2 * (deg + 6) + 2)
        } else {
            (0.0, 0.0)
        };
        let m2 = if with_rms { poly::integral(&poly::mul(mp, mp), w) } else { 0.0 };
        return (pp, tp, m2);
    }
    let (pp, tp) = if with_power {
        poly::abs_max_by(w, 2 * sine_scan(seg), |t| {
            let k = seg.eval_local(t);
            let mm = m.alpha * k.a + m.beta * k.v + m.gamma * k.s + m.eps;
            let dm = m.alpha * k.j + m.beta * k.a + m.gamma * k.v;
            (m.kappa * mm * k.v, m.kappa * (dm * k.v + mm * k.a))
        })
    } else {
        (0.0, 0.0)
    };
    if !with_rms {
        return (pp, tp, 0.0);
    }
    let rule = gl8();
    let panels = 1 + 2 * sine_half_periods(seg);
    let hp = w / panels as f64;
    let mut acc = 0.0;
    for i in 0..panels {
        let mid = (i as f64 + 0.5) * hp;
        for &(x, wt) in rule {
            let k = seg.eval_local(mid + 0.5 * hp * x);
            let mm = m.alpha * k.a + m.beta * k.v + m.gamma * k.s + m.eps;
            acc += 0.5 * hp * wt * mm * mm;
        }
    }
    (pp, tp, acc)
}

fn gl8() -> &'static [(f64, f64)] {
    static RULE: OnceLock<Vec<(f64, f64)>> = OnceLock::new();
    RULE.get_or_init(|| loomkin_laws::gauss_legendre(8))
}

/// Peak and RMS torque and peak power of `drive` moved through `law` at `speed_rpm` (1/min).
///
/// Over one turn (rise, dwell, return, dwell — see [`Drive::layout`]). The extremes are found
/// exactly per law segment (roots of the derivative bracketed and bisected); the RMS torque is
/// `√((1/T_c) Σ_phases T_p ∫₀¹ M² dx)`, with `∫M² dx` exact for polynomial segments and 8-point
/// Gauss–Legendre per half-period for sinusoidal ones.
pub fn summary(law: &Law, drive: &Drive, speed_rpm: f64) -> Result<TorqueSummary> {
    let ms = models(drive, speed_rpm)?;
    let cycle_s = CYCLE_DEG / (speed_rpm * 6.0);
    let st = stats(law, &ms, cycle_s, true, true);
    let met = law.metrics();
    let h = drive.stroke_m;
    let t_rise = ms[0].duration_s;
    let t_min = ms[0].duration_s.min(ms[2].duration_s);
    let vmax = h * met.cv / t_min;
    Ok(TorqueSummary {
        speed_rpm,
        peak_torque_nm: st.peak_torque_nm,
        peak_torque_angle_deg: st.peak_torque_angle_deg,
        rms_torque_nm: st.rms_torque_nm,
        peak_power_w: st.peak_power_w,
        peak_velocity_m_s: vmax,
        peak_accel_m_s2: h * met.ca / (t_min * t_min),
        peak_motor_speed_rpm: loomkin_units::rpm_from_rad_per_s(vmax * drive.motor_rad_per_m()),
        rise_time_s: t_rise,
        cycle_time_s: cycle_s,
    })
}

/// Peak and RMS torque (and, if asked, peak power) over one turn.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stats {
    pub peak_torque_nm: f64,
    pub peak_torque_angle_deg: f64,
    pub rms_torque_nm: f64,
    pub peak_power_w: f64,
}

pub(crate) fn stats(law: &Law, ms: &[PhaseModel; 4], cycle_s: f64, with_power: bool, with_rms: bool) -> Stats {
    stats_above(law, ms, cycle_s, with_power, with_rms, 0.0)
}

/// The largest |M| over the turn and its angle, where a peak not above `floor` need not be found:
/// `max(floor, value)` is that of the full scan, and so is the angle when `floor = 0`.
///
/// The scan reports the largest value, the first of equal maxima in turn order (phases, then
/// segments, then each segment's own first maximum). A polynomial segment whose upper bound of |M|
/// ([`poly::abs_bound`]) is below the floor or below the best value found so far is not searched:
/// it cannot hold that peak.
fn peak_torque(law: &Law, ms: &[PhaseModel; 4], floor: f64) -> (f64, f64) {
    peak_walk(law, ms, |seg, m, best| segment_peak_above(seg, m, floor.max(best)))
}

/// The walk of the peak search: the dwells' constant |M|, then each moving phase's segments in
/// turn, keeping the first of equal maxima. `seg_peak(seg, m, best)` gives a segment's largest
/// |M| and its local t, or `None` when it cannot exceed the best value found so far.
fn peak_walk(
    law: &Law,
    ms: &[PhaseModel; 4],
    mut seg_peak: impl FnMut(&Segment, &PhaseModel, f64) -> Option<(f64, f64)>,
) -> (f64, f64) {
    let (mut pk_m, mut pk_m_deg) = (0.0f64, 0.0);
    for m in ms {
        if !m.moving {
            if m.eps.abs() > pk_m && m.length_deg > 0.0 {
                pk_m = m.eps.abs();
                pk_m_deg = m.start_deg;
            }
            continue;
        }
        for seg in law.segments() {
            let Some((a, ta)) = seg_peak(seg, m, pk_m) else { continue };
            if a > pk_m {
                pk_m = a;
                pk_m_deg = m.start_deg + m.length_deg * (seg.x0() + ta);
            }
        }
    }
    (pk_m, pk_m_deg)
}

/// Largest |M| of one phase model on one law segment and its local t; `None` for a polynomial
/// segment whose upper bound of |M| ([`poly::abs_bound`]) is below `above` (it is not searched).
fn segment_peak_above(seg: &Segment, m: &PhaseModel, above: f64) -> Option<(f64, f64)> {
    if seg.sine().is_some() {
        return Some(segment_peak(seg, m));
    }
    let (mp, deg) = torque_poly(seg, m);
    if poly::abs_bound(&mp, seg.width()) < above {
        return None;
    }
    Some(poly::abs_max(&mp[..=deg], seg.width(), torque_scan(deg)))
}

/// [`stats`], where a peak torque not above `floor` need not be found: `max(floor, peak_torque_nm)`
/// is the same as with [`stats`], bit for bit, and so is everything else when `floor = 0`
/// (`floor = +∞` skips the peak search, for the RMS alone).
pub(crate) fn stats_above(
    law: &Law,
    ms: &[PhaseModel; 4],
    cycle_s: f64,
    with_power: bool,
    with_rms: bool,
    floor: f64,
) -> Stats {
    let (pk_m, pk_m_deg) = if floor == f64::INFINITY { (0.0, 0.0) } else { peak_torque(law, ms, floor) };
    let (mut pk_p, mut m2) = (0.0f64, 0.0);
    if with_power || with_rms {
        for m in ms {
            if !m.moving {
                m2 += m.eps * m.eps * m.duration_s;
                continue;
            }
            let mut int = 0.0;
            for seg in law.segments() {
                let (p, _, i2) = segment_power_rms(seg, m, with_power, with_rms);
                pk_p = pk_p.max(p);
                int += i2;
            }
            m2 += int * m.duration_s;
        }
    }
    Stats {
        peak_torque_nm: pk_m,
        peak_torque_angle_deg: pk_m_deg,
        rms_torque_nm: (m2 / cycle_s).sqrt(),
        peak_power_w: pk_p,
    }
}

/// [`summary`] at several speeds.
pub fn summaries(law: &Law, drive: &Drive, speeds_rpm: &[f64]) -> Result<Vec<TorqueSummary>> {
    speeds_rpm.iter().map(|&n| summary(law, drive, n)).collect()
}

/// `n ≥ 2` samples of the drive over one turn (0…360° of the main shaft, both ends included).
pub fn torque_curve(law: &Law, drive: &Drive, speed_rpm: f64, n: usize) -> Result<Vec<DrivePoint>> {
    let ms = models(drive, speed_rpm)?;
    let n = n.max(2);
    let deg_per_s = speed_rpm * 6.0;
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let angle = CYCLE_DEG * i as f64 / (n - 1) as f64;
        let idx = ms.iter().rposition(|m| m.length_deg > 0.0 && angle >= m.start_deg).unwrap_or(0);
        out.push(point(law, &ms[idx], drive, angle, deg_per_s));
    }
    Ok(out)
}

fn point(law: &Law, m: &PhaseModel, drive: &Drive, angle: f64, deg_per_s: f64) -> DrivePoint {
    let time_s = angle / deg_per_s;
    if !m.moving {
        return DrivePoint {
            angle_deg: angle,
            time_s,
            phase: m.phase,
            u_m: m.base_m,
            v_m_s: 0.0,
            a_m_s2: 0.0,
            torque_nm: m.eps,
            power_w: 0.0,
        };
    }
    let x = ((angle - m.start_deg) / m.length_deg).clamp(0.0, 1.0);
    let k = law.eval(x);
    let t = m.duration_s;
    let torque = m.alpha * k.a + m.beta * k.v + m.gamma * k.s + m.eps;
    let v = m.stroke_m * k.v / t;
    DrivePoint {
        angle_deg: angle,
        time_s,
        phase: m.phase,
        u_m: m.base_m + m.stroke_m * k.s,
        v_m_s: v,
        a_m_s2: m.stroke_m * k.a / (t * t),
        torque_nm: torque,
        power_w: torque * v * drive.motor_rad_per_m(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{SplineEnd, SplineLaw};
    use loomkin_laws::LawSpec;
    use proptest::prelude::*;

    /// The peak search of every segment in turn order (`peak_torque`'s walk), none skipped by its
    /// bound: the bounded scan must reproduce it bit for bit.
    fn plain_peak(law: &Law, ms: &[PhaseModel; 4]) -> (f64, f64) {
        peak_walk(law, ms, |seg, m, _| segment_peak_above(seg, m, f64::NEG_INFINITY))
    }

    fn drive(damping: f64, spring: f64, force: f64) -> Drive {
        Drive { damping_n_s_m: damping, spring_n_m: spring, constant_force_n: force, ..Drive::needle_rack_default() }
    }

    /// Spline laws from random points, drives with and without spring, damping and a constant
    /// force (the dwell torque then competes with the moving phases), and random floors.
    fn check_law(law: &Law, d: &Drive, speed: f64, floor: f64) {
        let ms = models(d, speed).unwrap();
        let plain = plain_peak(law, &ms);
        let bounded = peak_torque(law, &ms, 0.0);
        assert_eq!(bounded.0.to_bits(), plain.0.to_bits(), "peak {bounded:?} vs {plain:?}");
        assert_eq!(bounded.1.to_bits(), plain.1.to_bits(), "angle {bounded:?} vs {plain:?}");
        let above = peak_torque(law, &ms, floor);
        assert_eq!(above.0.max(floor).to_bits(), plain.0.max(floor).to_bits(), "floor {floor}");
        let s = stats(law, &ms, 0.1, true, true);
        assert_eq!((s.peak_torque_nm, s.peak_torque_angle_deg), plain);
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]
        #[test]
        fn bounded_peak_search_is_the_plain_scan(
            ys in proptest::collection::vec(0.05f64..1.0, 5),
            gaps in proptest::collection::vec(0.3f64..1.0, 6),
            damping in 0.0f64..40.0,
            spring in prop_oneof![Just(0.0), 0.0f64..4000.0],
            force in prop_oneof![Just(0.0), -60.0f64..60.0],
            speed in 100.0f64..900.0,
            floor_frac in 0.0f64..1.5,
        ) {
            let total: f64 = gaps.iter().sum();
            let mut x = 0.0;
            let mut pts = vec![[0.0, 0.0]];
            for (g, y) in gaps.iter().zip(&ys) {
                x += 0.5 * g / total;
                pts.push([x, *y]);
            }
            pts.push([0.5, 0.0]);
            let Ok(law) = SplineLaw::new(&pts, SplineEnd::Natural) else { return Ok(()) };
            let d = drive(damping, spring, force);
            let full = plain_peak(law.law(), &models(&d, speed).unwrap()).0;
            check_law(law.law(), &d, speed, floor_frac * full);
        }
    }

    #[test]
    fn bounded_peak_search_on_catalogue_laws() {
        // Sinusoid segments (cycloidal, modified sine) are searched in full; polynomial ones
        // (3-4-5, trapezoid) bounded; a constant force makes the dwells hold the peak.
        for name in ["cycloidal", "poly345", "modified-trapezoid", "modified-sine", "constant-acceleration"] {
            let law = LawSpec::parse::<&str, &str>(name, &[]).unwrap().build().unwrap();
            for (damping, spring, force) in [(5.0, 0.0, 0.0), (20.0, 1500.0, 10.0), (0.0, 0.0, 400.0)] {
                for speed in [300.0, 600.0] {
                    check_law(&law, &drive(damping, spring, force), speed, 0.0);
                }
            }
        }
    }
}
