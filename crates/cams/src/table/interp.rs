//! What a controller runs between two table points: one quintic per interval.

/// One interval of a re-interpolated table: the slave position as a quintic in the normalised
/// master coordinate `u = (X − X₀)/(X₁ − X₀) ∈ [0, 1]`,
///
/// $$ Y(u) = \sum_{k=0}^{5} b_k\,u^k, $$
///
/// with every `b_k` in the slave unit (mm or deg). Derivatives with respect to the master angle
/// `X` (deg) follow by the chain rule, `dᵏY/dXᵏ = Y⁽ᵏ⁾(u) / (X₁ − X₀)ᵏ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    /// Master angle at the start (deg).
    pub start_deg: f64,
    /// Master angle at the end (deg).
    pub end_deg: f64,
    /// Coefficients `b₀…b₅` in the slave unit, lowest power first.
    pub b: [f64; 6],
}

impl Interval {
    /// The quintic Hermite interval through `(Y, V, A)` at both ends (`V = dY/dX`, `A = d²Y/dX²`
    /// in slave units per degree and per degree²): the fifth-degree polynomial a controller puts
    /// between two XYVA points.
    ///
    /// In `u`, the end derivatives are `Y'(0) = V₀h`, `Y''(0) = A₀h²` (and likewise at `u = 1`),
    /// `h = X₁ − X₀`. With `Δ = Y₁ − (Y₀ + V₀h + A₀h²/2)`, `Δv = (V₁ − V₀ − A₀h)h`,
    /// `Δa = (A₁ − A₀)h²`:
    /// `b₃ = 10Δ − 4Δv + Δa/2`, `b₄ = −15Δ + 7Δv − Δa`, `b₅ = 6Δ − 3Δv + Δa/2`.
    pub fn hermite(start_deg: f64, end_deg: f64, y0: [f64; 3], y1: [f64; 3]) -> Self {
        let h = end_deg - start_deg;
        let (v0, a0) = (y0[1] * h, y0[2] * h * h);
        let (v1, a1) = (y1[1] * h, y1[2] * h * h);
        let d = y1[0] - (y0[0] + v0 + 0.5 * a0);
        let dv = v1 - (v0 + a0);
        let da = a1 - a0;
        let b = [
            y0[0],
            v0,
            0.5 * a0,
            10.0 * d - 4.0 * dv + 0.5 * da,
            -15.0 * d + 7.0 * dv - da,
            6.0 * d - 3.0 * dv + 0.5 * da,
        ];
        Self { start_deg, end_deg, b }
    }

    /// The straight line from `Y₀` at `X₀` to `Y₁` at `X₁`: a controller that joins positions
    /// only by lines (`b₀ = Y₀`, `b₁ = Y₁ − Y₀`, the rest zero).
    pub fn linear(start_deg: f64, end_deg: f64, y0: f64, y1: f64) -> Self {
        Self { start_deg, end_deg, b: [y0, y1 - y0, 0.0, 0.0, 0.0, 0.0] }
    }

    /// The cubic from `Y₀` at `X₀` to `Y₁` at `X₁` with second derivatives `M₀`, `M₁` (slave unit
    /// per deg²) at its ends, one interval of a cubic spline through positions: in `u`,
    /// `b₀ = Y₀`, `b₁ = Y₁ − Y₀ − (2M₀ + M₁)h²/6`, `b₂ = M₀h²/2`, `b₃ = (M₁ − M₀)h²/6`.
    pub fn cubic(start_deg: f64, end_deg: f64, y0: f64, y1: f64, m0: f64, m1: f64) -> Self {
        let h2 = (end_deg - start_deg).powi(2);
        let b = [y0, y1 - y0 - (2.0 * m0 + m1) * h2 / 6.0, 0.5 * m0 * h2, (m1 - m0) * h2 / 6.0, 0.0, 0.0];
        Self { start_deg, end_deg, b }
    }

    /// Width `X₁ − X₀` (deg).
    pub fn width(&self) -> f64 {
        self.end_deg - self.start_deg
    }

    /// The derivatives of orders 0 to 5 of `Y` with respect to the master angle at `X₀ + τ`
    /// (`τ` in degrees from the interval's start).
    pub fn derivs(&self, tau: f64) -> [f64; 6] {
        let h = self.width();
        let u = tau / h;
        let b = &self.b;
        let du = [
            b[0] + u * (b[1] + u * (b[2] + u * (b[3] + u * (b[4] + u * b[5])))),
            b[1] + u * (2.0 * b[2] + u * (3.0 * b[3] + u * (4.0 * b[4] + u * 5.0 * b[5]))),
            2.0 * b[2] + u * (6.0 * b[3] + u * (12.0 * b[4] + u * 20.0 * b[5])),
            6.0 * b[3] + u * (24.0 * b[4] + u * 60.0 * b[5]),
            24.0 * b[4] + u * 120.0 * b[5],
            120.0 * b[5],
        ];
        let mut out = [0.0; 6];
        let mut scale = 1.0;
        for k in 0..6 {
            out[k] = du[k] * scale;
            scale /= h;
        }
        out
    }

    /// `[Y, V, A, J]` at master angle `deg`.
    pub fn eval(&self, deg: f64) -> [f64; 4] {
        let d = self.derivs(deg - self.start_deg);
        [d[0], d[1], d[2], d[3]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite_matches_its_end_conditions_and_finite_differences() {
        let iv = Interval::hermite(10.0, 12.5, [1.0, 0.3, -0.2], [1.7, -0.1, 0.4]);
        let e0 = iv.eval(10.0);
        let e1 = iv.eval(12.5);
        for (got, want) in [(e0[0], 1.0), (e0[1], 0.3), (e0[2], -0.2), (e1[0], 1.7), (e1[1], -0.1), (e1[2], 0.4)] {
            assert!((got - want).abs() < 1e-13, "{got} vs {want}");
        }
        let h = 1e-4;
        let lin = Interval::linear(1.0, 3.0, 2.0, 5.0);
        assert_eq!((lin.eval(2.0), lin.eval(3.0)[0]), ([3.5, 1.5, 0.0, 0.0], 5.0));
        // A cubic through its end values with the given end curvatures: against finite differences.
        let c = Interval::cubic(2.0, 4.5, 1.0, -0.5, 0.3, -0.7);
        let (c0, c1) = (c.eval(2.0), c.eval(4.5));
        for (got, want) in [(c0[0], 1.0), (c1[0], -0.5), (c0[2], 0.3), (c1[2], -0.7)] {
            assert!((got - want).abs() < 1e-13, "{got} vs {want}");
        }
        let fd = (c.eval(3.0 + h)[0] - 2.0 * c.eval(3.0)[0] + c.eval(3.0 - h)[0]) / (h * h);
        assert!((fd - c.eval(3.0)[2]).abs() < 1e-6, "{fd}");
        for x in [10.3, 11.1, 12.2] {
            let (m, p) = (iv.eval(x - h), iv.eval(x + h));
            let c = iv.eval(x);
            for k in 0..3 {
                let fd = (p[k] - m[k]) / (2.0 * h);
                assert!((fd - c[k + 1]).abs() < 1e-7 * (1.0 + c[k + 1].abs()), "order {k} at {x}");
            }
        }
    }
}
