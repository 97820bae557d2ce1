//! The law and motion angle of each kind of move — rise, fall, and the moves pass-through lays end
//! to end — as a loom file gives them in `[shedding.servo]` (for every frame) and
//! `[[shedding.servo.frame]]` (for some):
//!
//! ```toml
//! [shedding.servo]
//! rise_law = "poly4567"                                          # a catalogue law by name
//! fall_law = { law = "modified-trapezoid", params = { ramp = 0.1 } }  # with its parameters
//! through_law = { preset = "dobby" }                             # a shedding law (a preset)
//! rise_motion_deg = 260
//! fall_motion_deg = 300
//! [[shedding.servo.frame]]
//! frames = [1]
//! rise_law = { spline = [[0, 0], [0.1, 0.9], [0.25, 1], [0.4, 0.7], [0.5, 0]], end = "clamped" }
//! ```
//!
//! A spline law is the servo law of `loomkin servo` (the cubic spline of the acceleration through
//! the definition points, [`loomkin_servo::SplineLaw`]) held as the core's `polynomial` law, the
//! form `servo export --format cycle` writes. Every law is checked where the frame's motion is
//! built: C² at every rest transition and across every pass-through joint ([`crate::analyse`]).

use crate::{EshedError, MoveLaws, Result};
use loomkin_laws::{Law, LawSpec, poly_segments_of};
use loomkin_units::Field;
use std::collections::BTreeMap;

/// A law a loom file gives for one kind of move: its catalogue form, the built law, and the field
/// it is given in (named when it is refused).
#[derive(Debug, Clone, PartialEq)]
pub struct GivenLaw {
    /// The catalogue form (what a cycle file holds).
    pub spec: LawSpec,
    /// The law.
    pub law: Law,
    /// The loom file's field (`shedding.servo.frame[0].fall_law`).
    pub field: String,
    /// Its name in text, in the loom file's form: the catalogue law with its parameters
    /// (`modified-trapezoid (ramp=0.125)`), `dobby preset`, `spline (5 points, clamped)`.
    pub label: String,
}

/// A frame's laws and motion angles by kind of move, as the loom file gives them; `None` where it
/// gives none (the shedding law's, `[shedding]`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MoveKinds {
    /// The law of a move up.
    pub rise_law: Option<GivenLaw>,
    /// The law of a move down.
    pub fall_law: Option<GivenLaw>,
    /// The law of the moves laid end to end by pass-through (both ways).
    pub through_law: Option<GivenLaw>,
    /// The motion angle of a move up, deg.
    pub rise_motion_deg: Option<f64>,
    /// The motion angle of a move down, deg.
    pub fall_motion_deg: Option<f64>,
}

impl MoveKinds {
    /// `rise_motion_deg`: the motion angle of a frame's moves up, 1 … 360° (the motion angle's
    /// range, [`loomkin_shed::MOTION_DEG`]).
    pub const RISE_MOTION_DEG: Field = Field::new(
        "rise_motion_deg",
        loomkin_shed::MOTION_DEG,
        "Motion angle of a frame's moves up (before pass-through lengthens moves): 1 … 360° of the main \
         shaft; the frame's motion_deg, else [shedding] motion_deg, when left out.",
    );
    /// `fall_motion_deg`: the motion angle of a frame's moves down, 1 … 360°.
    pub const FALL_MOTION_DEG: Field = Field::new(
        "fall_motion_deg",
        loomkin_shed::MOTION_DEG,
        "Motion angle of a frame's moves down (before pass-through lengthens moves): 1 … 360° of the \
         main shaft; the frame's motion_deg, else [shedding] motion_deg, when left out.",
    );

    /// The frame's laws: those given, else `default`'s rise and fall (the shedding law's, with
    /// their fields and labels).
    pub fn laws(&self, default: &MoveLaws) -> MoveLaws {
        let pick = |g: &Option<GivenLaw>, k: usize| match g {
            Some(g) => ((g.spec.clone(), g.law.clone()), g.field.clone(), g.label.clone()),
            None => (default.law(k == 0).clone(), default.fields[k].clone(), default.labels[k].clone()),
        };
        let (rise, rf, rl) = pick(&self.rise_law, 0);
        let (fall, ff, fl) = pick(&self.fall_law, 1);
        let through = self.through_law.as_ref().map(|g| (g.spec.clone(), g.law.clone()));
        let (tf, tl) = match &self.through_law {
            Some(g) => (g.field.clone(), g.label.clone()),
            None => (format!("{} (through)", default.fields[2]), String::new()),
        };
        MoveLaws { rise, fall, through, fields: [rf, ff, tf], labels: [rl, fl, tl] }
    }

    /// `frame` over `all`: each key the frame gives, else all frames' (`motion_deg`: the frame's
    /// one angle for both ways, below its own `rise_motion_deg` and `fall_motion_deg`).
    pub(crate) fn over(frame: Self, motion_deg: Option<f64>, all: &Self) -> Self {
        Self {
            rise_law: frame.rise_law.or_else(|| all.rise_law.clone()),
            fall_law: frame.fall_law.or_else(|| all.fall_law.clone()),
            through_law: frame.through_law.or_else(|| all.through_law.clone()),
            rise_motion_deg: frame.rise_motion_deg.or(motion_deg).or(all.rise_motion_deg),
            fall_motion_deg: frame.fall_motion_deg.or(motion_deg).or(all.fall_motion_deg),
        }
    }
}

