//! One segment of a law: polynomial plus sinusoid acceleration, integrated in closed form.

use crate::Kinematics;
use serde::Serialize;

/// Highest degree of the displacement polynomial of a segment (acceleration degree + 2).
pub const MAX_DEGREE: usize = 7;
const NC: usize = MAX_DEGREE + 1;

/// A sinusoidal acceleration term `amp · sin(omega · t + phase)` in the local coordinate `t`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct Sine {
    /// Amplitude (units of acceleration).
    pub amp: f64,
    /// Angular frequency in the local coordinate (rad per unit of `t`); must be non-zero.
    pub omega: f64,
    /// Phase at `t = 0` (rad).
    pub phase: f64,
}

/// One segment `[x0, x1]` of a law.
///
/// In the local coordinate `t = x − x0` the acceleration is a polynomial plus a sinusoid,
///
/// $$ a(t) = \sum_{k=0}^{5} c_k t^k + A \sin(\omega t + \varphi), $$
///
/// and the displacement, integrated twice in closed form, is
///
/// $$ s(t) = \sum_{k=0}^{7} p_k t^k - \frac{A}{\omega^2} \sin(\omega t + \varphi). $$
///
/// Velocity and jerk follow by differentiation. Every quantity is exact and costs one
/// Horner pass plus at most one `sin_cos`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Segment {
    x0: f64,
    x1: f64,
    /// Displacement polynomial in `t`, lowest power first.
    p: [f64; NC],
    sine: Option<Sine>,
    /// Index of the highest non-zero coefficient of `p` (0 for a zero polynomial).
    deg: usize,
}

impl Segment {
    /// Integrates the acceleration `poly(t) + sine(t)` on `[x0, x1]` twice, with
    /// `s(0) = s0`, `v(0) = v0` at the segment start.
    ///
    /// `accel_poly` holds the acceleration polynomial in the local coordinate `t`, lowest power
    /// first, of degree at most 5. Returns `None` when the polynomial is too long, an input is not
    /// finite, `x1 ≤ x0`, or the sine has a zero frequency.
    pub fn from_accel(x0: f64, x1: f64, accel_poly: &[f64], sine: Option<Sine>, s0: f64, v0: f64) -> Option<Self> {
        if accel_poly.len() > NC - 2 || x1 <= x0 || x1.is_nan() || !x0.is_finite() || !x1.is_finite() {
            return None;
        }
        let finite = accel_poly.iter().all(|c| c.is_finite()) && s0.is_finite() && v0.is_finite();
        if !finite {
            return None;
        }
        let sine = match sine {
            Some(sn) if sn.amp == 0.0 => None,
            Some(sn) if sn.omega == 0.0 || !(sn.amp.is_finite() && sn.omega.is_finite() && sn.phase.is_finite()) => {
                return None;
            }
            other => other,
        };
        let mut p = [0.0; NC];
        for (k, c) in accel_poly.iter().enumerate() {
            p[k + 2] = c / ((k + 1) * (k + 2)) as f64;
        }
        p[0] = s0;
        p[1] = v0;
        if let Some(sn) = sine {
            p[0] += sn.amp / (sn.omega * sn.omega) * sn.phase.sin();
            p[1] += sn.amp / sn.omega * sn.phase.cos();
        }
        Some(Self { x0, x1, p, sine, deg: degree_of(&p) })
    }

    /// Start of the segment.
    pub fn x0(&self) -> f64 {
        self.x0
    }

    /// End of the segment.
    pub fn x1(&self) -> f64 {
        self.x1
    }

    /// Width `x1 − x0`.
    pub fn width(&self) -> f64 {
        self.x1 - self.x0
    }

    /// The displacement polynomial in the local coordinate, lowest power first (8 coefficients).
    pub fn displacement_poly(&self) -> &[f64; NC] {
        &self.p
    }

    /// The sinusoidal acceleration term, if any.
    pub fn sine(&self) -> Option<Sine> {
        self.sine
    }

    /// Degree of the displacement polynomial (0 for a zero polynomial).
    pub fn degree(&self) -> usize {
        self.deg
    }

    /// The same segment with every quantity multiplied by `k` (displacement scale).
    pub fn scaled(&self, k: f64) -> Self {
        let mut out = *self;
        for c in &mut out.p {
            *c *= k;
        }
        if let Some(sn) = &mut out.sine {
            sn.amp *= k;
        }
        out.deg = degree_of(&out.p);
        out
    }

