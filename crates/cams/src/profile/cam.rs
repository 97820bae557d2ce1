//! A disc cam built from a closed motion and a design: its pitch curves, working profiles,
//! pressure angle, curvature and their extremes.

use super::design::{CamDesign, Closure, Follower, Size};
use super::extremes::{Extremes, extremes};
use super::jet::Jet;
use super::lift::{Lift, Span};
use super::sizing;
use super::track::{Track, curvature, offset};
use crate::table::Motion;
use crate::{CamError, Result};
use loomkin_laws::StrokeUnit;
use loomkin_units::{Field, Range};

/// A working surface: the pitch curve of track `track` offset by `dist` (mm) along its outward
/// normal (−r: the roller outside the cam; +r: the outer wall of a groove), or the flat face's
/// contact curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wall {
    /// Index of the track (0: the cam, 1: the counter-cam of a conjugate pair).
    pub track: usize,
    /// Offset along the outward normal (mm).
    pub dist: f64,
    /// The name of its layer and of its column: `profile`, `counter_profile`, `groove_outer`.
    pub name: &'static str,
}

/// The extremes of one track (one pitch curve).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackExtremes {
    /// Largest |pressure angle| (deg) and the main-shaft angle where it occurs (deg).
    pub max_pressure_angle_deg: f64,
    /// Where the largest |pressure angle| occurs (main-shaft deg).
    pub max_pressure_angle_at_deg: f64,
    /// Signed pressure angle there (deg).
    pub max_pressure_angle_signed_deg: f64,
    /// Largest curvature of the pitch curve where it is convex (1/mm; ≤ 0 when nowhere convex) and where (deg).
    pub max_convex_curvature_per_mm: f64,
    /// Where the pitch curve is most curved convexly (main-shaft deg).
    pub max_convex_curvature_at_deg: f64,
    /// Largest curvature where it is concave, as a positive number (1/mm; ≤ 0 when nowhere concave).
    pub max_concave_curvature_per_mm: f64,
    /// Where the pitch curve is most curved concavely (main-shaft deg).
    pub max_concave_curvature_at_deg: f64,
}

/// One sample of a cam at a main-shaft angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CamPoint {
    /// Main-shaft angle (deg).
    pub angle_deg: f64,
    /// Pitch point in the cam frame (mm).
    pub pitch_mm: [f64; 2],
    /// Pressure angle (deg).
    pub pressure_angle_deg: f64,
    /// Curvature of the pitch curve, positive where convex (1/mm).
    pub curvature_pitch_per_mm: f64,
    /// Point of the working profile (mm).
    pub profile_mm: [f64; 2],
    /// Curvature of the working profile, positive where convex (1/mm).
    pub curvature_profile_per_mm: f64,
}

/// A disc cam and its extremes.
#[derive(Debug, Clone)]
pub struct CamProfile {
    lift: Lift,
    design: CamDesign,
    prime_radius_mm: f64,
    tracks: Vec<Track>,
    walls: Vec<Wall>,
    extremes: Vec<TrackExtremes>,
    roller_max_mm: Option<f64>,
    undercut_at_deg: Option<f64>,
    flat: Option<FlatExtremes>,
}

/// Extremes of a flat-faced follower's cam.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlatExtremes {
    /// Least radius of curvature of the profile, `r_b + s + d²s/dψ²` (mm), and where (deg).
    pub min_radius_profile_mm: f64,
    /// Where the profile's radius of curvature is least (main-shaft deg).
    pub min_radius_profile_at_deg: f64,
    /// The least base circle radius without a cusp (mm): `max(−(s + d²s/dψ²))`.
    pub least_prime_radius_mm: f64,
    /// Contact point's distance from the line of motion, least and greatest (mm): the face must
    /// reach from `face_min_mm` to `face_max_mm`.
    pub face_min_mm: f64,
    /// Greatest distance of the contact point from the line of motion (mm).
    pub face_max_mm: f64,
}

/// Allowed main-shaft angle step of the sampled points ([`CamProfile::sample`], deg): from a
/// thousandth of a degree (360 000 points a turn) to a quarter turn.
pub const SAMPLE_STEP_RANGE: Range = Range::closed(1e-3, 90.0, "deg");
/// The step of the sampled points when none is given (deg).
pub const DEFAULT_SAMPLE_STEP_DEG: f64 = 1.0;

