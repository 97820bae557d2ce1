//! Sizing: the least prime circle for a largest pressure angle.

use super::cam::tracks;
use super::design::{CamDesign, Closure, Follower};
use super::extremes::{Extremes, extremes};
use super::lift::Lift;
use super::track::Track;
use crate::{CamError, Result};

/// γ₀, the angle at the pivot between the line to the cam centre and the arm when the roller
/// centre lies on the prime circle: `R_p² = d² + L² − 2 d L cos γ₀`. The geometry must let the arm
/// swing on by the whole stroke `h` (rad) with the roller moving away from the centre, `γ₀ + h < π`.
pub(crate) fn initial_arm_angle(d: f64, l: f64, rp: f64, h: f64) -> Result<f64> {
    let (lo, hi) = ((d - l).abs(), reach(d, l, h));
    if !(rp > lo && rp < hi) {
        return Err(CamError::Usage {
            field: "prime_radius_mm".into(),
            reason: if hi <= lo {
                format!(
                    "an arm of {} mm about a pivot {} mm from the cam centre cannot swing through the stroke of {}° (it would fold past the line of centres)",
                    loomkin_units::compact(l),
                    loomkin_units::compact(d),
                    loomkin_units::compact(h.to_degrees())
                )
            } else {
                format!(
                    "{} mm: with arm {} mm and pivot {} mm the prime radius must lie between {} mm (|pivot − arm|) and {} mm (the arm must still swing {}° outward)",
                    loomkin_units::compact(rp),
                    loomkin_units::compact(l),
                    loomkin_units::compact(d),
                    loomkin_units::compact(lo),
                    loomkin_units::compact(hi),
                    loomkin_units::compact(h.to_degrees())
                )
            },
        });
    }
    Ok(((d * d + l * l - rp * rp) / (2.0 * d * l)).clamp(-1.0, 1.0).acos())
}

/// The largest prime radius from which an arm `l` about a pivot `d` can still swing out by `h`
/// (rad): `γ₀ + h < π` gives `R_p² < d² + L² + 2 d L cos h`.
fn reach(d: f64, l: f64, h: f64) -> f64 {
    if h >= std::f64::consts::PI { (d - l).abs() } else { (d * d + l * l + 2.0 * d * l * h.cos()).max(0.0).sqrt() }
}

/// Largest |pressure angle| (rad) over the tracks of a design at a prime radius.
pub(crate) fn max_pressure(lift: &Lift, tracks: &[Track]) -> f64 {
    let mut m: f64 = 0.0;
    for t in tracks {
        for sp in lift.spans() {
            let e = extremes(sp, |psi| {
                let p = t.jets(psi, lift.jet(sp.piece, psi)).phi;
                [p.v(), p.d(1), p.d(2)]
            });
            m = m.max(e.max.0.abs()).max(e.min.0.abs());
        }
    }
    m
}