    /// The same segment with `ds` added to its displacement.
    pub fn offset(&self, ds: f64) -> Self {
        let mut out = *self;
        out.p[0] += ds;
        out.deg = degree_of(&out.p);
        out
    }

    /// Kinematics at local coordinate `t` (not clamped to the segment).
    #[inline]
    pub fn eval_local(&self, t: f64) -> Kinematics {
        let mut k = poly_kin(&self.p, t);
        if let Some(sn) = self.sine {
            let (sin, cos) = (sn.omega * t + sn.phase).sin_cos();
            add_sine(&mut k, sn, sin, cos);
        }
        k
    }

    /// The derivative of order `order` of the displacement at local coordinate `t`
    /// (0 = s, 1 = v, 2 = a, 3 = j, 4 = snap, …).
    pub fn deriv_local(&self, order: usize, t: f64) -> f64 {
        let mut acc = 0.0;
        if order < NC {
            let f = &FALLING[order];
            for k in (order..NC).rev() {
                acc = acc * t + self.p[k] * f[k];
            }
        }
        if let Some(sn) = self.sine {
            // s_sin = -A/ω² sin(ωt+φ); its n-th derivative is -A ω^(n-2) sin(ωt+φ+nπ/2).
            let w = sn.omega;
            let arg = w * t + sn.phase + order as f64 * std::f64::consts::FRAC_PI_2;
            acc -= sn.amp * w.powi(order as i32 - 2) * arg.sin();
        }
        acc
    }

    /// Upper bounds of |s|, |v|, |a|, |j| and the next two derivatives over the segment, from the
    /// coefficients: `Σ |p_k·k!/(k−n)!| + |A|·|ω|^(n−2)` for order `n` (`|t| ≤ width ≤ 1`).
    pub(crate) fn derivative_bounds(&self) -> [f64; 6] {
        let mut out = [0.0; 6];
        for (order, o) in out.iter_mut().enumerate() {
            *o = (order..NC).map(|k| (self.p[k] * FALLING[order][k]).abs()).sum::<f64>();
            if let Some(sn) = self.sine {
                *o += sn.amp.abs() * sn.omega.abs().powi(order as i32 - 2);
            }
        }
        out
    }

    /// The magnitudes of the terms that make up s, v, a, j and the snap at local `t`:
    /// `Σ |p_k·k!/(k−n)!·t^(k−n)| + |A|·|ω|^(n−2)` for order `n`. Evaluated values carry rounding of a
    /// few ulps of these sums, however small the value itself is (a quarter sine's jerk at its flat
    /// end is `A·ω·cos(π/2)`).
    pub(crate) fn term_magnitudes(&self, t: f64) -> [f64; 5] {
        let mut out = [0.0; 5];
        for (order, o) in out.iter_mut().enumerate() {
            let mut tk = 1.0;
            for k in order..NC {
                *o += (self.p[k] * FALLING[order][k] * tk).abs();
                tk *= t.abs();
            }
            if let Some(sn) = self.sine {
                *o += sn.amp.abs() * sn.omega.abs().powi(order as i32 - 2);
            }
        }
        out
    }

    /// The derivatives of orders 0 to 5 of the displacement at local `t`, with one `sin_cos`.
    pub fn derivs_local(&self, t: f64) -> [f64; 6] {
        let mut out = [0.0; 6];
        for (order, o) in out.iter_mut().enumerate() {
            let f = &FALLING[order];
            let mut acc = 0.0;
            // From the true degree down: the skipped leading terms are exact zeros.
            for k in (order..=self.deg).rev() {
                acc = acc * t + self.p[k] * f[k];
            }
            *o = acc;
        }
        if let Some(sn) = self.sine {
            // n-th derivative of -A/ω² sin(θ) is -A ω^(n-2) sin(θ + nπ/2): cycle through sin, cos, −sin, −cos.
            let (sin, cos) = (sn.omega * t + sn.phase).sin_cos();
            let cycle = [sin, cos, -sin, -cos];
            let mut scale = -sn.amp / (sn.omega * sn.omega);
            for (order, o) in out.iter_mut().enumerate() {
                *o += scale * cycle[order % 4];
                scale *= sn.omega;
            }
        }
        out
    }