/// Which curve of a cam.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Curve {
    /// The pitch curve of a track.
    Pitch(usize),
    /// A working surface (index into [`CamProfile::walls`]).
    Wall(usize),
}

impl CamProfile {
    /// Builds the cam of a closed motion (a cycle in mm for a translating or flat follower, in deg
    /// for a swinging one) and locates every extreme.
    pub fn new(motion: &Motion, design: &CamDesign) -> Result<Self> {
        design.check()?;
        let lift = Lift::new(motion)?;
        let need = match design.follower {
            Follower::Oscillating { .. } => StrokeUnit::Deg,
            _ => StrokeUnit::Mm,
        };
        if lift.unit() != need {
            return Err(CamError::Usage {
                field: "unit".into(),
                reason: match need {
                    StrokeUnit::Deg => "an oscillating follower needs a cycle in deg (the swing of the arm)".into(),
                    StrokeUnit::Mm => "a translating or flat-faced follower needs a cycle in mm".into(),
                },
            });
        }
        if design.follower == Follower::Flat && design.closure != Closure::Single {
            return Err(CamError::Usage {
                field: "closure".into(),
                reason: "a flat-faced follower is built as a single cam (spring closure) only".into(),
            });
        }
        let rp = match design.size {
            Size::PrimeRadiusMm(r) => r,
            Size::MaxPressureDeg(a) => {
                let rp = sizing::least_prime_radius(&lift, design, a)?;
                if !super::design::LENGTH_RANGE.contains(rp) {
                    return Err(CamError::Usage {
                        field: "max_pressure_deg".into(),
                        reason: format!(
                            "the least prime radius for {}° is {} mm, outside the allowed {}",
                            loomkin_units::compact(a),
                            loomkin_units::compact(rp),
                            super::design::LENGTH_RANGE.describe("prime_radius_mm")
                        ),
                    });
                }
                rp
            }
        };
        let tracks = tracks(&lift, design, rp)?;
        let r = if design.follower == Follower::Flat { 0.0 } else { design.roller_radius_mm };
        if r >= rp {
            return Err(CamError::Usage {
                field: "roller_radius_mm".into(),
                reason: format!(
                    "a {} mm roller leaves no base circle inside the {} mm prime circle (base radius = prime − roller must be > 0)",
                    loomkin_units::compact(r),
                    loomkin_units::compact(rp)
                ),
            });
        }
        let walls = match (design.follower, design.closure) {
            (Follower::Flat, _) => vec![Wall { track: 0, dist: 0.0, name: "profile" }],
            (_, Closure::Single) => vec![Wall { track: 0, dist: -r, name: "profile" }],
            (_, Closure::Conjugate) => {
                vec![Wall { track: 0, dist: -r, name: "profile" }, Wall { track: 1, dist: -r, name: "counter_profile" }]
            }
            (_, Closure::Groove) => {
                vec![Wall { track: 0, dist: -r, name: "profile" }, Wall { track: 0, dist: r, name: "groove_outer" }]
            }
        };
        let mut cam = Self {
            lift,
            design: *design,
            prime_radius_mm: rp,
            tracks,
            walls,
            extremes: Vec::new(),
            roller_max_mm: None,
            undercut_at_deg: None,
            flat: None,
        };
        cam.extremes = (0..cam.tracks.len()).map(|i| cam.track_extremes(i)).collect();
        if design.follower == Follower::Flat {
            cam.flat = Some(cam.flat_extremes());
            if cam.flat.is_some_and(|f| f.min_radius_profile_mm <= 0.0) {
                cam.undercut_at_deg = cam.flat.map(|f| f.min_radius_profile_at_deg);
            }
        } else {
            let mut best: Option<(f64, f64)> = None;
            for w in &cam.walls {
                let e = &cam.extremes[w.track];
                let (k, at) = if w.dist <= 0.0 {
                    (e.max_convex_curvature_per_mm, e.max_convex_curvature_at_deg)
                } else {
                    (e.max_concave_curvature_per_mm, e.max_concave_curvature_at_deg)
                };
                if k > 0.0 && best.is_none_or(|(b, _)| 1.0 / k < b) {
                    best = Some((1.0 / k, at));
                }
            }
            cam.roller_max_mm = Some(best.map_or(rp, |(b, _)| b.min(rp)));
            if let Some((b, at)) = best
                && r > 0.0
                && r >= b
            {
                cam.undercut_at_deg = Some(at);
            }
        }
        Ok(cam)
    }

