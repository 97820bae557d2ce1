//! The closed-form response of one damped oscillator to polynomial-plus-sinusoid forcing.
//!
//! On one piece of the motion (time `t ∈ [0, T]` from the piece's start, s) the coordinate `y`
//! obeys
//!
//! $$ y'' + 2ζω_n y' + ω_n^2 y = q(t), \qquad q(t) = \sum_{k=0}^{7} q_k t^k + b\sin(Ωt + φ). $$
//!
//! The solution is the sum of
//! * the polynomial particular solution, by undetermined coefficients from the top power down:
//!   `ω²·y_k = q_k − 2ζω·(k+1)·y_{k+1} − (k+2)(k+1)·y_{k+2}`;
//! * the sinusoidal part: away from resonance the steady state `Im(b·e^{iφ}·H(Ω)·e^{iΩt})` with the
//!   transfer function `H(Ω) = 1/(ω² − Ω² + 2iζωΩ)`; where `|iΩ − λ₁|·T < 0.01` (λ₁ = −ζω + iω_d, the
//!   forcing close to a free mode) the zero-state response `Im(b·e^{iφ}·e[iΩ, λ₁, λ₂](t))`, the second
//!   divided difference of `z ↦ e^{zt}` at the forcing exponent and the two roots, computed with
//!   `φ₁(z) = (e^z − 1)/z` so that it stays exact through exact resonance (ζ = 0, Ω = ω_n, where it
//!   becomes the secular `t·cos` solution) — no division by a vanishing `ω² − Ω²`;
//! * the damped free vibration that matches the initial state:
//!   `y_h = e^{−ζωt}·[a·cos ω_d t + (b + ζω a)·sin(ω_d t)/ω_d]`, `ω_d = ω_n·√(1 − ζ²)`.

use crate::complex::{C, phi1};

/// The sinusoid's zero-state route is taken where `|iΩ − λ₁|·T` is below this: the steady-state route
/// then would cancel the particular and free parts, losing about `log₁₀(1/(|iΩ − λ₁|·T))` digits (≤ 2
/// above the switch, so ≥ 13 remain).
pub const ZERO_STATE_BELOW: f64 = 0.01;

/// Number of polynomial coefficients of a forcing (degree ≤ 7).
pub const NCOEF: usize = 8;

/// A sinusoidal term `amp·sin(omega·t + phase)` (omega in rad/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Harmonic {
    /// Amplitude (units of the quantity it is a term of).
    pub amp: f64,
    /// Circular frequency (rad/s), non-zero.
    pub omega: f64,
    /// Phase at t = 0 (rad).
    pub phase: f64,
}

impl Harmonic {
    /// The same function written with a positive frequency: `A·sin(−Ωt + φ) = −A·sin(Ωt − φ)`.
    pub fn positive(self) -> Self {
        if self.omega < 0.0 { Self { amp: -self.amp, omega: -self.omega, phase: -self.phase } } else { self }
    }
}

/// The right-hand side `q(t)` of one piece: a polynomial (lowest power first) plus an optional sinusoid.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Forcing {
    /// Polynomial coefficients `q_k` of `t^k`.
    pub poly: [f64; NCOEF],
    /// The sinusoidal term.
    pub sine: Option<Harmonic>,
}

impl Forcing {
    /// `q` and its first two time derivatives at `t`.
    pub fn derivs(&self, t: f64) -> [f64; 3] {
        let mut out = poly_derivs::<3>(&self.poly, t);
        if let Some(h) = self.sine {
            let (s, c) = (h.omega * t + h.phase).sin_cos();
            out[0] += h.amp * s;
            out[1] += h.amp * h.omega * c;
            out[2] -= h.amp * h.omega * h.omega * s;
        }
        out
    }
}

