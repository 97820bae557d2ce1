//! Cam tables for a motion controller (master angle → slave position), and what they lose when
//! the controller interpolates between their points.

use crate::drive::CYCLE_DEG;
use crate::spline::solve_tridiagonal;
use crate::{Drive, Result, ServoError, poly};
use loomkin_io::csv::{CsvText, exponent};
use loomkin_laws::{Law, Segment};
use loomkin_units::Range;
use serde::Serialize;

/// One point of a cam table: master angle, slave position and its derivatives with respect to
/// the master angle (speed-independent, as controllers store cams).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CamPoint {
    /// Master (main-shaft) angle X (deg).
    pub master_deg: f64,
    /// Slave (rack) position Y (m).
    pub slave_m: f64,
    /// V = dY/dX (m/deg).
    pub v_m_per_deg: f64,
    /// A = d²Y/dX² (m/deg²).
    pub a_m_per_deg2: f64,
}

/// A cam table over one main-shaft turn, `0…360°` in equal steps (both ends included).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CamTable {
    /// The points.
    pub points: Vec<CamPoint>,
}

/// How a controller interpolates between table points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Interpolation {
    /// Straight lines between positions (velocity piecewise constant, acceleration zero).
    Linear,
    /// A natural cubic spline through the positions only.
    CubicSpline,
    /// Fifth-degree Hermite polynomials matching Y, V and A at both ends (XYVA points).
    QuinticHermite,
}

impl Interpolation {
    /// Every mode.
    pub const ALL: [Interpolation; 3] = [Self::Linear, Self::CubicSpline, Self::QuinticHermite];

    /// Kebab-case name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Linear => "linear",
            Self::CubicSpline => "cubic-spline",
            Self::QuinticHermite => "quintic-hermite",
        }
    }
}

/// The worst errors of a re-interpolated table against the exact law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct InterpolationError {
    /// Interpolation mode.
    pub mode: Interpolation,
    /// Table step (deg).
    pub step_deg: f64,
    /// Largest position error (m).
    pub max_position_error_m: f64,
    /// Largest velocity error (m/deg).
    pub max_velocity_error_m_per_deg: f64,
    /// Largest acceleration error (m/deg²).
    pub max_accel_error_m_per_deg2: f64,
    /// Position error relative to the stroke.
    pub rel_position_error: f64,
    /// Velocity error relative to the peak velocity.
    pub rel_velocity_error: f64,
    /// Acceleration error relative to the peak acceleration.
    pub rel_accel_error: f64,
}

/// Exact slave kinematics `(Y, dY/dX, d²Y/dX²)` at master angle `deg` for the rise / dwell /
/// return / dwell cycle of [`Drive::layout`].
pub fn slave_at(law: &Law, drive: &Drive, deg: f64) -> Result<[f64; 3]> {
    let lay = drive.layout()?;
    Ok(slave_in(law, drive.stroke_m, &lay, deg))
}

fn slave_in(law: &Law, h: f64, lay: &crate::CycleLayout, deg: f64) -> [f64; 3] {
    let st = lay.starts_deg();
    let deg = deg.clamp(0.0, CYCLE_DEG);
    if deg < st[1] {
        let k = law.eval(deg / lay.rise_deg);
        [h * k.s, h * k.v / lay.rise_deg, h * k.a / lay.rise_deg.powi(2)]
    } else if deg < st[2] {
        [h, 0.0, 0.0]
    } else if deg < st[3] {
        let k = law.eval((deg - st[2]) / lay.return_deg);
        [h * (1.0 - k.s), -h * k.v / lay.return_deg, -h * k.a / lay.return_deg.powi(2)]
    } else {
        [0.0, 0.0, 0.0]
    }
}

impl CamTable {
    /// The table of `law` on `drive`'s cycle with a step of about `step_deg` (deg), rounded so
    /// that a whole number `n = round(360/step)` of steps fits one turn (4 ≤ n ≤ 1 000 000).
    pub fn new(law: &Law, drive: &Drive, step_deg: f64) -> Result<Self> {
        drive.validate()?;
        let step = Range::closed(CYCLE_DEG / 1e6, CYCLE_DEG / 4.0, "deg").check("step_deg", step_deg)?;
        let lay = drive.layout()?;
        let n = (CYCLE_DEG / step).round() as usize;
        let points = (0..=n)
            .map(|i| {
                let x = CYCLE_DEG * i as f64 / n as f64;
                let [y, v, a] = slave_in(law, drive.stroke_m, &lay, x);
                CamPoint { master_deg: x, slave_m: y, v_m_per_deg: v, a_m_per_deg2: a }
            })
            .collect();
        Ok(Self { points })
    }