/// The least prime radius (mm) for which the largest |pressure angle| is at most `a_deg`.
///
/// Translating roller follower: `|tan φ| = |s′ − ε| / (y + s)` with `y = √(R_p² − ε²)` (and, for the
/// counter-cam of a conjugate pair, `|s′ − ε| / (y + H − s)`), so `|φ| ≤ A` everywhere exactly when
/// `y ≥ max_ψ (|s′ − ε|/tan A − s)` (resp. `− (H − s)`): the maximum of a smooth function of ψ,
/// located at the roots of its derivative `±s″/tan A − s′`. Then `R_p = √(y² + ε²)`.
///
/// Oscillating follower: the largest pressure angle `F(R_p)` (itself located exactly) is scanned
/// upward from `|d − L|` and the first crossing of `A` bisected to the last bit.
pub(crate) fn least_prime_radius(lift: &Lift, design: &CamDesign, a_deg: f64) -> Result<f64> {
    let ta = a_deg.to_radians().tan();
    match design.follower {
        Follower::Translating { offset_mm: eps } => {
            let h = lift.stroke();
            let mut ext = Extremes::EMPTY;
            let conj = design.closure == Closure::Conjugate;
            for sp in lift.spans() {
                for sign in [1.0, -1.0] {
                    // counter-cam: distance y + H − s, i.e. the same with −s (and H added after).
                    for (k, shift) in [(1.0, 0.0), (-1.0, h)].into_iter().take(if conj { 2 } else { 1 }) {
                        ext.merge(
                            &extremes(sp, |psi| {
                                let s = lift.jet(sp.piece, psi);
                                [
                                    sign * (s.d(1) - eps) / ta - k * s.v() - shift,
                                    sign * s.d(2) / ta - k * s.d(1),
                                    sign * s.d(3) / ta - k * s.d(2),
                                ]
                            }),
                            0.0,
                        );
                    }
                }
            }
            let y = ext.max.0;
            if y.is_nan() || y <= 0.0 {
                return Err(CamError::Usage {
                    field: "max_pressure_deg".into(),
                    reason: format!(
                        "every prime radius above |offset| = {} mm keeps the pressure angle within {}°: give --prime-radius-mm instead",
                        loomkin_units::compact(eps.abs()),
                        loomkin_units::compact(a_deg)
                    ),
                });
            }
            Ok((y * y + eps * eps).sqrt())
        }
        Follower::Oscillating { arm_mm: l, pivot_mm: d } => {
            let h = lift.stroke();
            let (lo, hi) = ((d - l).abs(), reach(d, l, h));
            if hi <= lo {
                initial_arm_angle(d, l, 0.5 * (lo + hi), h)?;
            }
            let f = |rp: f64| -> Result<f64> { Ok(max_pressure(lift, &tracks(lift, design, rp)?)) };
            let target = a_deg.to_radians();
            const N: usize = 200;
            let mut prev = lo;
            let mut best = (f64::INFINITY, lo);
            let mut grid: Vec<(f64, f64)> = Vec::with_capacity(N);
            for i in 1..N {
                let rp = lo + (hi - lo) * i as f64 / N as f64;
                let v = f(rp)?;
                grid.push((rp, v));
                if v < best.0 {
                    best = (v, rp);
                }
                if v <= target {
                    if i == 1 {
                        // Already within A next to |d − L|: bisect towards it from the feasible side.
                        prev = lo + (hi - lo) * 1e-9;
                        if f(prev)? <= target {
                            return Ok(prev);
                        }
                    }
                    return Ok(loomkin_numeric::try_bisect_bracket(prev, rp, |m| -> Result<bool> {
                        Ok(f(m)? > target)
                    })?
                    .1);
                }
                prev = rp;
            }
            // No grid point within A: a minimum of F narrower than the grid may still dip below it.
            // Locate every grid minimum exactly (golden section on its two neighbouring intervals);
            // the least feasible radius is then the crossing between the grid point before it and it.
            for k in 1..grid.len().saturating_sub(1) {
                let ((a, va), (_, vm), (b, vb)) = (grid[k - 1], grid[k], grid[k + 1]);
                if vm > va || vm > vb {
                    continue;
                }
                let m = loomkin_numeric::golden_max(|rp| -f(rp).unwrap_or(f64::INFINITY), a, b);
                if -m.value < best.0 {
                    best = (-m.value, m.at);
                }
                if -m.value <= target {
                    let feasible = |rp: f64| f(rp).is_ok_and(|v| v <= target);
                    // The feasible end of the last bracket, not its midpoint: the radius returned
                    // must meet the target (the midpoint of adjacent doubles may be the other one).
                    return Ok(loomkin_numeric::bisect_bracket(a, m.at, |rp| !feasible(rp)).1);
                }
            }
            Err(CamError::Usage {
                field: "max_pressure_deg".into(),
                reason: format!(
                    "with arm {} mm and pivot {} mm no prime radius keeps the pressure angle within {}° (the least reached is {}° at a prime radius of {} mm): change --arm-mm or --pivot-mm",
                    loomkin_units::compact(l),
                    loomkin_units::compact(d),
                    loomkin_units::compact(a_deg),
                    loomkin_units::compact(best.0.to_degrees()),
                    loomkin_units::compact(best.1)
                ),
            })
        }
        Follower::Flat => Err(CamError::Usage {
            field: "max_pressure_deg".into(),
            reason:
                "a flat face perpendicular to its motion has a pressure angle of 0 everywhere: give --prime-radius-mm"
                    .into(),
        }),
    }
}
