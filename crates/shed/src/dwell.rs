//! Where a closed-form law crosses a level, found by root finding on the closed form: each segment
//! is cut at the roots of its velocity (so `s` is monotone between the cuts), and a crossing inside
//! a monotone piece is refined by safeguarded Newton iteration (`s' = v` is known exactly).

use loomkin_laws::{Law, Segment};
use loomkin_numeric::refine_root;

/// Root of `g` in `[lo, hi]` where `g(lo)` and `g(hi)` have opposite signs; `dg` is its
/// derivative (the core's safeguarded Newton, [`loomkin_numeric::refine_root`]).
pub(crate) fn refine(lo: f64, hi: f64, g: impl Fn(f64) -> f64, dg: impl Fn(f64) -> f64) -> f64 {
    refine_root(lo, hi, g(lo) < 0.0, |t| (g(t), dg(t)))
}

/// Cut points of a segment (local coordinate) between which `s` is monotone: the ends and the
/// roots of `v` (the core's root finder on the closed form).
fn monotone_cuts(seg: &Segment) -> Vec<f64> {
    let mut cuts = vec![0.0];
    cuts.extend(seg.derivative_roots(1).into_iter().filter(|&t| t > 0.0 && t < seg.width()));
    cuts.push(seg.width());
    cuts
}

/// Where the law enters the band `|s − 1| ≤ band` for the last time (`x_arrive`) and leaves the
/// band `|s| ≤ band` for the first time (`x_depart`), in one pass over the monotone pieces.
///
/// Arrival is an upward crossing of `s = 1 − band` or a downward crossing of `s = 1 + band` (a law
/// that overshoots its end); departure an upward crossing of `s = band` or a downward crossing of
/// `s = −band` (a law that first undershoots). A monotone piece holds at most one crossing of each
/// kind, so the last piece with an arrival and the first with a departure decide, and only those
/// two roots are refined.
pub(crate) fn band_crossings(law: &Law, band: f64) -> (Option<f64>, Option<f64>) {
    // (segment, local bracket, level) of the last arrival and the first departure.
    let mut arrive: Option<(&Segment, f64, f64, f64)> = None;
    let mut depart: Option<(&Segment, f64, f64, f64)> = None;
    let crossed = |sa: f64, sb: f64, level: f64| (sa < level && sb >= level) || (sa > level && sb <= level);
    for seg in law.segments() {
        let cuts = monotone_cuts(seg);
        let mut sa = seg.deriv_local(0, cuts[0]);
        for c in cuts.windows(2) {
            let sb = seg.deriv_local(0, c[1]);
            let up = sb > sa;
            let (arrive_level, depart_level) = if up { (1.0 - band, band) } else { (1.0 + band, -band) };
            if crossed(sa, sb, arrive_level) {
                arrive = Some((seg, c[0], c[1], arrive_level));
            }
            if depart.is_none() && crossed(sa, sb, depart_level) {
                depart = Some((seg, c[0], c[1], depart_level));
            }
            sa = sb;
        }
    }
    let root = |(seg, a, b, level): (&Segment, f64, f64, f64)| {
        let g = |t: f64| seg.deriv_local(0, t) - level;
        let t = if g(b) == 0.0 { b } else { refine(a, b, g, |t| seg.deriv_local(1, t)) };
        seg.x0() + t
    };
    (arrive.map(root), depart.map(root))
}

/// End of the leading stretch over which the law stands exactly still at `s = 0` (segments of zero
/// acceleration entered at rest), as a fraction of the motion.
pub(crate) fn lead(law: &Law) -> f64 {
    let mut x = 0.0;
    for seg in law.segments() {
        let p = seg.displacement_poly();
        if seg.sine().is_none() && p.iter().all(|&c| c == 0.0) {
            x = seg.x1();
        } else {
            break;
        }
    }
    x
}

/// Start of the trailing stretch over which the law stands still at `s = 1` (within rounding).
pub(crate) fn tail(law: &Law) -> f64 {
    let mut x = 1.0;
    for seg in law.segments().iter().rev() {
        let p = seg.displacement_poly();
        let still = seg.sine().is_none()
            && p[2..].iter().all(|&c| c == 0.0)
            && p[1].abs() * seg.width() <= 1e-12
            && (p[0] - 1.0).abs() <= 1e-9;
        if still {
            x = seg.x0();
        } else {
            break;
        }
    }
    x
}