    /// The roots in `[0, width]` (local coordinate, ascending) of the derivative of order `order`
    /// (0 = s, 1 = v, 2 = a, 3 = j, 4 = snap), found as the metrics find them: sign changes bracketed
    /// on a grid sized to the degree and frequency, hidden close pairs included, refined by Newton.
    /// A root at an end of the segment is reported only where the value there is exactly zero.
    ///
    /// # Panics
    /// Never; orders above 4 are treated as 4.
    pub fn derivative_roots(&self, order: usize) -> Vec<f64> {
        let k = order.min(4);
        let n = crate::extrema::brackets(self, self.deg.saturating_sub(k));
        let mut out = Vec::new();
        loomkin_numeric::grid_roots(
            self.width(),
            n,
            |t| {
                let d = self.derivs_local(t);
                (d[k], d[k + 1])
            },
            |t| out.push(t),
        );
        out
    }

    /// Kinematics at global `x` (not clamped).
    #[inline]
    pub fn eval(&self, x: f64) -> Kinematics {
        self.eval_local(x - self.x0)
    }

    /// Kinematics at the start of the segment.
    pub fn start(&self) -> Kinematics {
        self.eval_local(0.0)
    }

    /// Kinematics at the end of the segment (left limit at `x1`).
    pub fn end(&self) -> Kinematics {
        self.eval_local(self.width())
    }

    /// Evaluates `n` points `t = t0 + i·h` in this segment into `out`.
    ///
    /// The polynomial is evaluated by Horner at its true degree (the kernel is chosen once per run,
    /// so a cycloidal segment costs a degree-1 pass, not degree 7); the results are bit-identical to
    /// [`Segment::eval_local`]'s polynomial part because the skipped leading terms are exact zeros.
    /// The sinusoid follows an exact angle-addition recurrence in four interleaved lanes (each lane
    /// rotates by 4h, so the four rotation chains run in parallel instead of one serial chain),
    /// re-seeded from `sin_cos` every [`RUN_CHUNK`] points so rounding cannot accumulate (at most
    /// 32 rotations per lane: the error stays within a few ulps of the direct `sin_cos`, checked
    /// over 10⁷ points in `tests/sampling.rs`). Four points are computed together, each quantity
    /// as a `[f64; 4]`, so that every step is one operation on four independent lanes (packed
    /// vector instructions; 2 lanes per instruction in the portable x86-64 build).
    pub(crate) fn eval_run(&self, t0: f64, h: f64, out: &mut [Kinematics]) {
        self.eval_run_from(t0, h, 0, out);
    }

    /// [`Segment::eval_run`] written with non-temporal stores where the target has them (for
    /// tables far larger than the caches; see `nontemporal`): the same values, bit for bit. The caller
    /// calls `nontemporal::fence` after the table's last run.
    pub(crate) fn eval_run_nontemporal(&self, t0: f64, h: f64, out: &mut [Kinematics]) {
        self.run_of_degree::<true>(t0, h, 0, out);
    }

    /// Points `first, first + 1, …` of the run `t = t0 + i·h` into `out`: a piece of a longer
    /// run, bit-identical to the same points of [`Segment::eval_run`] over the whole run as long
    /// as `first` is a multiple of [`RUN_CHUNK`] (the recurrence is re-seeded at the same points).
    pub(crate) fn eval_run_from(&self, t0: f64, h: f64, first: usize, out: &mut [Kinematics]) {
        debug_assert_eq!(first % RUN_CHUNK, 0);
        self.run_of_degree::<false>(t0, h, first, out);
    }

    /// The run with the kernel for the segment's degree and sinusoid, written with ordinary or
    /// non-temporal stores.
    #[inline(always)]
    fn run_of_degree<const NONTEMPORAL: bool>(&self, t0: f64, h: f64, first: usize, out: &mut [Kinematics]) {
        let c = DerivCoeffs::new(&self.p);
        match self.deg {
            0 | 1 => self.run::<1, NONTEMPORAL>(&c, t0, h, first, out),
            2 | 3 => self.run::<3, NONTEMPORAL>(&c, t0, h, first, out),
            4 | 5 => self.run::<5, NONTEMPORAL>(&c, t0, h, first, out),
            _ => self.run::<7, NONTEMPORAL>(&c, t0, h, first, out),
        }
    }

