//! The slave motion against the master angle, in the slave units of a cycle, as smooth pieces.

use crate::profile::Jet;
use crate::{CamError, Result};
use loomkin_laws::{Cycle, Law, Segment, StrokeUnit};
use loomkin_units::{Field, Range};
use std::sync::Arc;

/// One smooth piece of a slave motion: a dwell, or one segment of a law inside a rise or return.
///
/// On a moving piece the law's segment is scaled to the slave: with `x = (X − X₀)/B` the fraction
/// of the rise or return angle `B` (deg) that starts at master angle `X₀`, `s(x)` the normalised
/// law, `Y₀` the position at the start and `H` the signed stroke (slave units),
///
/// $$ Y = Y_0 + H\,s(x),\quad V = \frac{dY}{dX} = \frac{H s'(x)}{B},\quad
///    A = \frac{H s''(x)}{B^2},\quad J = \frac{H s'''(x)}{B^3}. $$
#[derive(Debug, Clone, PartialEq)]
pub struct Piece {
    /// Master angle where the piece starts (deg).
    pub start_deg: f64,
    /// Master angle where the piece ends (deg).
    pub end_deg: f64,
    shape: PieceShape,
    /// The slave as another coordinate of the law's position ([`Motion::mapped`]).
    map: Option<SharedMap>,
}

/// A smooth, monotone map from a motion's slave position to the coordinate a controller drives
/// (a frame's height to its motor's angle through a crank and lever): the series of the position
/// in the master angle (its derivatives of orders 0 … 5, [`Jet`]) to the series of the coordinate.
pub trait SlaveMap: Send + Sync + std::fmt::Debug {
    /// The coordinate's series for the position's series (orders 0 … 5, exact to rounding).
    fn map(&self, position: Jet) -> Jet;
}

/// A shared [`SlaveMap`]; two are equal when they are the same map.
#[derive(Debug, Clone)]
struct SharedMap(Arc<dyn SlaveMap>);

impl PartialEq for SharedMap {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

#[derive(Debug, Clone, PartialEq)]
enum PieceShape {
    Dwell(f64),
    Moving { seg: Segment, law_start_deg: f64, law_len_deg: f64, base: f64, stroke: f64 },
}

impl Piece {
    /// `[Y, V, A, J]` at master angle `deg` by this piece's formula (also a little outside it, so
    /// that a point on a joint can be evaluated from either side).
    pub fn eval(&self, deg: f64) -> [f64; 4] {
        let d = self.derivs(deg);
        [d[0], d[1], d[2], d[3]]
    }

    /// The derivatives of orders 0 to 5 of `Y` with respect to the master angle (deg) at `deg`.
    pub fn derivs(&self, deg: f64) -> [f64; 6] {
        let d = self.position_derivs(deg);
        match &self.map {
            None => d,
            Some(m) => {
                let j = m.0.map(Jet::from_derivs(d));
                std::array::from_fn(|k| j.d(k))
            }
        }
    }

    /// The derivatives of the law's position (before a [`SlaveMap`]).
    fn position_derivs(&self, deg: f64) -> [f64; 6] {
        match &self.shape {
            PieceShape::Dwell(y) => [*y, 0.0, 0.0, 0.0, 0.0, 0.0],
            PieceShape::Moving { seg, law_start_deg, law_len_deg, base, stroke } => {
                let t = (deg - law_start_deg) / law_len_deg - seg.x0();
                let d = seg.derivs_local(t);
                let mut out = [0.0; 6];
                let mut scale = *stroke;
                for k in 0..6 {
                    out[k] = scale * d[k];
                    scale /= law_len_deg;
                }
                out[0] += base;
                out
            }
        }
    }

    /// Whether the slave stands still on this piece.
    pub fn is_dwell(&self) -> bool {
        matches!(self.shape, PieceShape::Dwell(_))
    }