    /// The step between points (deg).
    pub fn step_deg(&self) -> f64 {
        CYCLE_DEG / (self.points.len() - 1) as f64
    }

    /// CSV with header `master_deg,slave_m,slave_v_m_per_deg,slave_a_m_per_deg2`.
    pub fn to_csv(&self) -> String {
        self.points_csv(&[], &["master_deg", "slave_m", "slave_v_m_per_deg", "slave_a_m_per_deg2"])
    }

    /// PLCopen-style XYVA points (`X,Y,V,A` per line after comment lines); a controller joins
    /// them with fifth-degree polynomials ([`Interpolation::QuinticHermite`]).
    pub fn to_xyva(&self) -> String {
        let comments = [
            "loomkin servo cam: PLCopen-style XYVA points over one main-shaft turn",
            "X master angle (deg), Y slave position (m), V = dY/dX (m/deg), A = d2Y/dX2 (m/deg^2)",
            "join consecutive points with fifth-degree polynomials matching Y, V, A at both ends",
        ];
        self.points_csv(&comments, &["X", "Y", "V", "A"])
    }

    /// The points as CSV under `comments` and the header `columns`, numbers in exponent form.
    fn points_csv(&self, comments: &[&str], columns: &[&str]) -> String {
        let mut t = CsvText::new(comments, columns);
        for p in &self.points {
            t.push([p.master_deg, p.slave_m, p.v_m_per_deg, p.a_m_per_deg2].map(exponent));
        }
        t.finish()
    }

    /// Re-interpolates the table as a controller would and returns the worst errors against the
    /// exact law.
    ///
    /// Every table interval is cut at the joints of the exact cycle inside it (the law's segment
    /// joints in the rise and the return, and the phase boundaries); on each piece the exact
    /// motion is one smooth law segment, and the largest |error| of position, velocity and
    /// acceleration is located by bracketing the sign changes of its derivative (the error of the
    /// next derivative) and refining them to rounding. The errors relative to the peaks use the
    /// exact peaks `H·Cv/φ_min` and `H·Ca/φ_min²` of the law's metrics.
    pub fn interpolation_error(&self, law: &Law, drive: &Drive, mode: Interpolation) -> Result<InterpolationError> {
        let lay = drive.layout()?;
        let stroke = drive.stroke_m;
        let h = self.step_deg();
        let pts = &self.points;
        let n = pts.len() - 1;
        let m2 = match mode {
            Interpolation::CubicSpline => natural_spline_moments(pts, h),
            _ => Vec::new(),
        };
        let joints = cycle_joints(law, &lay);
        let (mut ep, mut ev, mut ea) = (0.0f64, 0.0f64, 0.0f64);
        for i in 0..n {
            let (p0, p1) = (pts[i], pts[i + 1]);
            let c: Vec<f64> = match mode {
                Interpolation::Linear => vec![p0.slave_m, (p1.slave_m - p0.slave_m) / h],
                Interpolation::CubicSpline => {
                    let (ma, mb) = (m2[i], m2[i + 1]);
                    let d = (p1.slave_m - p0.slave_m) / h;
                    vec![p0.slave_m, d - h * (2.0 * ma + mb) / 6.0, ma / 2.0, (mb - ma) / (6.0 * h)]
                }
                Interpolation::QuinticHermite => quintic_hermite(
                    [p0.slave_m, p0.v_m_per_deg, p0.a_m_per_deg2],
                    [p1.slave_m, p1.v_m_per_deg, p1.a_m_per_deg2],
                    h,
                )
                .to_vec(),
            };
            // The interpolant and its first three derivatives (local t = master − X_i).
            let mut d = vec![c];
            for _ in 0..3 {
                let next = poly::deriv(&d[d.len() - 1]);
                d.push(next);
            }
            let inner = joints.iter().map(|&j| j - p0.master_deg).filter(|&t| t > 0.0 && t < h);
            let cuts: Vec<f64> = std::iter::once(0.0).chain(inner).chain(std::iter::once(h)).collect();
            for w in cuts.windows(2) {
                let (t0, t1) = (w[0], w[1]);
                let piece = Piece::at(law, stroke, &lay, p0.master_deg + 0.5 * (t0 + t1));
                for (q, worst) in [&mut ep, &mut ev, &mut ea].into_iter().enumerate() {
                    let (e, _) = poly::abs_max_by(t1 - t0, 16, |tau| {
                        let t = t0 + tau;
                        let ex = piece.eval(p0.master_deg + t);
                        (poly::eval(&d[q], t) - ex[q], poly::eval(&d[q + 1], t) - ex[q + 1])
                    });
                    *worst = worst.max(e);
                }
            }
        }
        let met = law.metrics();
        let phi = lay.rise_deg.min(lay.return_deg);
        let (pv, pa) = (stroke * met.cv / phi, stroke * met.ca / (phi * phi));
        let rel = |e: f64, p: f64| if p > 0.0 { e / p } else { 0.0 };
        Ok(InterpolationError {
            mode,
            step_deg: h,
            max_position_error_m: ep,
            max_velocity_error_m_per_deg: ev,
            max_accel_error_m_per_deg2: ea,
            rel_position_error: rel(ep, stroke),
            rel_velocity_error: rel(ev, pv),
            rel_accel_error: rel(ea, pa),
        })
    }
}