/// `FALLING[n][k] = k!/(k − n)!`, the factor of `t^(k−n)` in the n-th derivative of `t^k`.
const FALLING: [[f64; NCOEF]; 5] = {
    let mut table = [[0.0; NCOEF]; 5];
    let mut n = 0;
    while n < 5 {
        let mut k = n;
        while k < NCOEF {
            let mut f = 1.0;
            let mut m = 0;
            while m < n {
                f *= (k - m) as f64;
                m += 1;
            }
            table[n][k] = f;
            k += 1;
        }
        n += 1;
    }
    table
};

/// `p(t)` and its derivatives of order `0..N` (N ≤ 5) by one Horner pass per order.
#[inline]
pub(crate) fn poly_derivs<const N: usize>(p: &[f64; NCOEF], t: f64) -> [f64; N] {
    let mut out = [0.0; N];
    for (order, o) in out.iter_mut().enumerate() {
        let f = &FALLING[order];
        let mut acc = 0.0;
        for k in (order..NCOEF).rev() {
            acc = acc * t + p[k] * f[k];
        }
        *o = acc;
    }
    out
}

/// The roots in `[0, t_max]` of the free vibration `e^{−ζω_n t}·(A cos ω_d t + B sin ω_d t)` that starts
/// from `(u, u')`, at most `max` of them, ascending: `ω_d t = α + π/2 + kπ`, `α = atan2(B, A)`.
pub fn free_roots(osc: &Oscillator, u: f64, du: f64, t_max: f64, max: usize) -> impl Iterator<Item = f64> {
    let a = u;
    let b = (du + osc.zeta * osc.omega_n * u) / osc.omega_d;
    let alpha = b.atan2(a);
    let first = (alpha + std::f64::consts::FRAC_PI_2).rem_euclid(std::f64::consts::PI);
    let wd = osc.omega_d;
    let live = a != 0.0 || b != 0.0;
    (0..max).map(move |k| (first + k as f64 * std::f64::consts::PI) / wd).filter(move |&t| live && t <= t_max)
}

/// A damped linear oscillator `y'' + 2ζω_n·y' + ω_n²·y = q(t)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Oscillator {
    omega_n: f64,
    zeta: f64,
    omega_d: f64,
}

impl Oscillator {
    /// An oscillator of circular natural frequency `omega_n` (rad/s, > 0, finite) and damping ratio
    /// `zeta` (0 ≤ ζ < 1). The caller validates; here the values are only clamped into range so
    /// that nothing is ever NaN.
    ///
    /// Every ζ below 1 is kept as given, up to the largest double below 1 (1 − 2⁻⁵³), and
    /// `1 − ζ² = (1 − ζ)(1 + ζ)` is formed without cancellation (1 − ζ is exact there): ω_d, and
    /// with it the residual amplitude ∝ 1/ω_d, are then correct to a few ulps however close ζ is
    /// to 1. (ζ was clamped to 1 − 10⁻¹² while the follower accepts any ζ < 1, so every ζ above
    /// that was computed as 1 − 10⁻¹²: 95× too small a residual at ζ = 1 − 2⁻⁵³; and `1 − ζ·ζ`
    /// is off by up to ε/(1 − ζ²) relative, 1.5e-9 at ζ = 1 − 3·10⁻⁹.)
    pub fn new(omega_n: f64, zeta: f64) -> Self {
        let omega_n = if omega_n.is_finite() && omega_n > 0.0 { omega_n } else { 1.0 };
        let zeta = if zeta.is_finite() { zeta.clamp(0.0, 1.0 - f64::EPSILON / 2.0) } else { 0.0 };
        Self { omega_n, zeta, omega_d: omega_n * ((1.0 - zeta) * (1.0 + zeta)).sqrt() }
    }

    /// ω_n (rad/s).
    pub fn omega_n(&self) -> f64 {
        self.omega_n
    }

    /// ζ.
    pub fn zeta(&self) -> f64 {
        self.zeta
    }

    /// ω_d = ω_n·√(1 − ζ²) (rad/s).
    pub fn omega_d(&self) -> f64 {
        self.omega_d
    }