/// The keys of a table that give the laws and angles by kind of move.
#[derive(Debug, Default, serde::Deserialize)]
pub(crate) struct MoveKindsFile {
    pub rise_law: Option<toml::Value>,
    pub fall_law: Option<toml::Value>,
    pub through_law: Option<toml::Value>,
    pub rise_motion_deg: Option<f64>,
    pub fall_motion_deg: Option<f64>,
}

impl MoveKindsFile {
    /// Reads the keys under the table `at` (each law built, each angle range-checked).
    pub(crate) fn read(&self, at: &str) -> Result<MoveKinds> {
        let law =
            |v: &Option<toml::Value>, key: &str| v.as_ref().map(|v| read_law(v, &format!("{at}.{key}"))).transpose();
        let angle = |v: Option<f64>, field: Field| {
            v.map(|v| field.check_as(&format!("{at}.{}", field.name), v)).transpose().map_err(EshedError::from)
        };
        Ok(MoveKinds {
            rise_law: law(&self.rise_law, "rise_law")?,
            fall_law: law(&self.fall_law, "fall_law")?,
            through_law: law(&self.through_law, "through_law")?,
            rise_motion_deg: angle(self.rise_motion_deg, MoveKinds::RISE_MOTION_DEG)?,
            fall_motion_deg: angle(self.fall_motion_deg, MoveKinds::FALL_MOTION_DEG)?,
        })
    }
}

const LAW_FORMS: &str = "a catalogue law \"NAME\" or { law = \"NAME\", params = { … } }, a shedding law { preset = \
                         \"NAME\" }, or a spline law { spline = [[X, Y], …], end = \"natural\" | \"clamped\" }";

/// One law of a loom file at `field`: a catalogue law by name (with `params`, read as cycle files
/// read them, [`LawSpec::parse_table`]), a shedding preset, or a servo spline law through
/// definition points.
pub fn read_law(value: &toml::Value, field: &str) -> Result<GivenLaw> {
    let bad = |why: String| EshedError::field(field, why);
    let built = |spec: LawSpec| spec.build().map(|law| (spec, law)).map_err(|e| bad(e.to_string()));
    let (spec, law, label) = match value {
        toml::Value::String(name) => {
            let (spec, law) = built(LawSpec::parse_table(name, &BTreeMap::new()).map_err(|e| bad(e.to_string()))?)?;
            let label = spec.label();
            (spec, law, label)
        }
        toml::Value::Table(t) => {
            if let Some(k) = t.keys().find(|k| !["law", "params", "preset", "spline", "end"].contains(&k.as_str())) {
                return Err(bad(format!("unknown key {k}: {LAW_FORMS}")));
            }
            let text = |k: &str| match t.get(k) {
                None => Ok(None),
                Some(toml::Value::String(s)) => Ok(Some(s.as_str())),
                Some(_) => Err(bad(format!("{k} must be a name in quotes"))),
            };
            let forms = ["law", "preset", "spline"].iter().filter(|k| t.contains_key(**k)).count();
            if forms != 1 {
                return Err(bad(format!("give one of law, preset or spline: {LAW_FORMS}")));
            }
            if t.contains_key("params") && !t.contains_key("law") {
                return Err(bad("params only with law = \"NAME\"".into()));
            }
            if t.contains_key("end") && !t.contains_key("spline") {
                return Err(bad("end only with spline = [[X, Y], …]".into()));
            }
            if let Some(name) = text("law")? {
                let params: BTreeMap<String, toml::Value> = match t.get("params") {
                    None => BTreeMap::new(),
                    Some(toml::Value::Table(p)) => p.clone().into_iter().collect(),
                    Some(_) => return Err(bad("params must be a table, e.g. { ramp = 0.1 }".into())),
                };
                let (spec, law) = built(LawSpec::parse_table(name, &params).map_err(|e| bad(e.to_string()))?)?;
                let label = spec.label();
                (spec, law, label)
            } else if let Some(name) = text("preset")? {
                let shed = loomkin_shed::preset(name).map_err(|e| bad(e.to_string()))?;
                let segments = shed.motion_segments().map_err(|e| bad(e.to_string()))?;
                let law = shed.build().map_err(|e| bad(e.to_string()))?;
                (LawSpec::Piecewise { segments }, law, format!("{} preset", name.trim()))
            } else {
                let points: Vec<[f64; 2]> = t
                    .get("spline")
                    .and_then(|v| v.clone().try_into().ok())
                    .ok_or_else(|| bad("spline: the definition points as [[X, Y], …] (numbers)".into()))?;
                let end = match text("end")? {
                    Some(e) => loomkin_servo::SplineEnd::parse(e).map_err(|e| bad(e.to_string()))?,
                    None => loomkin_servo::SplineEnd::default(),
                };
                let spline = loomkin_servo::SplineLaw::new(&points, end).map_err(|e| bad(e.to_string()))?;
                let segments = poly_segments_of(spline.law())
                    .ok_or_else(|| bad("the spline law has a segment that is not polynomial".into()))?;
                let (spec, law) = built(LawSpec::Polynomial { segments })?;
                (spec, law, format!("spline ({} points, {})", points.len(), end.name()))
            }
        }
        _ => return Err(bad(LAW_FORMS.into())),
    };
    Ok(GivenLaw { spec, law, field: field.to_string(), label })
}
