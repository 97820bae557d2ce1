//! Machine cycles: dwell / rise / dwell / return segments over one turn of the main shaft.

use crate::{Kinematics, Law, LawError, LawSpec, Result};
use loomkin_units::{Field, Range, ShaftSpeed, compact};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The follower's kind of motion, and so the unit of its stroke.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum StrokeUnit {
    /// A translating follower; strokes in millimetres, results in m, m/s, m/s², m/s³.
    #[default]
    Mm,
    /// A swinging follower; strokes in degrees, results in rad, rad/s, rad/s², rad/s³.
    Deg,
}

impl StrokeUnit {
    /// The allowed stroke of a rise or return in this unit (mm or deg): from 10⁻¹² (a stroke the
    /// law's normalisation still resolves) to 10⁶ (a kilometre, or 2 778 turns of a swing).
    pub const fn stroke_range(self) -> Range {
        match self {
            StrokeUnit::Mm => Range::closed(1e-12, 1e6, "mm"),
            StrokeUnit::Deg => Range::closed(1e-12, 1e6, "deg"),
        }
    }

    /// Factor from the stroke unit to SI (m or rad).
    pub fn to_si(self) -> f64 {
        match self {
            StrokeUnit::Mm => 1e-3,
            StrokeUnit::Deg => std::f64::consts::PI / 180.0,
        }
    }

    /// SI unit names of position, velocity, acceleration and jerk.
    pub fn si_units(self) -> [&'static str; 4] {
        match self {
            StrokeUnit::Mm => ["m", "m/s", "m/s²", "m/s³"],
            StrokeUnit::Deg => ["rad", "rad/s", "rad/s²", "rad/s³"],
        }
    }

    /// ASCII unit suffixes for CSV headers and JSON keys.
    pub fn key_units(self) -> [&'static str; 4] {
        match self {
            StrokeUnit::Mm => ["m", "m_s", "m_s2", "m_s3"],
            StrokeUnit::Deg => ["rad", "rad_s", "rad_s2", "rad_s3"],
        }
    }

    /// The names of a sample's six values, as CSV headers, JSON keys and array names:
    /// `angle_deg`, `time_s`, then s, v, a, j with their unit suffixes (`s_m`, `v_m_s`, … or
    /// `s_rad`, …).
    pub fn sample_keys(self) -> [String; 6] {
        let [pu, vu, au, ju] = self.key_units();
        [
            "angle_deg".into(),
            "time_s".into(),
            format!("s_{pu}"),
            format!("v_{vu}"),
            format!("a_{au}"),
            format!("j_{ju}"),
        ]
    }
}

/// What a cycle segment does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SegmentKind {
    /// The follower stands still.
    Dwell,
    /// The follower rises by the stroke.
    Rise,
    /// The follower returns by the stroke.
    Return,
}

impl SegmentKind {
    /// `dwell`, `rise` or `return`, as in cycle files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Dwell => "dwell",
            Self::Rise => "rise",
            Self::Return => "return",
        }
    }
}

/// One segment of a cycle file, as written in TOML (`[[segment]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SegmentSpec {
    /// dwell, rise or return.
    pub kind: SegmentKind,
    /// Start angle of the main shaft in degrees (defaults to the end of the previous segment, or 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub from_deg: Option<f64>,
    /// End angle in degrees (give this or `length_deg`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub to_deg: Option<f64>,
    /// Angular length in degrees (give this or `to_deg`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length_deg: Option<f64>,
    /// Law name (rise and return; defaults to `cycloidal`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub law: Option<String>,
    /// Law parameters, e.g. `{ ramp = 0.1 }`.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub params: BTreeMap<String, toml::Value>,
    /// Stroke in the cycle's unit (defaults to the cycle's `stroke`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stroke: Option<f64>,
}

