//! The follower's lift against the cam angle: the motion of a closed cycle, re-expressed per radian
//! of cam rotation and measured from its lowest point.

use super::extremes::{Extremes, extremes};
use super::jet::{Jet, N};
use crate::table::Motion;
use crate::{CamError, Result};
use loomkin_laws::StrokeUnit;

/// The lift `s(ψ)` of a closed motion against the cam angle `ψ` (rad), in mm (translating) or rad
/// (swinging), with `s ≥ 0` and `min s = 0`.
///
/// The cam turns once per cycle period `P` (deg): `ψ = 2π θ / P` for the main-shaft angle `θ` (deg),
/// so `dᵏs/dψᵏ = Y⁽ᵏ⁾(θ) · (P/2π)ᵏ` with `Y⁽ᵏ⁾` the motion's derivatives per degree.
#[derive(Debug, Clone)]
pub struct Lift {
    motion: Motion,
    /// dθ/dψ, deg per rad of cam.
    c: f64,
    /// Slave unit → mm or rad.
    to_unit: f64,
    /// Lowest position (slave unit).
    y_min: f64,
    /// Stroke `max s` (mm or rad).
    stroke: f64,
    /// Where the lift is least and greatest (main-shaft deg).
    pub(crate) min_at_deg: f64,
    pub(crate) max_at_deg: f64,
}

/// One smooth span of the lift: `[a, b]` in ψ (rad), the motion piece it comes from.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Span {
    pub a: f64,
    pub b: f64,
    pub piece: usize,
    pub dwell: bool,
    /// Grid intervals for bracketing roots on this span.
    pub grid: usize,
}

impl Lift {
    /// The lift of a closed motion; fails (naming `segment`) when the motion does not return.
    pub fn new(motion: &Motion) -> Result<Self> {
        let period = motion.end_deg() - motion.start_deg();
        let to_unit = match motion.unit() {
            StrokeUnit::Mm => 1.0,
            StrokeUnit::Deg => std::f64::consts::PI / 180.0,
        };
        let mut lift = Self {
            motion: motion.clone(),
            c: period / std::f64::consts::TAU,
            to_unit,
            y_min: 0.0,
            stroke: 0.0,
            min_at_deg: 0.0,
            max_at_deg: 0.0,
        };
        let last = motion.pieces().len() - 1;
        let y0 = motion.pieces()[0].eval(motion.start_deg())[0];
        let y1 = motion.pieces()[last].eval(motion.end_deg())[0];
        if (y1 - y0).abs() > 1e-9 * motion.stroke().max(1e-12) {
            return Err(CamError::Law {
                field: "segment".into(),
                reason: format!(
                    "the motion ends {} {} from where it starts: a cam needs a cycle that closes (rises and returns balance over the period)",
                    loomkin_units::compact(y1 - y0),
                    if motion.unit() == StrokeUnit::Mm { "mm" } else { "deg" }
                ),
            });
        }
        let mut ext = Extremes::EMPTY;
        for sp in lift.spans() {
            ext.merge(
                &extremes(sp, |psi| {
                    let j = lift.jet(sp.piece, psi);
                    [j.v(), j.d(1), j.d(2)]
                }),
                0.0,
            );
        }
        lift.y_min = ext.min.0 / to_unit;
        lift.stroke = ext.max.0 - ext.min.0;
        lift.min_at_deg = lift.deg(ext.min.1);
        lift.max_at_deg = lift.deg(ext.max.1);
        if lift.stroke.is_nan() || lift.stroke <= 0.0 {
            return Err(CamError::Law { field: "segment".into(), reason: "the follower never moves".into() });
        }
        Ok(lift)
    }

    /// The stroke `max s − min s` (mm or rad).
    pub fn stroke(&self) -> f64 {
        self.stroke
    }

    /// The motion's slave unit.
    pub fn unit(&self) -> StrokeUnit {
        self.motion.unit()
    }

    /// Main-shaft angle (deg) of a cam angle (rad).
    pub fn deg(&self, psi: f64) -> f64 {
        psi * self.c
    }

    /// Cam angle (rad) of a main-shaft angle (deg).
    pub fn psi(&self, deg: f64) -> f64 {
        deg / self.c
    }

    /// First and last cam angle of the cycle (rad).
    pub fn range(&self) -> (f64, f64) {
        (self.psi(self.motion.start_deg()), self.psi(self.motion.end_deg()))
    }

    /// The main-shaft angles of the motion's joints (deg), both ends included.
    pub fn joints_deg(&self) -> Vec<f64> {
        self.motion.joints()
    }

    /// The piece holding main-shaft angle `deg`.
    pub fn piece_at(&self, deg: f64) -> usize {
        self.motion.piece_index(deg)
    }

    /// The lift and its derivatives per radian of cam as a jet, by the formula of piece `piece`.
    pub fn jet(&self, piece: usize, psi: f64) -> Jet {
        let d = self.motion.pieces()[piece].derivs(self.deg(psi));
        let mut out = [0.0; N];
        let mut k_c = self.to_unit;
        for k in 0..N {
            out[k] = d[k] * k_c;
            k_c *= self.c;
        }
        out[0] -= self.y_min * self.to_unit;
        Jet::from_derivs(out)
    }

    /// The lift jet at any cam angle (the right-hand piece at a joint).
    pub fn jet_at(&self, psi: f64) -> Jet {
        self.jet(self.piece_at(self.deg(psi)), psi)
    }

    /// The smooth spans of the lift, with grid sizes for root bracketing.
    pub(crate) fn spans(&self) -> Vec<Span> {
        self.motion
            .pieces()
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let (a, b) = (self.psi(p.start_deg), self.psi(p.end_deg));
                // Polynomial degree and sine half-periods of the law, plus the cam's own rotation
                // (sines and cosines of ψ in the geometry): about 16 grid points per radian of cam.
                let grid = 8 + 2 * p.wiggles(p.start_deg, p.end_deg) + (16.0 * (b - a)).ceil() as usize;
                Span { a, b, piece: i, dwell: p.is_dwell(), grid }
            })
            .collect()
    }
}