    /// A bound on the number of extrema a function built from this piece and a quintic can have
    /// per unit of the piece (used to size root brackets): the polynomial degree and, for a
    /// sinusoidal segment, its half-periods over the piece.
    pub(crate) fn wiggles(&self, from_deg: f64, to_deg: f64) -> usize {
        match &self.shape {
            PieceShape::Dwell(_) => 0,
            PieceShape::Moving { seg, law_len_deg, .. } => {
                let half_periods = |s: loomkin_laws::Sine| {
                    (s.omega.abs() * (to_deg - from_deg) / law_len_deg / std::f64::consts::PI).ceil()
                };
                let osc = seg.sine().map_or(0.0, half_periods);
                seg.degree() + 3 * osc as usize
            }
        }
    }
}

/// A slave motion over a master range: contiguous smooth pieces, in the slave unit of the cycle.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    unit: StrokeUnit,
    pieces: Vec<Piece>,
    stroke: f64,
}

/// A master angle within 1e-9 of a multiple of 1e-9 degree is put on it: a cycle stores its angles
/// in radians, and this gives back the decimal degrees of the file.
fn snap_deg(x: f64) -> f64 {
    let k = (x * 1e9).round();
    if (x * 1e9 - k).abs() < 1e-3 { k / 1e9 } else { x }
}

/// The allowed stroke of a single rise (in the slave unit).
pub const STROKE_RANGE: Range = Range::open_closed(0.0, 1e6, "");
/// The allowed motion angle of a single rise (deg).
pub const MOTION_DEG_RANGE: Range = Range::closed(1e-6, 36_000.0, "deg");

impl Motion {
    /// `motion_deg` of [`Motion::rise`] (`cam table --motion-deg`): [`MOTION_DEG_RANGE`], no default.
    pub const MOTION_DEG: Field = Field::new(
        "motion_deg",
        MOTION_DEG_RANGE,
        "Master angle of a cam table's single rise, deg: 1e-6 … 36000 (a hundred turns: a table may span \
         several turns of the master).",
    );
    /// `stroke_mm` of [`Motion::rise`] (`cam table --stroke-mm`): [`STROKE_RANGE`], no default.
    pub const STROKE_MM: Field =
        Field::new("stroke_mm", STROKE_RANGE, "Stroke of a cam table's single rise, mm: 0 < h ≤ 10⁶ (a kilometre).");
    /// `stroke_deg` of [`Motion::rise`] (`cam table --stroke-deg`): [`STROKE_RANGE`], no default.
    pub const STROKE_DEG: Field =
        Field::new("stroke_deg", STROKE_RANGE, "Swing of a cam table's single rise, deg: 0 < h ≤ 10⁶.");

    /// The motion of a checked cycle file, from its first segment's start over one period.
    pub fn from_cycle(cycle: &Cycle) -> Self {
        let mut pieces = Vec::new();
        let to_unit = 1.0 / cycle.unit.to_si();
        let mut stroke: f64 = 0.0;
        for s in &cycle.segments {
            let start = snap_deg(s.start_rad.to_degrees());
            let end = snap_deg((s.start_rad + s.length_rad).to_degrees());
            let base = s.base_si * to_unit;
            let h = s.stroke_si * to_unit;
            stroke = stroke.max(s.base_si.abs() * to_unit).max((s.base_si + s.stroke_si).abs() * to_unit);
            match &s.law {
                None => {
                    pieces.push(Piece { start_deg: start, end_deg: end, shape: PieceShape::Dwell(base), map: None })
                }
                Some((_, law)) => push_law(&mut pieces, law, start, end - start, base, h),
            }
        }
        Self { unit: cycle.unit, pieces, stroke }
    }

    /// A single rise by `stroke` (slave unit, > 0) over the master angles `0…motion_deg`.
    pub fn rise(law: &Law, stroke: f64, motion_deg: f64, unit: StrokeUnit) -> Result<Self> {
        let h = if unit == StrokeUnit::Mm { Self::STROKE_MM } else { Self::STROKE_DEG }.check(stroke)?;
        let b = Self::MOTION_DEG.check(motion_deg)?;
        let mut pieces = Vec::new();
        push_law(&mut pieces, law, 0.0, b, 0.0, h);
        Ok(Self { unit, pieces, stroke: h })
    }