/// A cycle file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CycleSpec {
    /// Angle of one cycle of the main shaft in degrees (default 360).
    #[serde(default = "default_period")]
    pub period_deg: f64,
    /// `mm` (translating follower) or `deg` (swinging follower).
    #[serde(default)]
    pub unit: StrokeUnit,
    /// Default stroke of rises and returns in `unit`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stroke: Option<f64>,
    /// Main-shaft speed in rpm (default [`loomkin_units::ShaftSpeed::DEFAULT_RPM`], 300; the CLI's
    /// `--speed-rpm` overrides it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed_rpm: Option<f64>,
    /// The segments, in order.
    pub segment: Vec<SegmentSpec>,
}

fn default_period() -> f64 {
    360.0
}

impl SegmentSpec {
    /// A dwell of `length_deg` degrees.
    pub fn dwell(length_deg: f64) -> Self {
        Self {
            kind: SegmentKind::Dwell,
            from_deg: None,
            to_deg: None,
            length_deg: Some(length_deg),
            law: None,
            params: BTreeMap::new(),
            stroke: None,
        }
    }

    /// A rise or return of `length_deg` degrees by a catalogue law (its name and parameters are
    /// written as the file holds them; the stroke is the cycle's).
    pub fn moving(kind: SegmentKind, length_deg: f64, law: &LawSpec) -> Self {
        let params = law.params().into_iter().map(|(k, v)| (k, param_value(&v))).collect();
        Self { law: Some(law.name().to_string()), params, ..Self::dwell(length_deg) }.with_kind(kind)
    }

    fn with_kind(mut self, kind: SegmentKind) -> Self {
        self.kind = kind;
        self
    }
}

/// A parameter as a TOML value: a number where the text is one, else the text.
fn param_value(text: &str) -> toml::Value {
    match text.parse::<f64>() {
        Ok(x) if x.is_finite() => toml::Value::Float(x),
        _ => toml::Value::String(text.to_string()),
    }
}

impl CycleSpec {
    /// The allowed motion angle of [`CycleSpec::rise_return`] (deg): the rise and the return each
    /// take at most half of the turn.
    pub const RISE_RETURN_MOTION_DEG: Range = Range::closed(1e-6, 180.0, "deg");
    /// `motion_deg` of [`CycleSpec::rise_return`] as an input (`cam profile --motion-deg`):
    /// [`CycleSpec::RISE_RETURN_MOTION_DEG`], no default.
    pub const MOTION_DEG: Field = Field::new(
        "motion_deg",
        Self::RISE_RETURN_MOTION_DEG,
        "Master angle of a single law's rise and of its return, deg: 1e-6 … 180 (each takes at most half the turn).",
    );
    /// `stroke_mm` of [`CycleSpec::rise_return`] with a translating follower:
    /// [`StrokeUnit::stroke_range`] in mm, no default.
    pub const STROKE_MM: Field = Field::new(
        "stroke_mm",
        StrokeUnit::Mm.stroke_range(),
        "Stroke of a single law's rise, mm: 1e-12 (what the law's normalisation resolves) … 10⁶ (a kilometre).",
    );
    /// `stroke_deg` of [`CycleSpec::rise_return`] with a swinging follower:
    /// [`StrokeUnit::stroke_range`] in deg, no default.
    pub const STROKE_DEG: Field = Field::new(
        "stroke_deg",
        StrokeUnit::Deg.stroke_range(),
        "Swing of a single law's rise, deg: 1e-12 (what the law's normalisation resolves) … 10⁶ (2 778 turns).",
    );