    /// The free vibration from `(y, y') = (a, b)` after time `t`: `(y(t), y'(t))`.
    #[inline]
    pub fn free(&self, a: f64, b: f64, t: f64) -> (f64, f64) {
        let (w, z, wd) = (self.omega_n, self.zeta, self.omega_d);
        let e = (-z * w * t).exp();
        let (s, c) = (wd * t).sin_cos();
        let sd = s / wd;
        (e * (a * c + (b + z * w * a) * sd), e * (b * c - (z * w * b + w * w * a) * sd))
    }

    /// The amplitude of the free vibration that starts from `(δ, δ')`:
    /// `A = √(δ² + ((δ' + ζω_nδ)/ω_d)²)` (the envelope value at the start). As ζ → 1 it grows like 1/ω_d
    /// while the motion becomes aperiodic.
    pub fn amplitude(&self, d: f64, dv: f64) -> f64 {
        d.hypot((dv + self.zeta * self.omega_n * d) / self.omega_d)
    }

    /// The exact solution on a piece of duration `duration` with forcing `f` from `(y, y') = (y0, v0)`.
    pub fn solve(&self, f: &Forcing, duration: f64, y0: f64, v0: f64) -> PieceSolution {
        let (w, z) = (self.omega_n, self.zeta);
        let w2 = w * w;
        let mut poly = [0.0; NCOEF];
        for k in (0..NCOEF).rev() {
            let y1 = if k + 1 < NCOEF { poly[k + 1] } else { 0.0 };
            let y2 = if k + 2 < NCOEF { poly[k + 2] } else { 0.0 };
            poly[k] = (f.poly[k] - 2.0 * z * w * (k + 1) as f64 * y1 - ((k + 2) * (k + 1)) as f64 * y2) / w2;
        }
        let sine = match f.sine.map(Harmonic::positive) {
            None => SinePart::None,
            Some(h) if h.amp == 0.0 => SinePart::None,
            Some(h) => {
                let bc = C::new(h.phase.cos(), h.phase.sin()).scale(h.amp);
                let mu = C::new(0.0, h.omega);
                let l1 = C::new(-z * w, self.omega_d);
                if (mu - l1).norm() * duration < ZERO_STATE_BELOW {
                    SinePart::ZeroState { bc, omega: h.omega }
                } else {
                    let den = C::new(w2 - h.omega * h.omega, 2.0 * z * w * h.omega);
                    SinePart::Steady { p: bc / den, omega: h.omega }
                }
            }
        };
        let mut sol = PieceSolution { osc: *self, forcing: *f, poly, sine, a: 0.0, b: 0.0, duration, series: None };
        let (s0, s1) = sol.sine_part(0.0);
        let degree = f.poly.iter().rposition(|&q| q != 0.0);
        if degree.is_some_and(|d| w * duration < series_below(d)) {
            // c_{n+2} = (q_n − 2ζω(n+1)c_{n+1} − ω²c_n)/((n+2)(n+1)), c₀, c₁ from the initial state.
            let mut c = [0.0; NSERIES];
            c[0] = y0 - s0;
            c[1] = v0 - s1;
            for n in 0..NSERIES - 2 {
                let q = if n < NCOEF { f.poly[n] } else { 0.0 };
                c[n + 2] = (q - 2.0 * z * w * (n + 1) as f64 * c[n + 1] - w2 * c[n]) / ((n + 2) * (n + 1)) as f64;
            }
            // The terms that matter on [0, T], for every derivative the piece is asked for (orders 0..5): term
            // n weighs |c_n|·n!/(n−k)!·T^{n−k} in the k-th; it is kept while above 1e-18 of the largest.
            // (The common factor T^{−k} cancels from the comparison.)
            let mut power = 1.0;
            let mut size: [f64; NSERIES] = std::array::from_fn(|n| {
                let v = c[n].abs() * power;
                power *= duration;
                v
            });
            let mut len = 2;
            for k in 0..5 {
                let largest = size.iter().fold(0.0, |m: f64, &v| m.max(v));
                if let Some(n) = size.iter().rposition(|&v| v > 1e-18 * largest) {
                    len = len.max(n + 1);
                }
                for (n, v) in size.iter_mut().enumerate() {
                    *v *= n.saturating_sub(k) as f64;
                }
            }
            sol.poly = [0.0; NCOEF];
            sol.series = Some(Series { c, len });
            return sol;
        }
        let p0 = poly_derivs::<2>(&sol.poly, 0.0);
        sol.a = y0 - p0[0] - s0;
        sol.b = v0 - p0[1] - s1;
        sol
    }
}

