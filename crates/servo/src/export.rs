//! Export of the spline law's coefficients for a servo controller (text and JSON).

use crate::points::format_points;
use crate::{Result, ServoError, SplineLaw, poly};
use serde::{Deserialize, Serialize};

/// The polynomials of one interval of the unit law, in global `x ∈ [0, 1]`, lowest power first.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IntervalCoeffs {
    /// Start of the interval (fraction of the motion angle).
    pub x_start: f64,
    /// End of the interval.
    pub x_end: f64,
    /// Acceleration `u°''(x) = a₀ + a₁x + a₂x² + a₃x³` of the unit law.
    pub accel: [f64; 4],
    /// Velocity `u°'(x)`, degree 4.
    pub velocity: [f64; 5],
    /// Position `u°(x)`, degree 5.
    pub position: [f64; 6],
    /// The paper's spline coefficients `b₁…b₄` of the acceleration image `f_j(x)` (through the
    /// definition points, not normalised): `accel = scale · b`.
    pub b: [f64; 4],
}

/// Everything the controller needs: the definition points and the per-interval polynomials.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CoefficientExport {
    /// Format tag, `loomkin-servo-coefficients`.
    pub format: String,
    /// The definition points `[[X, Y], …]`.
    pub def_points: Vec<[f64; 2]>,
    /// Start condition of the spline (`natural` or `clamped`).
    pub end: String,
    /// Slope `D` of the acceleration image at `x = 0.5`.
    pub d: f64,
    /// Scale `1/F(1)` from the acceleration image to the unit law.
    pub scale: f64,
    /// The `2(N − 1)` intervals covering `[0, 1]`.
    pub intervals: Vec<IntervalCoeffs>,
}

impl CoefficientExport {
    /// Evaluates `(s, v, a)` of the exported polynomials at `x` (the interval containing `x`).
    pub fn eval(&self, x: f64) -> [f64; 3] {
        let i = self.intervals.partition_point(|iv| iv.x_start <= x).clamp(1, self.intervals.len()) - 1;
        let iv = &self.intervals[i];
        [poly::eval(&iv.position, x), poly::eval(&iv.velocity, x), poly::eval(&iv.accel, x)]
    }
}

/// The per-interval polynomials of the unit law in global `x` (see [`IntervalCoeffs`]).
///
/// The law's segments store the displacement in the local coordinate `t = x − x₀`; the position
/// polynomial in global `x` is its Taylor shift `s(x) = Σ p_k (x − x₀)^k` expanded by the binomial
/// theorem; velocity and acceleration are its derivatives.
pub fn export_coefficients(law: &SplineLaw) -> CoefficientExport {
    let scale = law.scale();
    let intervals = law
        .law()
        .segments()
        .iter()
        .map(|seg| {
            let pos = poly::shift(&seg.displacement_poly()[..6], seg.x0());
            let vel = poly::deriv(&pos);
            let acc = poly::deriv(&vel);
            IntervalCoeffs {
                x_start: seg.x0(),
                x_end: seg.x1(),
                accel: std::array::from_fn(|k| acc[k]),
                velocity: std::array::from_fn(|k| vel[k]),
                position: std::array::from_fn(|k| pos[k]),
                b: std::array::from_fn(|k| acc[k] / scale),
            }
        })
        .collect();
    CoefficientExport {
        format: "loomkin-servo-coefficients".into(),
        def_points: law.points().to_vec(),
        end: law.end().name().into(),
        d: law.d(),
        scale,
        intervals,
    }
}

/// The coefficient export as pretty JSON.
pub fn export_json(law: &SplineLaw) -> String {
    serde_json::to_string_pretty(&export_coefficients(law)).unwrap_or_default()
}

/// Reads a coefficient export back from JSON.
pub fn read_json(text: &str) -> Result<CoefficientExport> {
    serde_json::from_str(text).map_err(|e| ServoError::Parse {
        field: "coefficients".into(),
        text: e.to_string(),
        expected: "the JSON written by export_json".into(),
    })
}

/// The coefficients as documented text, one interval per line (the paper's export of `b_{k,j}`,
/// with the normalised acceleration, velocity and position polynomials added).
pub fn export_coeffs_text(law: &SplineLaw) -> String {
    let e = export_coefficients(law);
    let mut out = String::new();
    let lines = [
        "# loomkin servo: motion law from definition points (cubic-spline acceleration, Sivcak 2017)".to_string(),
        format!("# def_points (X:Y): {}", format_points(&e.def_points)),
        format!("# spline start condition: {}; slope at x = 0.5: D = {:e}", e.end, e.d),
        format!("# scale 1/F(1) from the acceleration image f to the unit law: {:e}", e.scale),
        "# x = fraction of the motion angle (0..1); unit stroke: u(0) = 0, u(1) = 1.".into(),
        "# Every polynomial is in GLOBAL x, lowest power first, valid on [x_start, x_end]:".into(),
        "#   f_j(x) = b1 + b2 x + b3 x^2 + b4 x^3        acceleration image through the points (paper's b_k,j)".into(),
        "#   a_j(x) = a0 + a1 x + a2 x^2 + a3 x^3        = scale * f_j(x), acceleration d2u/dx2".into(),
        "#   v_j(x) = v0 + ... + v4 x^4                  velocity du/dx".into(),
        "#   u_j(x) = u0 + ... + u5 x^5                  position".into(),
        "# For a stroke H (m) over a motion time T (s): position H*u, velocity H*v/T, acceleration H*a/T^2.".into(),
        "# columns: j x_start x_end b1 b2 b3 b4 a0 a1 a2 a3 v0 v1 v2 v3 v4 u0 u1 u2 u3 u4 u5".into(),
    ];
    for l in lines {
        out.push_str(&l);
        out.push('\n');
    }
    for (j, iv) in e.intervals.iter().enumerate() {
        let mut row = vec![(j + 1).to_string(), format!("{:e}", iv.x_start), format!("{:e}", iv.x_end)];
        for c in iv.b.iter().chain(&iv.accel).chain(&iv.velocity).chain(&iv.position) {
            row.push(format!("{c:e}"));
        }
        out.push_str(&row.join(" "));
        out.push('\n');
    }
    out
}

/// Reads the text written by [`export_coeffs_text`] back into intervals (comment lines skipped).
pub fn read_coeffs_text(text: &str) -> Result<Vec<IntervalCoeffs>> {
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let err = || ServoError::Parse {
            field: format!("coefficients line {}", n + 1),
            text: line.into(),
            expected: "j x_start x_end and 19 coefficients".into(),
        };
        let v: Vec<f64> =
            line.split_whitespace().skip(1).map(str::parse).collect::<Result<_, _>>().map_err(|_| err())?;
        if v.len() != 21 {
            return Err(err());
        }
        out.push(IntervalCoeffs {
            x_start: v[0],
            x_end: v[1],
            b: std::array::from_fn(|k| v[2 + k]),
            accel: std::array::from_fn(|k| v[6 + k]),
            velocity: std::array::from_fn(|k| v[10 + k]),
            position: std::array::from_fn(|k| v[15 + k]),
        });
    }
    Ok(out)
}