    /// One turn (360°) of a rise by `law` over `motion_deg`, a dwell, the return by the same law
    /// over `motion_deg` and a dwell of the same length (dwells of zero length left out): the
    /// machine cycle of a single law. Fails when the two motions do not fit in the turn.
    pub fn rise_return(law: &LawSpec, unit: StrokeUnit, stroke: f64, motion_deg: f64) -> Result<Self> {
        Self::MOTION_DEG.check(motion_deg)?;
        match unit {
            StrokeUnit::Mm => Self::STROKE_MM.check(stroke)?,
            StrokeUnit::Deg => Self::STROKE_DEG.check(stroke)?,
        };
        let dwell = 180.0 - motion_deg;
        let mut segment = vec![SegmentSpec::moving(SegmentKind::Rise, motion_deg, law)];
        if dwell > 0.0 {
            segment.push(SegmentSpec::dwell(dwell));
        }
        segment.push(SegmentSpec::moving(SegmentKind::Return, motion_deg, law));
        if dwell > 0.0 {
            segment.push(SegmentSpec::dwell(dwell));
        }
        let spec = Self { period_deg: 360.0, unit, stroke: Some(stroke), speed_rpm: None, segment };
        Cycle::new(&spec)?;
        Ok(spec)
    }

    /// The cycle file as TOML text, which [`Cycle::from_toml`] reads back to the same spec
    /// (numbers in their shortest round-trip form, so a written law reads back bit for bit).
    pub fn to_toml(&self) -> Result<String> {
        toml::to_string(self).map_err(|e| LawError::Parse {
            field: "cycle file".into(),
            text: e.to_string(),
            expected: "a cycle that TOML can hold".into(),
        })
    }
}

/// One segment of a checked cycle.
#[derive(Debug, Clone)]
pub struct CycleSegment {
    /// What it does.
    pub kind: SegmentKind,
    /// Start angle (rad).
    pub start_rad: f64,
    /// Angular length (rad).
    pub length_rad: f64,
    /// The law and its spec (none for dwells).
    pub law: Option<(LawSpec, Law)>,
    /// Position at the start (SI: m or rad).
    pub base_si: f64,
    /// Signed displacement over the segment (SI).
    pub stroke_si: f64,
}

/// A checked machine cycle.
#[derive(Debug, Clone)]
pub struct Cycle {
    /// The stroke unit of the file.
    pub unit: StrokeUnit,
    /// Cycle angle (rad).
    pub period_rad: f64,
    /// Speed given in the file, if any (rpm).
    pub speed_rpm: Option<f64>,
    /// The segments.
    pub segments: Vec<CycleSegment>,
}

/// One sample of a cycle in physical units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CyclePoint {
    /// Main-shaft angle (deg).
    pub angle_deg: f64,
    /// Time from the cycle start (s).
    pub time_s: f64,
    /// Position, velocity, acceleration, jerk (SI: m… or rad…).
    pub kin: Kinematics,
}

const DEG: f64 = std::f64::consts::PI / 180.0;

impl Cycle {
    /// Reads and checks a cycle from TOML text.
    pub fn from_toml(text: &str) -> Result<Self> {
        let spec: CycleSpec = toml::from_str(text).map_err(|e| LawError::Parse {
            field: "cycle file".into(),
            text: loomkin_units::toml_reason(text, &e),
            expected: "TOML with [[segment]] tables (kind, from_deg/to_deg or length_deg, law, stroke)".into(),
        })?;
        Self::new(&spec)
    }