/// The sinusoidal part of a piece solution.
#[derive(Debug, Clone, Copy, PartialEq)]
enum SinePart {
    None,
    /// Steady state `Im(p·e^{iΩt})`.
    Steady {
        p: C,
        omega: f64,
    },
    /// Zero-state response `Im(bc·e[iΩ, λ₁, λ₂](t))` (near a free mode).
    ZeroState {
        bc: C,
        omega: f64,
    },
}

/// The exact response on one piece; see the module docs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PieceSolution {
    osc: Oscillator,
    forcing: Forcing,
    poly: [f64; NCOEF],
    sine: SinePart,
    /// Initial value of the free-vibration part.
    a: f64,
    /// Initial rate of the free-vibration part.
    b: f64,
    duration: f64,
    /// Short pieces (`ω_n·T` below [`series_below`] of the forcing's degree): the polynomial-forced part with its initial state as
    /// one power series in `t` (replaces `poly`, `a`, `b`).
    series: Option<Series>,
}

/// The power series `Σ c_n t^n` of a short piece, with the number of terms that matter on it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Series {
    c: [f64; NSERIES],
    len: usize,
}

/// Below this `ω_n·T` the polynomial part of a piece whose forcing polynomial has degree `d` is solved as a
/// power series. The particular polynomial holds terms of about `d!/(ω_nT)^{d+2}` times the response, which
/// the free vibration then cancels: with one switch at 0.5 for every degree, a poly4567 return (d = 5)
/// just above it lost seven digits (2e-9 of the response against DOP853, found by the random-cycle
/// property test). The switch is where that ratio is `1.25^{−(d+2)}` (below one):
/// `1.25·(d!)^{1/(d+2)}` = 1.25 (d = 0, 1) … 2.50 (d = 5) … 3.24 (d = 7). Below it the series' terms sum
/// to at most `e^{ω_nT} < 26` times the initial amplitude (about one digit) and its tail after [`NSERIES`]
/// terms is below `3.3³²/32! ≈ 1.6e-19`. A piece without polynomial forcing (a dwell) loses nothing on the
/// closed-form route and never takes the series.
pub fn series_below(degree: usize) -> f64 {
    let factorial: f64 = (1..=degree).map(|k| k as f64).product();
    1.25 * factorial.powf(1.0 / (degree + 2) as f64)
}

/// Number of power-series coefficients: the tail beyond is below `series_below(7)^NSERIES/NSERIES!`.
pub const NSERIES: usize = 32;

/// `Σ c_n t^n` (its first `len` terms) and its derivatives of orders `0..N`, in one Horner pass: after term
/// n, `d[k]` holds the k-th Taylor coefficient at `t` of the terms seen so far.
#[inline]
fn series_derivs<const N: usize>(s: &Series, t: f64) -> [f64; N] {
    let mut d = [0.0; N];
    for &c in s.c[..s.len].iter().rev() {
        for k in (1..N).rev() {
            d[k] = d[k] * t + d[k - 1];
        }
        if N > 0 {
            d[0] = d[0] * t + c;
        }
    }
    let mut factorial = 1.0;
    for (k, v) in d.iter_mut().enumerate().skip(1) {
        factorial *= k as f64;
        *v *= factorial;
    }
    d
}

