//! The cubic spline of the acceleration through the definition points, and the law built on it.

use crate::points::check_points;
use crate::{Result, ServoError, poly};
use loomkin_laws::{AccelPiece, EndCondition, Law};
use loomkin_numeric::solve_tridiagonal;
use serde::{Deserialize, Serialize};

/// The condition of the acceleration spline at `x = 0` (the start of the motion).
///
/// At `x = 0.5` the slope is always the paper's `D` (see [`slope_at_middle`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum SplineEnd {
    /// `f''(0) = 0`, the natural spline (the default). The jerk `f'(0)` is free, so it jumps
    /// from 0 when the motion starts out of a dwell.
    #[default]
    Natural,
    /// `f'(0) = 0`: the jerk is zero at the start (and, by symmetry, at the end), so the
    /// displacement is C³ at the junctions with the dwells.
    Clamped,
}

impl SplineEnd {
    /// Reads `natural` or `clamped`.
    pub fn parse(text: &str) -> Result<Self> {
        match text.trim().to_ascii_lowercase().as_str() {
            "natural" => Ok(Self::Natural),
            "clamped" => Ok(Self::Clamped),
            _ => {
                Err(ServoError::Parse { field: "end".into(), text: text.into(), expected: "natural or clamped".into() })
            }
        }
    }

    /// `natural` or `clamped`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Natural => "natural",
            Self::Clamped => "clamped",
        }
    }
}

/// The paper's slope `D = g'(0.5)` of the cubic `g` through the points `(X_a, Y_a)`, `(X_b, Y_b)`
/// (the paper's points 5 and 6, i.e. N−2 and N−1) and their images `(1 − X, −Y)` about `(0.5, 0)`.
///
/// Four points placed odd-symmetrically about `(0.5, 0)` have an odd interpolating cubic, so with
/// `t = x − 0.5`, `g = D·t + β·t³`, and from `g(X_a) = Y_a`, `g(X_b) = Y_b`:
///
/// $$ D = \frac{Y_a t_b^3 - Y_b t_a^3}{t_a t_b (t_b^2 - t_a^2)}, \qquad t = X - 0.5. $$
///
/// This equals the paper's expanded formula (its numerator is `8(Y_b t_a³ − Y_a t_b³)`); both are
/// checked against a direct 4×4 solve in the tests. Requires `X_a < X_b < 0.5`.
pub fn slope_at_middle(a: [f64; 2], b: [f64; 2]) -> f64 {
    let (ta, tb) = (a[0] - 0.5, b[0] - 0.5);
    (a[1] * tb.powi(3) - b[1] * ta.powi(3)) / (ta * tb * (tb * tb - ta * ta))
}

/// Second derivatives `M_j = f''(X_j)` of the cubic spline through `points` with the given start
/// condition and `f'(0.5) = d`.
///
/// With `h_j = X_{j+1} − X_j` and `δ_j = (Y_{j+1} − Y_j)/h_j`, the interior rows are
/// `h_{j−1}M_{j−1} + 2(h_{j−1} + h_j)M_j + h_jM_{j+1} = 6(δ_j − δ_{j−1})`; the last row is
/// `h M_{N−1} + 2h M_N = 6(D − δ_{N−1})`; the first is `M_1 = 0` (natural) or
/// `2h M_1 + h M_2 = 6δ_1` (clamped, `f'(0) = 0`).
pub(crate) fn spline_moments(points: &[[f64; 2]], end: SplineEnd, d: f64) -> Vec<f64> {
    let n = points.len();
    let h: Vec<f64> = points.windows(2).map(|w| w[1][0] - w[0][0]).collect();
    let delta: Vec<f64> = points.windows(2).zip(&h).map(|(w, h)| (w[1][1] - w[0][1]) / h).collect();
    let (mut lo, mut di, mut up, mut r) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    match end {
        SplineEnd::Natural => di[0] = 1.0,
        SplineEnd::Clamped => {
            di[0] = 2.0 * h[0];
            up[0] = h[0];
            r[0] = 6.0 * delta[0];
        }
    }
    for i in 1..n - 1 {
        lo[i] = h[i - 1];
        di[i] = 2.0 * (h[i - 1] + h[i]);
        up[i] = h[i];
        r[i] = 6.0 * (delta[i] - delta[i - 1]);
    }
    lo[n - 1] = h[n - 2];
    di[n - 1] = 2.0 * h[n - 2];
    r[n - 1] = 6.0 * (d - delta[n - 2]);
    solve_tridiagonal(&lo, &di, &up, &mut r);
    r
}