    /// Checks a cycle: the angles must follow one another without gap or overlap and close the
    /// cycle, every rise and return needs a positive stroke, and the follower must end where it began.
    pub fn new(spec: &CycleSpec) -> Result<Self> {
        let period = Range::closed(1e-6, 36_000.0, "deg").check("period_deg", spec.period_deg)?;
        if let Some(n) = spec.speed_rpm {
            ShaftSpeed::from_rpm(n)?;
        }
        if spec.segment.is_empty() {
            return Err(LawError::Cycle {
                field: "segment".into(),
                reason: "a cycle needs at least one [[segment]]".into(),
            });
        }
        let mut at = spec.segment[0].from_deg.unwrap_or(0.0);
        let start = at;
        let mut pos = 0.0;
        let mut segments = Vec::new();
        for (i, s) in spec.segment.iter().enumerate() {
            let f = |name: &str| format!("segment[{i}].{name}");
            if let Some(from) = s.from_deg {
                Range::closed(-36_000.0, 36_000.0, "deg").check(&f("from_deg"), from)?;
                if (from - at).abs() > 1e-9 {
                    return Err(LawError::Cycle {
                        field: f("from_deg"),
                        reason: format!(
                            "starts at {}° but the previous segment ends at {}°: leave no gap or overlap",
                            compact(from),
                            compact(at)
                        ),
                    });
                }
            }
            let len = match (s.to_deg, s.length_deg) {
                (Some(to), None) => to - at,
                (None, Some(l)) => l,
                _ => {
                    return Err(LawError::Cycle {
                        field: f("to_deg"),
                        reason: "give exactly one of to_deg and length_deg".into(),
                    });
                }
            };
            if !(len.is_finite() && len > 0.0) {
                return Err(LawError::Cycle {
                    field: f(if s.to_deg.is_some() { "to_deg" } else { "length_deg" }),
                    reason: format!(
                        "the segment's length is {}°; it must be positive (segments in increasing angle)",
                        compact(len)
                    ),
                });
            }
            let law = match s.kind {
                SegmentKind::Dwell => {
                    if s.law.is_some() || s.stroke.is_some() {
                        return Err(LawError::Cycle {
                            field: f("law"),
                            reason: "a dwell takes no law or stroke".into(),
                        });
                    }
                    None
                }
                _ => {
                    let spec_law = LawSpec::parse_table(s.law.as_deref().unwrap_or("cycloidal"), &s.params)
                        .map_err(|e| LawError::Cycle { field: f("law"), reason: e.to_string() })?;
                    let built =
                        spec_law.build().map_err(|e| LawError::Cycle { field: f("law"), reason: e.to_string() })?;
                    Some((spec_law, built))
                }
            };
            let stroke = match s.kind {
                SegmentKind::Dwell => 0.0,
                kind => {
                    let h = s.stroke.or(spec.stroke).ok_or_else(|| LawError::Cycle {
                        field: f("stroke"),
                        reason: "a rise or return needs a stroke (here or as the cycle's `stroke`)".into(),
                    })?;
                    spec.unit.stroke_range().check(&f("stroke"), h)?;
                    let si = h * spec.unit.to_si();
                    if kind == SegmentKind::Rise { si } else { -si }
                }
            };
            segments.push(CycleSegment {
                kind: s.kind,
                start_rad: at * DEG,
                length_rad: len * DEG,
                law,
                base_si: pos,
                stroke_si: stroke,
            });
            pos += stroke;
            at += len;
        }
        if (at - start - period).abs() > 1e-6 {
            return Err(LawError::Cycle {
                field: format!("segment[{}].to_deg", spec.segment.len() - 1),
                reason: format!(
                    "the segments span {}°, the cycle is {}°: the angles must close the cycle",
                    compact(at - start),
                    compact(period)
                ),
            });
        }
        let scale = segments.iter().map(|s| s.stroke_si.abs()).fold(0.0, f64::max);
        if pos.abs() > 1e-9 * scale.max(1e-12) {
            return Err(LawError::Cycle {
                field: "segment".into(),
                reason: format!(
                    "the follower ends {:.6} {} from where it started: rises and returns must balance",
                    pos / spec.unit.to_si(),
                    if spec.unit == StrokeUnit::Mm { "mm" } else { "deg" }
                ),
            });
        }
        Ok(Self { unit: spec.unit, period_rad: period * DEG, speed_rpm: spec.speed_rpm, segments })
    }