impl PieceSolution {
    /// The piece's duration (s).
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// The oscillator.
    pub fn oscillator(&self) -> &Oscillator {
        &self.osc
    }

    /// The forcing.
    pub fn forcing(&self) -> &Forcing {
        &self.forcing
    }

    /// `(y, y')` of the sinusoidal part at `t`.
    #[inline]
    fn sine_part(&self, t: f64) -> (f64, f64) {
        match self.sine {
            SinePart::None => (0.0, 0.0),
            SinePart::Steady { p, omega } => {
                let e = p * C::new(0.0, omega * t).exp();
                (e.im, omega * e.re)
            }
            SinePart::ZeroState { bc, omega } => {
                let (d, dd) = self.divided_differences(omega, t);
                ((bc * d).im, (bc * dd).im)
            }
        }
    }

    /// `e[μ, λ₁, λ₂](t)` and its time derivative, μ = iΩ, λ₁,₂ = −ζω ± iω_d.
    fn divided_differences(&self, omega: f64, t: f64) -> (C, C) {
        let o = &self.osc;
        let mu = C::new(0.0, omega);
        let l1 = C::new(-o.zeta * o.omega_n, o.omega_d);
        let l2 = C::new(-o.zeta * o.omega_n, -o.omega_d);
        let (e_mu, e_l1, e_l2) = (C::new(0.0, omega * t).exp(), (l1.scale(t)).exp(), (l2.scale(t)).exp());
        // f[a, b] = e^{bt}·t·φ₁((a − b)t) — exact when a → b.
        let f_mu_l1 = e_l1 * phi1((mu - l1).scale(t)).scale(t);
        let f_l1_l2 = e_l2 * phi1((l1 - l2).scale(t)).scale(t);
        // |μ − λ₂| ≥ ω_n: the outer division is always well conditioned.
        let den = mu - l2;
        let d = (f_mu_l1 - f_l1_l2) / den;
        // g(z) = z·e^{zt}: g[a, b] = e^{at} + b·f[a, b].
        let g_mu_l1 = e_mu + l1 * f_mu_l1;
        let g_l1_l2 = e_l1 + l2 * f_l1_l2;
        (d, (g_mu_l1 - g_l1_l2) / den)
    }

    /// `y, y', y'', y''', y''''` at local time `t` (s).
    ///
    /// Away from resonance each part is differentiated in closed form (polynomial, `Im(p·(iΩ)^k·e^{iΩt})`,
    /// and the free part's coefficients mapped `(A, B) → (−ζωA + ω_dB, −ω_dA − ζωB)`): one `sin_cos` for
    /// the sinusoid and one `exp` plus `sin_cos` for the free vibration. On the zero-state route the
    /// higher derivatives follow from the equation itself.
    #[inline]
    pub fn derivs(&self, t: f64) -> [f64; 5] {
        self.derivs_n::<5>(t)
    }

    /// The derivatives of orders `0..N` (N ≤ 5) at local time `t` (s); see [`PieceSolution::derivs`].
    #[inline]
    pub fn derivs_n<const N: usize>(&self, t: f64) -> [f64; N] {
        let mut out = match &self.series {
            Some(c) => series_derivs::<N>(c, t),
            None => poly_derivs::<N>(&self.poly, t),
        };
        let o = &self.osc;
        // The free part e^{−ζωt}(A cos ω_d t + B sin ω_d t) (none on the series route: the series holds it).
        let (zw, wd) = (o.zeta * o.omega_n, o.omega_d);
        if self.series.is_none() {
            let (mut ca, mut cb) = (self.a, (self.b + zw * self.a) / wd);
            let e = (-zw * t).exp();
            let (sn, cs) = (wd * t).sin_cos();
            for d in out.iter_mut() {
                *d += e * (ca * cs + cb * sn);
                (ca, cb) = (-zw * ca + wd * cb, -wd * ca - zw * cb);
            }
        }
        match self.sine {
            SinePart::None => {}
            SinePart::Steady { p, omega } => {
                let (sn, cs) = (omega * t).sin_cos();
                let mut v = p * C::new(cs, sn);
                for d in out.iter_mut() {
                    *d += v.im;
                    v = C::new(-v.im * omega, v.re * omega);
                }
            }
            SinePart::ZeroState { bc, omega } => {
                let (dd0, dd1) = self.divided_differences(omega, t);
                let (y, v) = ((bc * dd0).im, (bc * dd1).im);
                // The zero-state part solves the equation with the sinusoid alone as forcing.
                let (s, c) = (omega * t).sin_cos();
                let q = C::new(c, s) * bc;
                let (q0, q1, q2) = (q.im, omega * q.re, -omega * omega * q.im);
                let w2 = o.omega_n * o.omega_n;
                let a = q0 - 2.0 * zw * v - w2 * y;
                let j = q1 - 2.0 * zw * a - w2 * v;
                let snap = q2 - 2.0 * zw * j - w2 * a;
                for (d, x) in out.iter_mut().zip([y, v, a, j, snap]) {
                    // (zip stops at N)
                    *d += x;
                }
            }
        }
        out
    }