    /// Builds a motion from pieces given directly (for tests and other crates): each `(start, end,
    /// law, base, stroke)` with `law = None` for a dwell at `base`.
    pub fn from_parts(unit: StrokeUnit, parts: &[(f64, f64, Option<&Law>, f64, f64)]) -> Result<Self> {
        let mut pieces = Vec::new();
        let mut stroke: f64 = 0.0;
        for (i, &(a, b, law, base, h)) in parts.iter().enumerate() {
            if !(a.is_finite() && b.is_finite() && b > a && base.is_finite() && h.is_finite()) {
                return Err(CamError::Law {
                    field: format!("parts[{i}]"),
                    reason: "a piece needs finite numbers and end > start".into(),
                });
            }
            if let Some(p) = pieces.last().map(|p: &Piece| p.end_deg)
                && (p - a).abs() > 1e-9
            {
                return Err(CamError::Law {
                    field: format!("parts[{i}]"),
                    reason: format!("starts at {a}° but the previous piece ends at {p}°"),
                });
            }
            stroke = stroke.max(base.abs()).max((base + h).abs());
            match law {
                None => pieces.push(Piece { start_deg: a, end_deg: b, shape: PieceShape::Dwell(base), map: None }),
                Some(l) => push_law(&mut pieces, l, a, b - a, base, h),
            }
        }
        if pieces.is_empty() {
            return Err(CamError::Law { field: "parts".into(), reason: "no pieces".into() });
        }
        Ok(Self { unit, pieces, stroke })
    }

    /// This motion with its slave taken through `map` (every piece: a dwell stays a dwell at the
    /// mapped position), in `unit`: a table of it holds the mapped coordinate (a motor's angle in
    /// deg for a frame's height in mm). The stroke scale is the largest |mapped value| at the
    /// pieces' ends (the map is monotone).
    pub fn mapped(mut self, map: Arc<dyn SlaveMap>, unit: StrokeUnit) -> Self {
        let shared = SharedMap(map);
        let mut stroke: f64 = 0.0;
        for p in &mut self.pieces {
            p.map = Some(shared.clone());
            stroke = stroke.max(p.derivs(p.start_deg)[0].abs()).max(p.derivs(p.end_deg)[0].abs());
        }
        self.unit = unit;
        self.stroke = stroke;
        self
    }

    /// The slave unit.
    pub fn unit(&self) -> StrokeUnit {
        self.unit
    }

    /// The smooth pieces in order.
    pub fn pieces(&self) -> &[Piece] {
        &self.pieces
    }

    /// First master angle (deg).
    pub fn start_deg(&self) -> f64 {
        self.pieces[0].start_deg
    }

    /// Last master angle (deg).
    pub fn end_deg(&self) -> f64 {
        self.pieces[self.pieces.len() - 1].end_deg
    }

    /// The largest |slave position| reached (the stroke scale of resolutions).
    pub fn stroke(&self) -> f64 {
        self.stroke
    }

    /// The master angles of every joint between pieces, both ends included, ascending.
    pub fn joints(&self) -> Vec<f64> {
        let mut j: Vec<f64> = self.pieces.iter().map(|p| p.start_deg).collect();
        j.push(self.end_deg());
        j
    }

    /// Index of the piece holding `deg` (the right one at a joint, the last one at the end).
    pub fn piece_index(&self, deg: f64) -> usize {
        self.pieces.partition_point(|p| p.start_deg <= deg).clamp(1, self.pieces.len()) - 1
    }

    /// `[Y, V, A, J]` at master angle `deg` (the right-hand piece at a joint).
    pub fn eval(&self, deg: f64) -> [f64; 4] {
        self.pieces[self.piece_index(deg)].eval(deg)
    }
}

fn push_law(pieces: &mut Vec<Piece>, law: &Law, start: f64, len: f64, base: f64, h: f64) {
    let segs = law.segments();
    for (i, seg) in segs.iter().enumerate() {
        let a = if i == 0 { start } else { snap_deg(start + len * seg.x0()) };
        let b = if i + 1 == segs.len() { start + len } else { snap_deg(start + len * seg.x1()) };
        pieces.push(Piece {
            start_deg: a,
            end_deg: b,
            shape: PieceShape::Moving { seg: *seg, law_start_deg: start, law_len_deg: len, base, stroke: h },
            map: None,
        });
    }
}