    #[inline(always)]
    fn run<const D: usize, const NONTEMPORAL: bool>(
        &self,
        c: &DerivCoeffs,
        t0: f64,
        h: f64,
        first: usize,
        out: &mut [Kinematics],
    ) {
        match self.sine {
            None => self.run_lanes::<D, false, NONTEMPORAL>(c, t0, h, first, out),
            Some(_) => self.run_lanes::<D, true, NONTEMPORAL>(c, t0, h, first, out),
        }
    }

    /// The run in groups of four points held lane by lane (`[f64; 4]` per quantity), so that each
    /// step is one operation on four independent values, which the compiler packs into vector
    /// instructions; the points are the same sums as [`Segment::eval_local`]'s, lane by lane.
    /// `NONTEMPORAL` writes the groups with non-temporal stores (`nontemporal::put4`).
    #[inline(always)]
    fn run_lanes<const D: usize, const SINE: bool, const NONTEMPORAL: bool>(
        &self,
        c: &DerivCoeffs,
        t0: f64,
        h: f64,
        first: usize,
        out: &mut [Kinematics],
    ) {
        // The sinusoid's factors as `add_sine` forms them, and rotations by h, 2h, 3h (lane seeds)
        // and 4h (each lane's step).
        let sn = self.sine.unwrap_or(Sine { amp: 0.0, omega: 1.0, phase: 0.0 });
        let w = sn.omega;
        let (ks, kv, ka, kj) = (sn.amp / (w * w), sn.amp / w, sn.amp, sn.amp * w);
        let rot = |m: f64| if SINE { (w * h * m).sin_cos() } else { (0.0, 1.0) };
        let (r1, r2, r3, (s4, c4)) = (rot(1.0), rot(2.0), rot(3.0), rot(4.0));
        // Without a sinusoid there is nothing to re-seed: one chunk.
        let chunk_len = if SINE { RUN_CHUNK } else { out.len().max(1) };
        for (ci, chunk) in out.chunks_mut(chunk_len).enumerate() {
            let i0 = first + ci * chunk_len;
            let (mut sin, mut cos) = ([0.0; 4], [0.0; 4]);
            if SINE {
                let (s0, c0) = (w * (t0 + i0 as f64 * h) + sn.phase).sin_cos();
                sin = [s0, s0 * r1.1 + c0 * r1.0, s0 * r2.1 + c0 * r2.0, s0 * r3.1 + c0 * r3.0];
                cos = [c0, c0 * r1.1 - s0 * r1.0, c0 * r2.1 - s0 * r2.0, c0 * r3.1 - s0 * r3.0];
            }
            // Point indices as floats: integers below 2^53, so `+ 4.0` is exact and equals the
            // conversion `(i + l) as f64`.
            let mut idx: [f64; 4] = std::array::from_fn(|l| (i0 + l) as f64);
            let i = i0 + (chunk.len() & !3);
            let mut quads = chunk.chunks_exact_mut(4);
            for quad in &mut quads {
                let t: [f64; 4] = std::array::from_fn(|l| t0 + idx[l] * h);
                let [mut s, mut v, mut a, mut j] = c.kin4::<D>(&t);
                if SINE {
                    for l in 0..4 {
                        s[l] -= ks * sin[l];
                        v[l] -= kv * cos[l];
                        a[l] += ka * sin[l];
                        j[l] += kj * cos[l];
                    }
                    for l in 0..4 {
                        let ns = sin[l] * c4 + cos[l] * s4;
                        cos[l] = cos[l] * c4 - sin[l] * s4;
                        sin[l] = ns;
                    }
                }
                if NONTEMPORAL {
                    crate::nontemporal::put4(quad, s, v, a, j);
                } else {
                    for l in 0..4 {
                        quad[l] = Kinematics { s: s[l], v: v[l], a: a[l], j: j[l] };
                    }
                }
                for l in 0..4 {
                    idx[l] += 4.0;
                }
            }
            for (l, k) in quads.into_remainder().iter_mut().enumerate() {
                let mut kin = c.kin::<D>(t0 + (i + l) as f64 * h);
                if SINE {
                    add_sine(&mut kin, sn, sin[l], cos[l]);
                }
                *k = kin;
            }
        }
    }
}

/// Points per re-seed of the sinusoid recurrence in [`Segment::eval_run`] (32 rotations per lane).
pub(crate) const RUN_CHUNK: usize = 128;

/// The coefficients of s, v, a and j of a displacement polynomial, lowest power first.
struct DerivCoeffs {
    s: [f64; NC],
    v: [f64; NC],
    a: [f64; NC],
    j: [f64; NC],
}