    /// The design.
    pub fn design(&self) -> &CamDesign {
        &self.design
    }

    /// The prime circle radius `R_p` (mm): the least radius of the pitch curve.
    pub fn prime_radius_mm(&self) -> f64 {
        self.prime_radius_mm
    }

    /// The base circle radius (mm): `R_p − r` (the least radius of the working profile of a single cam).
    pub fn base_radius_mm(&self) -> f64 {
        match self.design.follower {
            Follower::Flat => self.prime_radius_mm,
            _ => self.prime_radius_mm - self.design.roller_radius_mm,
        }
    }

    /// The stroke (mm, or deg for a swinging follower).
    pub fn stroke(&self) -> f64 {
        match self.lift.unit() {
            StrokeUnit::Mm => self.lift.stroke(),
            StrokeUnit::Deg => self.lift.stroke().to_degrees(),
        }
    }

    /// The first and last main-shaft angle of the cycle (deg).
    pub fn range_deg(&self) -> (f64, f64) {
        let (a, b) = self.lift.range();
        (self.lift.deg(a), self.lift.deg(b))
    }

    /// The main-shaft angles of the motion's joints (deg).
    pub fn joints_deg(&self) -> Vec<f64> {
        self.lift.joints_deg()
    }

    /// The number of tracks (pitch curves): 2 for a conjugate pair, else 1.
    pub fn track_count(&self) -> usize {
        self.tracks.len()
    }

    /// The trace-point path of a track.
    pub fn track(&self, i: usize) -> Track {
        self.tracks[i]
    }

    /// The working surfaces.
    pub fn walls(&self) -> &[Wall] {
        &self.walls
    }

    /// The extremes of each track.
    pub fn track_extremes_all(&self) -> &[TrackExtremes] {
        &self.extremes
    }

    /// Largest |pressure angle| over every track (deg), where (main-shaft deg) and its sign.
    pub fn max_pressure_angle(&self) -> (f64, f64, f64) {
        let e = self
            .extremes
            .iter()
            .max_by(|a, b| a.max_pressure_angle_deg.total_cmp(&b.max_pressure_angle_deg))
            .copied()
            .unwrap_or_else(unreachable_extremes);
        (e.max_pressure_angle_deg, e.max_pressure_angle_at_deg, e.max_pressure_angle_signed_deg)
    }

    /// The least radius of curvature where a pitch curve is convex (mm) and where (deg), over every track.
    pub fn min_convex_radius_pitch(&self) -> (f64, f64) {
        let e = self
            .extremes
            .iter()
            .max_by(|a, b| a.max_convex_curvature_per_mm.total_cmp(&b.max_convex_curvature_per_mm))
            .copied()
            .unwrap_or_else(unreachable_extremes);
        (1.0 / e.max_convex_curvature_per_mm, e.max_convex_curvature_at_deg)
    }

    /// The largest roller without undercut (mm; bounded by the prime radius); `None` for a flat face.
    pub fn roller_max_mm(&self) -> Option<f64> {
        self.roller_max_mm
    }

    /// Where the profile is undercut (main-shaft deg), if it is.
    pub fn undercut_at_deg(&self) -> Option<f64> {
        self.undercut_at_deg
    }

    /// The flat face's extremes (flat-faced follower only).
    pub fn flat_extremes_report(&self) -> Option<FlatExtremes> {
        self.flat
    }

    /// The smooth spans of the cam angle.
    pub(crate) fn spans(&self) -> Vec<Span> {
        self.lift.spans()
    }

    fn wrap_deg(&self, deg: f64) -> f64 {
        let (a, b) = self.range_deg();
        if deg >= a && deg <= b { deg } else { a + (deg - a).rem_euclid(b - a) }
    }

    /// The pitch curve (as jets) of a track at cam angle `psi` by the formula of span `piece`.
    fn track_jets(&self, track: usize, piece: usize, psi: f64) -> super::track::TrackJets {
        self.tracks[track].jets(psi, self.lift.jet(piece, psi))
    }

    /// A curve as jets at cam angle `psi` by the formula of span `piece`.
    pub(crate) fn curve_jets(&self, curve: Curve, piece: usize, psi: f64) -> [Jet; 2] {
        match curve {
            Curve::Pitch(t) => self.track_jets(t, piece, psi).p,
            Curve::Wall(w) => {
                let w = self.walls[w];
                let j = self.track_jets(w.track, piece, psi);
                if self.design.follower == Follower::Flat { j.contact } else { offset(j.p, w.dist) }
            }
        }
    }