    /// `(y, y')` at local time `t` (s).
    #[inline]
    pub fn state(&self, t: f64) -> (f64, f64) {
        let p = match &self.series {
            Some(c) => series_derivs::<2>(c, t),
            None => poly_derivs::<2>(&self.poly, t),
        };
        let (s0, s1) = self.sine_part(t);
        if self.series.is_some() {
            return (p[0] + s0, p[1] + s1);
        }
        let (h0, h1) = self.osc.free(self.a, self.b, t);
        (p[0] + s0 + h0, p[1] + s1 + h1)
    }

    /// When the forcing is constant (a dwell), `(y_eq, a, b)`: the solution is `y_eq` plus the free
    /// vibration from `(a, b)`.
    pub fn constant_plus_free(&self) -> Option<(f64, f64, f64)> {
        let constant = self.series.is_none()
            && self.forcing.poly[1..].iter().all(|&c| c == 0.0)
            && matches!(self.sine, SinePart::None);
        constant.then_some((self.poly[0], self.a, self.b))
    }

    /// `(y, y')` at the end of the piece.
    pub fn end(&self) -> (f64, f64) {
        self.state(self.duration)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Undamped resonance: y'' + ω²y = sin(ωt) from rest has y = (sin ωt − ωt·cos ωt)/(2ω²).
    #[test]
    fn exact_resonance_is_the_secular_solution() {
        let w = 7.0;
        let osc = Oscillator::new(w, 0.0);
        let f = Forcing { poly: [0.0; NCOEF], sine: Some(Harmonic { amp: 1.0, omega: w, phase: 0.0 }) };
        let sol = osc.solve(&f, 3.0, 0.0, 0.0);
        for &t in &[0.0, 0.1, 1.0, 2.7, 3.0] {
            let exact = ((w * t).sin() - w * t * (w * t).cos()) / (2.0 * w * w);
            let dexact = t * (w * t).sin() / 2.0;
            let (y, v) = sol.state(t);
            assert!((y - exact).abs() < 1e-15, "{t}: {y} vs {exact}");
            assert!((v - dexact).abs() < 1e-14, "{t}: {v} vs {dexact}");
        }
    }

    /// The steady and zero-state routes agree where both are well conditioned.
    #[test]
    fn the_two_sine_routes_agree() {
        let osc = Oscillator::new(10.0, 0.05);
        let f = Forcing {
            poly: [0.3, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            sine: Some(Harmonic { amp: 2.0, omega: 13.0, phase: 0.4 }),
        };
        // A short piece takes the zero-state route, a long one the steady route; compare at equal t.
        let short = osc.solve(&f, 0.002, 0.1, -0.2);
        let long = osc.solve(&f, 5.0, 0.1, -0.2);
        assert!(matches!(short.sine, SinePart::ZeroState { .. }));
        assert!(matches!(long.sine, SinePart::Steady { .. }));
        for &t in &[0.0, 0.0005, 0.0013, 0.002] {
            let (a, b) = (short.state(t), long.state(t));
            assert!((a.0 - b.0).abs() < 1e-15 && (a.1 - b.1).abs() < 1e-14, "{t}: {a:?} {b:?}");
        }
    }

    /// The power series (just below [`series_below`]) and the particular polynomial plus free vibration
    /// (just above) give the same response, for a degree-7 forcing at light and heavy damping.
    #[test]
    fn the_two_polynomial_routes_agree_at_the_switch() {
        let f = Forcing { poly: [0.0, 0.0, 420.0, -1680.0, 2100.0, -840.0, 30.0, -2.0], sine: None };
        for zeta in [0.0, 0.3, 0.95] {
            let osc = Oscillator::new(1.0, zeta);
            let below = osc.solve(&f, series_below(7) * (1.0 - 1e-9), 0.3, -0.7);
            let above = osc.solve(&f, series_below(7) * (1.0 + 1e-9), 0.3, -0.7);
            assert!(below.series.is_some() && above.series.is_none());
            let scale = (0..=64).map(|k| above.state(0.05 * k as f64).0.abs()).fold(0.0, f64::max);
            for k in 0..=64 {
                let t = 0.05 * k as f64;
                let (a, b) = (below.state(t), above.state(t));
                assert!(
                    (a.0 - b.0).abs() < 1e-13 * scale && (a.1 - b.1).abs() < 1e-13 * scale,
                    "ζ {zeta} t {t}: {a:?} vs {b:?}"
                );
            }
        }
    }

    /// The polynomial particular solution satisfies the equation identically, and the state's
    /// derivatives agree with central differences of the closed form.
    #[test]
    fn polynomial_particular_solves_the_equation() {
        let osc = Oscillator::new(30.0, 0.2);
        let f = Forcing { poly: [1.0, -2.0, 3.0, 0.5, -0.25, 0.125, 0.01, -0.003], sine: None };
        let sol = osc.solve(&f, 1.0, 0.01, 0.0);
        for &t in &[0.0, 0.3, 0.9] {
            let p = poly_derivs::<3>(&sol.poly, t);
            let q = f.derivs(t)[0];
            assert!((p[2] + 2.0 * 0.2 * 30.0 * p[1] + 900.0 * p[0] - q).abs() < 1e-13 * q.abs().max(1.0));
            let h = 1e-5;
            let d = sol.derivs(t + 0.05);
            let (yp, ym) = (sol.state(t + 0.05 + h), sol.state(t + 0.05 - h));
            assert!(((yp.0 - ym.0) / (2.0 * h) - d[1]).abs() < 1e-8);
            assert!(((yp.1 - ym.1) / (2.0 * h) - d[2]).abs() < 1e-7);
        }
    }

    /// The closed-form derivatives satisfy the equation and its two time derivatives, on both routes.
    #[test]
    fn derivatives_satisfy_the_equation() {
        let osc = Oscillator::new(40.0, 0.1);
        let f = Forcing {
            poly: [1.0, -2.0, 3.0, 0.5, -0.25, 0.125, 0.0, 0.0],
            sine: Some(Harmonic { amp: 50.0, omega: 25.0, phase: 0.3 }),
        };
        for dur in [1e-4, 2.0] {
            let sol = osc.solve(&f, dur, 0.02, -0.3);
            for k in 0..5 {
                let t = dur * k as f64 / 4.0;
                let d = sol.derivs(t);
                let q = f.derivs(t);
                for m in 0..3 {
                    let lhs = d[m + 2] + 2.0 * 0.1 * 40.0 * d[m + 1] + 1600.0 * d[m];
                    assert!(
                        (lhs - q[m]).abs() < 1e-11 * (1.0 + q[m].abs()),
                        "T {dur} t {t} order {m}: {lhs} vs {}",
                        q[m]
                    );
                }
            }
        }
    }
}