impl DerivCoeffs {
    fn new(p: &[f64; NC]) -> Self {
        let mut c = Self { s: *p, v: [0.0; NC], a: [0.0; NC], j: [0.0; NC] };
        for k in 0..NC {
            c.v[k] = if k + 1 < NC { FALLING[1][k + 1] * p[k + 1] } else { 0.0 };
            c.a[k] = if k + 2 < NC { FALLING[2][k + 2] * p[k + 2] } else { 0.0 };
            c.j[k] = if k + 3 < NC { FALLING[3][k + 3] * p[k + 3] } else { 0.0 };
        }
        c
    }

    /// s, v, a, j at four points `t` for a polynomial of degree at most `D`, lane by lane the same
    /// sums as [`DerivCoeffs::kin`].
    #[inline(always)]
    fn kin4<const D: usize>(&self, t: &[f64; 4]) -> [[f64; 4]; 4] {
        [
            horner4::<D, 0>(&self.s, t),
            horner4::<D, 1>(&self.v, t),
            horner4::<D, 2>(&self.a, t),
            horner4::<D, 3>(&self.j, t),
        ]
    }

    /// s, v, a, j at `t` for a polynomial of degree at most `D`.
    #[inline(always)]
    fn kin<const D: usize>(&self, t: f64) -> Kinematics {
        Kinematics {
            s: horner::<D>(&self.s, t),
            v: horner_below::<D, 1>(&self.v, t),
            a: horner_below::<D, 2>(&self.a, t),
            j: horner_below::<D, 3>(&self.j, t),
        }
    }
}

/// `Σ c_k t^k` for `k ≤ D`.
#[inline(always)]
fn horner<const D: usize>(c: &[f64; NC], t: f64) -> f64 {
    let mut acc = c[D];
    let mut k = D;
    while k > 0 {
        k -= 1;
        acc = acc * t + c[k];
    }
    acc
}

/// `Σ c_k t^k` for `k ≤ D − N` (zero when `N > D`).
#[inline(always)]
fn horner_below<const D: usize, const N: usize>(c: &[f64; NC], t: f64) -> f64 {
    if N > D {
        return 0.0;
    }
    let mut acc = c[D - N];
    let mut k = D - N;
    while k > 0 {
        k -= 1;
        acc = acc * t + c[k];
    }
    acc
}

/// [`horner_below`] at four points.
#[inline(always)]
fn horner4<const D: usize, const N: usize>(c: &[f64; NC], t: &[f64; 4]) -> [f64; 4] {
    if N > D {
        return [0.0; 4];
    }
    let mut acc = [c[D - N]; 4];
    let mut k = D - N;
    while k > 0 {
        k -= 1;
        for l in 0..4 {
            acc[l] = acc[l] * t[l] + c[k];
        }
    }
    acc
}

/// Index of the highest non-zero coefficient (0 for a zero polynomial).
fn degree_of(p: &[f64; NC]) -> usize {
    p.iter().rposition(|&c| c != 0.0).unwrap_or(0)
}