/// The master angles (deg) where the exact cycle changes its formula: the law's segment joints in
/// the rise and the return and the phase boundaries, sorted.
fn cycle_joints(law: &Law, lay: &crate::CycleLayout) -> Vec<f64> {
    let st = lay.starts_deg();
    let mut out: Vec<f64> = Vec::new();
    for (start, len) in [(st[0], lay.rise_deg), (st[2], lay.return_deg)] {
        out.extend(law.segments().iter().map(|seg| start + len * seg.x0()));
        out.push(start + len);
    }
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

/// One smooth piece of the exact cycle: a dwell, or one law segment in the rise or the return.
enum Piece<'a> {
    Dwell(f64),
    Moving { seg: &'a Segment, start_deg: f64, len_deg: f64, base_m: f64, stroke_m: f64 },
}

impl<'a> Piece<'a> {
    /// The piece that holds master angle `deg` (an angle strictly inside a piece).
    fn at(law: &'a Law, h: f64, lay: &crate::CycleLayout, deg: f64) -> Self {
        let st = lay.starts_deg();
        let (start, len, base, sign) = if deg < st[1] {
            (st[0], lay.rise_deg, 0.0, 1.0)
        } else if deg >= st[2] && deg < st[3] {
            (st[2], lay.return_deg, h, -1.0)
        } else {
            return Self::Dwell(if deg < st[2] { h } else { 0.0 });
        };
        let x = (deg - start) / len;
        let segs = law.segments();
        let k = segs.partition_point(|s| s.x1() <= x).min(segs.len() - 1);
        Self::Moving { seg: &segs[k], start_deg: start, len_deg: len, base_m: base, stroke_m: sign * h }
    }

    /// `[Y, dY/dX, d²Y/dX², d³Y/dX³]` (m, m/deg, m/deg², m/deg³) at master angle `deg`, from this
    /// piece's formula (extended a little past its ends, so a jump at a joint is not seen).
    fn eval(&self, deg: f64) -> [f64; 4] {
        match *self {
            Self::Dwell(y) => [y, 0.0, 0.0, 0.0],
            Self::Moving { seg, start_deg, len_deg, base_m, stroke_m } => {
                let k = seg.eval_local((deg - start_deg) / len_deg - seg.x0());
                [
                    base_m + stroke_m * k.s,
                    stroke_m * k.v / len_deg,
                    stroke_m * k.a / len_deg.powi(2),
                    stroke_m * k.j / len_deg.powi(3),
                ]
            }
        }
    }
}

/// Coefficients (local `t ∈ [0, h]`, lowest first) of the quintic with value, slope and
/// curvature `y0 = [Y, V, A]` at `t = 0` and `y1` at `t = h`.
///
/// With `Δ = Y₁ − (Y₀ + V₀h + A₀h²/2)`, `Δv = V₁ − (V₀ + A₀h)`, `Δa = A₁ − A₀`:
/// `c₃ = (10Δ − 4hΔv + h²Δa/2)/h³`, `c₄ = (−15Δ + 7hΔv − h²Δa)/h⁴`, `c₅ = (6Δ − 3hΔv + h²Δa/2)/h⁵`.
pub fn quintic_hermite(y0: [f64; 3], y1: [f64; 3], h: f64) -> [f64; 6] {
    let d = y1[0] - (y0[0] + y0[1] * h + 0.5 * y0[2] * h * h);
    let dv = y1[1] - (y0[1] + y0[2] * h);
    let da = y1[2] - y0[2];
    [
        y0[0],
        y0[1],
        0.5 * y0[2],
        (10.0 * d - 4.0 * h * dv + 0.5 * h * h * da) / h.powi(3),
        (-15.0 * d + 7.0 * h * dv - h * h * da) / h.powi(4),
        (6.0 * d - 3.0 * h * dv + 0.5 * h * h * da) / h.powi(5),
    ]
}

fn natural_spline_moments(pts: &[CamPoint], h: f64) -> Vec<f64> {
    let n = pts.len();
    let (mut lo, mut di, mut up, mut r) = (vec![h; n], vec![4.0 * h; n], vec![h; n], vec![0.0; n]);
    di[0] = 1.0;
    up[0] = 0.0;
    di[n - 1] = 1.0;
    lo[n - 1] = 0.0;
    for i in 1..n - 1 {
        r[i] = 6.0 * (pts[i + 1].slave_m - 2.0 * pts[i].slave_m + pts[i - 1].slave_m) / h;
    }
    solve_tridiagonal(&lo, &di, &up, &mut r);
    r
}

/// One fifth-degree segment of the exact law in controller units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Poly5Segment {
    /// Master start angle (deg).
    pub master_start_deg: f64,
    /// Master end angle (deg).
    pub master_end_deg: f64,
    /// Slave position (m) as a polynomial in `τ = master − master_start_deg` (deg), lowest first.
    pub coeffs: [f64; 6],
}