    /// A point of a curve (mm) at main-shaft angle `deg` (wrapped into the cycle).
    pub fn point(&self, curve: Curve, deg: f64) -> [f64; 2] {
        let deg = self.wrap_deg(deg);
        let psi = self.lift.psi(deg);
        let c = self.curve_jets(curve, self.lift.piece_at(deg), psi);
        [c[0].v(), c[1].v()]
    }

    /// Everything at main-shaft angle `deg` for track `track` and its first wall.
    pub fn eval(&self, track: usize, deg: f64) -> CamPoint {
        let deg = self.wrap_deg(deg);
        let psi = self.lift.psi(deg);
        let piece = self.lift.piece_at(deg);
        let j = self.track_jets(track, piece, psi);
        let w = self.walls.iter().position(|w| w.track == track).unwrap_or(0);
        let prof = self.curve_jets(Curve::Wall(w), piece, psi);
        CamPoint {
            angle_deg: deg,
            pitch_mm: [j.p[0].v(), j.p[1].v()],
            pressure_angle_deg: j.phi.v().to_degrees(),
            curvature_pitch_per_mm: curvature(j.p).v(),
            profile_mm: [prof[0].v(), prof[1].v()],
            curvature_profile_per_mm: curvature(prof).v(),
        }
    }

    /// `step_deg`: the main-shaft angle between the printed points of a profile: 0.001° … 90°
    /// (360 000 points a turn at the finest; four a turn at the coarsest); 1° when left out.
    pub const STEP_DEG: Field = Field::new(
        "step_deg",
        SAMPLE_STEP_RANGE,
        "Main-shaft angle between the profile's printed points: 0.001 … 90° (360 000 points a turn at \
         the finest, four at the coarsest); 1° when left out.",
    )
    .with_default(DEFAULT_SAMPLE_STEP_DEG);

    /// Samples of track `track` every `step_deg` of main-shaft angle from the cycle's start, the
    /// end excluded (the curve is closed).
    pub fn sample(&self, track: usize, step_deg: f64) -> Vec<CamPoint> {
        let (a, b) = self.range_deg();
        let n = ((b - a) / step_deg - 1e-9).ceil().max(1.0) as usize;
        (0..n).map(|i| self.eval(track, a + i as f64 * step_deg)).collect()
    }

    fn track_extremes(&self, t: usize) -> TrackExtremes {
        let (mut phi, mut kap) = (Extremes::EMPTY, Extremes::EMPTY);
        for sp in self.spans() {
            phi.merge(
                &extremes(sp, |psi| {
                    let p = self.track_jets(t, sp.piece, psi).phi;
                    [p.v(), p.d(1), p.d(2)]
                }),
                0.0,
            );
            kap.merge(
                &extremes(sp, |psi| {
                    let k = curvature(self.track_jets(t, sp.piece, psi).p);
                    [k.v(), k.d(1), k.d(2)]
                }),
                0.0,
            );
        }
        let (pm, pm_at) =
            if phi.max.0.abs() >= phi.min.0.abs() { (phi.max.0, phi.max.1) } else { (phi.min.0, phi.min.1) };
        TrackExtremes {
            max_pressure_angle_deg: pm.abs().to_degrees(),
            max_pressure_angle_at_deg: self.lift.deg(pm_at),
            max_pressure_angle_signed_deg: pm.to_degrees(),
            max_convex_curvature_per_mm: kap.max.0,
            max_convex_curvature_at_deg: self.lift.deg(kap.max.1),
            max_concave_curvature_per_mm: -kap.min.0,
            max_concave_curvature_at_deg: self.lift.deg(kap.min.1),
        }
    }