/// `FALLING[n][k] = k!/(k − n)!`, the factor of `t^(k−n)` in the n-th derivative of `t^k`.
const FALLING: [[f64; NC]; NC] = {
    let mut table = [[0.0; NC]; NC];
    let mut n = 0;
    while n < NC {
        let mut k = n;
        while k < NC {
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

/// s, v, a, j of the displacement polynomial `p` at `t`, one Horner pass for all four.
#[inline(always)]
fn poly_kin(p: &[f64; NC], t: f64) -> Kinematics {
    // Horner for s and its three derivatives in one pass over the coefficients. (Plain `*`/`+`:
    // without the `fma` target feature, `mul_add` is a slow library call.)
    let mut s = p[7];
    let mut v = 7.0 * p[7];
    let mut a = 42.0 * p[7];
    let mut j = 210.0 * p[7];
    s = s * t + p[6];
    v = v * t + 6.0 * p[6];
    a = a * t + 30.0 * p[6];
    j = j * t + 120.0 * p[6];
    s = s * t + p[5];
    v = v * t + 5.0 * p[5];
    a = a * t + 20.0 * p[5];
    j = j * t + 60.0 * p[5];
    s = s * t + p[4];
    v = v * t + 4.0 * p[4];
    a = a * t + 12.0 * p[4];
    j = j * t + 24.0 * p[4];
    s = s * t + p[3];
    v = v * t + 3.0 * p[3];
    a = a * t + 6.0 * p[3];
    j = j * t + 6.0 * p[3];
    s = s * t + p[2];
    v = v * t + 2.0 * p[2];
    a = a * t + 2.0 * p[2];
    s = s * t + p[1];
    v = v * t + p[1];
    s = s * t + p[0];
    Kinematics { s, v, a, j }
}

#[inline]
fn add_sine(k: &mut Kinematics, sn: Sine, sin: f64, cos: f64) {
    let w = sn.omega;
    k.s -= sn.amp / (w * w) * sin;
    k.v -= sn.amp / w * cos;
    k.a += sn.amp * sin;
    k.j += sn.amp * w * cos;
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn derivatives_agree_between_routes() {
        let seg = Segment::from_accel(
            0.2,
            0.7,
            &[1.0, -2.0, 3.0, 0.5, -0.25, 0.125],
            Some(Sine { amp: 2.0, omega: 5.0, phase: 0.3 }),
            0.1,
            -0.4,
        )
        .unwrap();
        for &t in &[0.0, 0.13, 0.37, 0.5] {
            let k = seg.eval_local(t);
            for order in 0..4 {
                assert_relative_eq!(seg.deriv_local(order, t), k.order(order), epsilon = 1e-12, max_relative = 1e-12);
            }
        }
        let k0 = seg.start();
        assert_relative_eq!(k0.s, 0.1, epsilon = 1e-15);
        assert_relative_eq!(k0.v, -0.4, epsilon = 1e-15);
    }

    #[test]
    fn run_matches_pointwise() {
        let seg =
            Segment::from_accel(0.0, 1.0, &[0.5], Some(Sine { amp: 1.0, omega: 40.0, phase: 0.1 }), 0.0, 0.0).unwrap();
        let mut out = vec![Kinematics::default(); 500];
        seg.eval_run(0.0, 0.002, &mut out);
        for (i, k) in out.iter().enumerate() {
            let e = seg.eval_local(i as f64 * 0.002);
            assert!((k.j - e.j).abs() < 1e-11 * 40.0, "{i}");
            assert!((k.s - e.s).abs() < 1e-13);
        }
    }

    #[test]
    fn run_kernels_of_every_degree_match_pointwise() {
        // Polynomial part: bit-identical to `eval_local` at every true degree (skipped leading terms
        // are exact zeros). Sinusoid: the lane recurrence within a few ulps of `sin_cos`, over runs that
        // are not multiples of the lane count or the re-seed chunk.
        for accel_len in 0..=6 {
            let poly: Vec<f64> = (0..accel_len).map(|k| 0.7 - 0.3 * k as f64).collect();
            for sine in [None, Some(Sine { amp: 3.0, omega: 17.0, phase: -0.4 })] {
                let seg = Segment::from_accel(0.1, 0.9, &poly, sine, 0.2, 0.05).unwrap();
                for n in [1, 3, 4, 5, 127, 128, 129, 1001] {
                    let h = 0.8 / n as f64;
                    let mut out = vec![Kinematics::default(); n];
                    seg.eval_run(0.0, h, &mut out);
                    for (i, k) in out.iter().enumerate() {
                        let e = seg.eval_local(i as f64 * h);
                        if sine.is_none() {
                            assert_eq!(*k, e, "degree {} n {n} i {i}", seg.degree());
                        } else {
                            for order in 0..4 {
                                let scale = 3.0 * 17f64.powi(order as i32 - 2) + e.order(order).abs();
                                assert!(
                                    (k.order(order) - e.order(order)).abs() < 1e-14 * scale,
                                    "n {n} i {i} order {order}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn rejects_bad_input() {
        assert!(Segment::from_accel(0.0, 0.0, &[1.0], None, 0.0, 0.0).is_none());
        assert!(Segment::from_accel(0.0, 1.0, &[f64::NAN], None, 0.0, 0.0).is_none());
        assert!(Segment::from_accel(0.0, 1.0, &[0.0; 7], None, 0.0, 0.0).is_none());
        let bad = Sine { amp: 1.0, omega: 0.0, phase: 0.0 };
        assert!(Segment::from_accel(0.0, 1.0, &[], Some(bad), 0.0, 0.0).is_none());
    }
}