    /// `points`: samples over the cycle, both ends included: at least 2 (a streamed table is bounded
    /// by the time budget, [`loomkin_units::Budget`]); 721 (every half degree of a turn) when left
    /// out. Held as arrays (Python): [`Cycle::HELD_POINTS`].
    pub const POINTS: Field = Field::count(
        "points",
        Range::at_least(2.0, ""),
        "Samples over the cycle, both ends included: at least 2 (a streamed table is bounded by the time \
         budget, arrays by 10⁷); 721 (every half degree of a turn) when left out.",
    )
    .with_default(721.0);
    /// [`Cycle::POINTS`] held in memory as float64 columns (Python's arrays): 2 … 10⁷ (about 500 MB).
    pub const HELD_POINTS: Field = Self::POINTS.within(
        Range::closed(2.0, 1e7, ""),
        "Samples over the cycle held as arrays (six float64 columns): 2 … 10⁷ (about 500 MB); 721 when left out.",
    );

    /// The speed to run the cycle at, rpm: `given` (a front end's `speed_rpm`), else the file's,
    /// else [`loomkin_units::ShaftSpeed::DEFAULT_RPM`]. Not checked: the caller checks it under its
    /// own field name.
    pub fn speed_rpm_or(&self, given: Option<f64>) -> f64 {
        given.or(self.speed_rpm).unwrap_or(loomkin_units::ShaftSpeed::DEFAULT_RPM)
    }

    /// Kinematics in SI units at main-shaft angle `theta_rad` (wrapped into the cycle) and speed.
    pub fn eval(&self, theta_rad: f64, speed_rpm: f64) -> Kinematics {
        let omega = loomkin_units::rad_per_s_from_rpm(speed_rpm);
        let start = self.segments[0].start_rad;
        let th = start + (theta_rad - start).rem_euclid(self.period_rad);
        let seg = self.segments.iter().rev().find(|s| th >= s.start_rad).unwrap_or(&self.segments[0]);
        Self::eval_segment(seg, (th - seg.start_rad) / seg.length_rad, omega)
    }

    /// Kinematics in SI units at the end of the cycle, as the left limit: the last segment at its end.
    pub fn eval_end(&self, speed_rpm: f64) -> Kinematics {
        let omega = loomkin_units::rad_per_s_from_rpm(speed_rpm);
        Self::eval_segment(&self.segments[self.segments.len() - 1], 1.0, omega)
    }

    /// One segment at its fraction `x` (0…1), the shaft turning at `omega` rad/s.
    fn eval_segment(seg: &CycleSegment, x: f64, omega: f64) -> Kinematics {
        let Some((_, law)) = &seg.law else {
            return Kinematics { s: seg.base_si, ..Kinematics::default() };
        };
        let k = law.eval(x);
        let r = omega / seg.length_rad; // dx/dt
        let h = seg.stroke_si;
        Kinematics { s: seg.base_si + h * k.s, v: h * k.v * r, a: h * k.a * r * r, j: h * k.j * r * r * r }
    }

    /// `n ≥ 2` samples over one cycle at a speed, both ends included.
    pub fn sample(&self, n: usize, speed_rpm: f64) -> Vec<CyclePoint> {
        self.samples(n, speed_rpm).collect()
    }

    /// The samples of [`Cycle::sample`] one at a time, nothing held (a table of 10⁷ rows streams).
    pub fn samples(&self, n: usize, speed_rpm: f64) -> impl ExactSizeIterator<Item = CyclePoint> + '_ {
        let n = n.max(2);
        let omega = loomkin_units::rad_per_s_from_rpm(speed_rpm);
        let start = self.segments[0].start_rad;
        (0..n).map(move |i| {
            let f = i as f64 / (n - 1) as f64;
            let th = start + f * self.period_rad;
            // The last sample is the cycle's end, evaluated as the left limit: the last segment at its end
            // (evaluated 1e-12 of the period before it, the acceleration there was j·Δt, 3e-11 of the peak,
            // where a law ends at rest with a = 0).
            let kin = if i + 1 == n { self.eval_end(speed_rpm) } else { self.eval(th, speed_rpm) };
            CyclePoint { angle_deg: th / DEG, time_s: (th - start) / omega, kin }
        })
    }
}