/// A motion law whose acceleration is the cubic spline through definition points (Sivčák 2017).
///
/// On `[0, 0.5]` the acceleration image `f(x)` is the cubic spline through `[X_j, Y_j]`,
/// `j = 1…N`, with slope `D` ([`slope_at_middle`]) at `x = 0.5` and the [`SplineEnd`] condition at
/// `x = 0`; on `[0.5, 1]` it is the odd mirror `f(x) = −f(1 − x)`. The core law
/// ([`SplineLaw::law`]) integrates `f` twice in closed form from rest and scales it by
/// `1/F(1)` so that `u°(1) = 1`; its acceleration is `u°'' = f / F(1)`.
///
/// ```
/// use loomkin_servo::{SplineEnd, SplineLaw};
/// let law = SplineLaw::new(&[[0.0, 0.0], [0.1, 0.9], [0.25, 1.0], [0.4, 0.7], [0.5, 0.0]], SplineEnd::Natural)?;
/// let k = law.law().eval(1.0);
/// assert!((k.s - 1.0).abs() < 1e-12 && k.v.abs() < 1e-12);
/// # Ok::<(), loomkin_servo::ServoError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SplineLaw {
    points: Vec<[f64; 2]>,
    end: SplineEnd,
    d: f64,
    /// Spline coefficients of f on each interval of [0, 0.5], local t = x − X_j, lowest first.
    local: Vec<[f64; 4]>,
    scale: f64,
    law: Law,
}

impl SplineLaw {
    /// Builds the law from definition points (checked by [`crate::check_points`]).
    pub fn new(points: &[[f64; 2]], end: SplineEnd) -> Result<Self> {
        let points = check_points(points)?;
        let n = points.len();
        let d = slope_at_middle(points[n - 3], points[n - 2]);
        if !d.is_finite() {
            return Err(ServoError::Point {
                index: n - 2,
                x: points[n - 3][0],
                y: points[n - 3][1],
                reason: "the slope D at x = 0.5 is not finite for these points".into(),
            });
        }
        let m = spline_moments(&points, end, d);
        let local: Vec<[f64; 4]> = points
            .windows(2)
            .zip(m.windows(2))
            .map(|(p, m)| {
                let h = p[1][0] - p[0][0];
                let delta = (p[1][1] - p[0][1]) / h;
                [p[0][1], delta - h * (2.0 * m[0] + m[1]) / 6.0, m[0] / 2.0, (m[1] - m[0]) / (6.0 * h)]
            })
            .collect();
        let mut pieces: Vec<AccelPiece> = Vec::with_capacity(2 * local.len());
        for (p, c) in points.windows(2).zip(&local) {
            pieces.push(AccelPiece::poly(p[1][0] - p[0][0], c));
        }
        for (p, c) in points.windows(2).zip(&local).rev() {
            let h = p[1][0] - p[0][0];
            let mut mirrored = [0.0; 4];
            poly::reflect_into(c, h, &mut mirrored);
            mirrored.iter_mut().for_each(|v| *v = -*v);
            pieces.push(AccelPiece::poly(h, &mirrored));
        }
        let raw_half = half_displacement(&points, &local);
        let scale = 1.0 / (2.0 * raw_half);
        if raw_half.is_nan() || raw_half <= 0.0 || !scale.is_finite() {
            // Where the spline swings lowest on [0, 0.5] (it may dip below zero between points
            // even when every Y is positive, e.g. after a steep slope D at x = 0.5).
            let (f_min, x_min) = points
                .windows(2)
                .zip(&local)
                .flat_map(|(p, c)| {
                    let h = p[1][0] - p[0][0];
                    (0..=32).map(move |k| {
                        let t = h * k as f64 / 32.0;
                        (poly::eval(c, t), p[0][0] + t)
                    })
                })
                .fold((f64::INFINITY, 0.0), |a, b| if b.0 < a.0 { b } else { a });
            return Err(ServoError::NoRise {
                reason: format!(
                    "the acceleration spline through these points gives a net displacement F(1) = {:.4e}: \
                     it must be positive (the spline reaches f = {:.3} at x = {:.3}; move or add points so that \
                     f stays mostly positive on [0, 0.5])",
                    2.0 * raw_half,
                    f_min,
                    x_min
                ),
            });
        }
        let law = Law::from_accel_pieces(&pieces, EndCondition::Rest, "def_points")?;
        Ok(Self { points, end, d, local, scale, law })
    }