    fn flat_extremes(&self) -> FlatExtremes {
        let (mut rho, mut face) = (Extremes::EMPTY, Extremes::EMPTY);
        for sp in self.spans() {
            rho.merge(
                &extremes(sp, |psi| {
                    let s = self.lift.jet(sp.piece, psi);
                    [s.v() + s.d(2), s.d(1) + s.d(3), s.d(2) + s.d(4)]
                }),
                0.0,
            );
            face.merge(
                &extremes(sp, |psi| {
                    let s = self.lift.jet(sp.piece, psi);
                    [s.d(1), s.d(2), s.d(3)]
                }),
                0.0,
            );
        }
        let rb = self.prime_radius_mm;
        FlatExtremes {
            min_radius_profile_mm: rb + rho.min.0,
            min_radius_profile_at_deg: self.lift.deg(rho.min.1),
            least_prime_radius_mm: (-rho.min.0).max(0.0),
            face_min_mm: face.min.0,
            face_max_mm: face.max.0,
        }
    }

    /// Points of a curve spaced so that no chord deviates from the curve by more than `tol_mm`:
    /// on each smooth span with `M` the largest `|C″(ψ)|` (located exactly), chords of
    /// `h = √(8·tol/M)` in ψ deviate at most `M h²/8 = tol`. Returns the closed polygon (the
    /// first point not repeated), joints included.
    pub fn polyline(&self, curve: Curve, tol_mm: f64) -> Vec<[f64; 2]> {
        let mut out = Vec::new();
        for sp in self.spans() {
            let acc = |psi: f64| {
                let c = self.curve_jets(curve, sp.piece, psi);
                let d2 = [c[0].deriv().deriv(), c[1].deriv().deriv()];
                let m = Jet::dot(d2, d2);
                [m.v(), m.d(1), m.d(2)]
            };
            let m = extremes(sp, acc).max.0.max(0.0).sqrt();
            let h = (8.0 * tol_mm / m.max(1e-300)).sqrt();
            let n = ((sp.b - sp.a) / h).ceil().clamp(1.0, 1e7) as usize;
            for i in 0..n {
                let psi = sp.a + (sp.b - sp.a) * i as f64 / n as f64;
                let c = self.curve_jets(curve, sp.piece, psi);
                out.push([c[0].v(), c[1].v()]);
            }
        }
        out
    }

    /// The pitch point of track 0 at main-shaft angle 0 (mm): where the 0° phase mark points.
    pub fn phase_point(&self) -> [f64; 2] {
        self.point(Curve::Pitch(0), 0.0)
    }

    /// The lift `s` (mm or rad, from its least value) at main-shaft angle `deg`, by the law.
    pub fn lift_at(&self, deg: f64) -> f64 {
        let deg = self.wrap_deg(deg);
        self.lift.jet(self.lift.piece_at(deg), self.lift.psi(deg)).v()
    }
}

fn unreachable_extremes() -> TrackExtremes {
    // A cam always has at least one track; this keeps the accessors total without a panic.
    TrackExtremes {
        max_pressure_angle_deg: 0.0,
        max_pressure_angle_at_deg: 0.0,
        max_pressure_angle_signed_deg: 0.0,
        max_convex_curvature_per_mm: 0.0,
        max_convex_curvature_at_deg: 0.0,
        max_concave_curvature_per_mm: 0.0,
        max_concave_curvature_at_deg: 0.0,
    }
}

/// The tracks of a design at prime radius `rp`, checking that the geometry can be built.
pub(crate) fn tracks(lift: &Lift, design: &CamDesign, rp: f64) -> Result<Vec<Track>> {
    let h = lift.stroke();
    let conj = design.closure == Closure::Conjugate;
    Ok(match design.follower {
        Follower::Translating { offset_mm: eps } => {
            if rp <= eps.abs() {
                return Err(CamError::Usage {
                    field: "prime_radius_mm".into(),
                    reason: format!(
                        "a prime circle of {} mm is too small for the offset of {} mm: the line of motion misses it (need prime radius > |offset|)",
                        loomkin_units::compact(rp),
                        loomkin_units::compact(eps)
                    ),
                });
            }
            let d0 = (rp * rp - eps * eps).sqrt();
            let mut t = vec![Track::Translating { eps, y0: d0 }];
            if conj {
                t.push(Track::Translating { eps, y0: -d0 - h });
            }
            t
        }
        Follower::Oscillating { arm_mm: l, pivot_mm: d } => {
            let g0 = sizing::initial_arm_angle(d, l, rp, h)?;
            let mut t = vec![Track::Oscillating { d, l, g0, sigma: 1.0 }];
            if conj {
                t.push(Track::Oscillating { d, l, g0: g0 + h, sigma: -1.0 });
            }
            t
        }
        Follower::Flat => vec![Track::Flat { rb: rp }],
    })
}