/// The exact law over one turn as fifth-degree polynomial segments in master degrees and slave
/// metres (rise segments, dwell, return segments, dwell): no interpolation loss.
///
/// Fails for laws with sinusoidal terms or displacement degree above 5 (catalogue laws such as
/// cycloidal); the spline law is always of degree 5.
pub fn poly5_segments(law: &Law, drive: &Drive) -> Result<Vec<Poly5Segment>> {
    let lay = drive.layout()?;
    let st = lay.starts_deg();
    let h = drive.stroke_m;
    let mut out = Vec::new();
    for (phase, (start, len, base, sign)) in
        [(st[0], lay.rise_deg, 0.0, 1.0), (st[2], lay.return_deg, h, -1.0)].into_iter().enumerate()
    {
        for seg in law.segments() {
            let p = seg.displacement_poly();
            if seg.sine().is_some() || p[6] != 0.0 || p[7] != 0.0 {
                return Err(ServoError::Cycle {
                    field: "law".into(),
                    reason: "poly5 export needs a polynomial law of degree ≤ 5 (the spline law is)".into(),
                });
            }
            let mut c: [f64; 6] = std::array::from_fn(|k| sign * h * p[k] / len.powi(k as i32));
            c[0] += base;
            out.push(Poly5Segment {
                master_start_deg: start + len * seg.x0(),
                master_end_deg: start + len * seg.x1(),
                coeffs: c,
            });
        }
        let (d0, dl, y) =
            if phase == 0 { (st[1], lay.dwell_after_rise_deg, h) } else { (st[3], lay.dwell_after_return_deg, 0.0) };
        if dl > 0.0 {
            out.push(Poly5Segment {
                master_start_deg: d0,
                master_end_deg: d0 + dl,
                coeffs: [y, 0.0, 0.0, 0.0, 0.0, 0.0],
            });
        }
    }
    Ok(out)
}

/// The fifth-degree segments as CSV with comment lines:
/// `master_start_deg,master_end_deg,c0_m,c1_m_per_deg,…,c5_m_per_deg5`.
pub fn poly5_csv(segments: &[Poly5Segment]) -> String {
    let mut t = CsvText::new(
        &[
            "loomkin servo cam: fifth-degree polynomial segments over one main-shaft turn",
            "slave position (m) = c0 + c1*t + ... + c5*t^5 with t = master angle - master_start_deg (deg)",
        ],
        &[
            "master_start_deg",
            "master_end_deg",
            "c0_m",
            "c1_m_per_deg",
            "c2_m_per_deg2",
            "c3_m_per_deg3",
            "c4_m_per_deg4",
            "c5_m_per_deg5",
        ],
    );
    for g in segments {
        t.push([g.master_start_deg, g.master_end_deg].iter().chain(&g.coeffs).map(|&v| exponent(v)));
    }
    t.finish()
}