    /// The law through the built-in [`crate::default_points`] (natural start).
    pub fn default_law() -> Self {
        // The default points are valid by construction.
        Self::new(&crate::default_points(), SplineEnd::Natural).unwrap_or_else(|_| unreachable!())
    }

    /// The (checked) definition points.
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// The start condition.
    pub fn end(&self) -> SplineEnd {
        self.end
    }

    /// The slope `D = f'(0.5)` of the acceleration image (in units of Y per unit x).
    pub fn d(&self) -> f64 {
        self.d
    }

    /// The scale `1/F(1)` from the acceleration image `f` to the unit law: `u°'' = f · scale`.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The law of the core (unit stroke on `x ∈ [0, 1]`).
    pub fn law(&self) -> &Law {
        &self.law
    }

    /// Consumes the spline law and returns the law of the core.
    pub fn into_law(self) -> Law {
        self.law
    }

    /// The paper's spline coefficients `b_{1..4, j}` of `f_j(x) = b₁ + b₂x + b₃x² + b₄x³` in
    /// global `x`, one row per interval `[X_j, X_{j+1}]` of `[0, 0.5]` (not normalised: `f`
    /// passes through the definition points).
    pub fn spline_coefficients(&self) -> Vec<[f64; 4]> {
        self.points
            .windows(2)
            .zip(&self.local)
            .map(|(p, c)| {
                let g = poly::shift(c, p[0][0]);
                [g[0], g[1], g[2], g[3]]
            })
            .collect()
    }

    /// The acceleration image `f(x)` on `[0, 1]` (through the definition points; `x` clamped).
    pub fn accel_image(&self, x: f64) -> f64 {
        let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
        let (xx, sign) = if x <= 0.5 { (x, 1.0) } else { (1.0 - x, -1.0) };
        let j = self.points.partition_point(|p| p[0] <= xx).clamp(1, self.points.len() - 1) - 1;
        sign * poly::eval(&self.local[j], xx - self.points[j][0])
    }
}

/// `F(0.5) = ∫₀^0.5 ∫₀^x f` in closed form, interval by interval (the paper's section 4):
/// `F^I` and `F^II` are carried from the end of one interval to the start of the next.
fn half_displacement(points: &[[f64; 2]], local: &[[f64; 4]]) -> f64 {
    let (mut v, mut s) = (0.0, 0.0);
    for (p, c) in points.windows(2).zip(local) {
        let h = p[1][0] - p[0][0];
        // velocity poly v + ∫c, displacement s + v·t + ∫∫c
        let vel = [v, c[0], c[1] / 2.0, c[2] / 3.0, c[3] / 4.0];
        s += poly::integral(&vel, h);
        v = poly::eval(&vel, h);
    }
    s
}
