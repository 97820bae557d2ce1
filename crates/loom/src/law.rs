//! The shedding law of every frame: a rise law for a frame going up, a fall law for one going
//! down, over one motion angle.

use crate::{LoomError, Result};
use loomkin_laws::{Cycle, CycleSpec, Law, LawSpec, SegmentKind};
use loomkin_shed::ShedLaw;

/// The law every frame follows when it changes place: a normalised rise (`s` from 0 to 1 over
/// `x ∈ [0, 1]`) for a frame going up and one for a frame going down (`y = top − H·s_fall(x)`),
/// over the motion angle `φ` of the main shaft.
#[derive(Debug, Clone)]
pub struct FrameLaw {
    rise_spec: LawSpec,
    rise: Law,
    fall_spec: LawSpec,
    fall: Law,
    motion_deg: f64,
    label: String,
}

impl FrameLaw {
    /// One law for both directions, from a shedding law of the shed crate (a preset or a
    /// piecewise law); its motion angle is the law's.
    pub fn from_shed(law: &ShedLaw, label: impl Into<String>) -> Result<Self> {
        let spec = LawSpec::Piecewise { segments: law.motion_segments()? };
        let built = law.build()?;
        Ok(Self {
            rise_spec: spec.clone(),
            rise: built.clone(),
            fall_spec: spec,
            fall: built,
            motion_deg: law.motion_deg(),
            label: label.into(),
        })
    }

    /// One catalogue law for both directions over `motion_deg`.
    pub fn from_spec(spec: &LawSpec, motion_deg: f64) -> Result<Self> {
        loomkin_shed::check_motion_deg(motion_deg)?;
        let built = spec.build()?;
        Ok(Self {
            rise_spec: spec.clone(),
            rise: built.clone(),
            fall_spec: spec.clone(),
            fall: built,
            motion_deg,
            label: spec.label(),
        })
    }

    /// The first rise and the first return of a machine cycle of the law core (their lengths must
    /// agree: one motion angle for every frame).
    pub fn from_cycle(spec: &CycleSpec) -> Result<Self> {
        let cycle = Cycle::new(spec)?;
        let find = |kind: SegmentKind| cycle.segments.iter().find(|s| s.kind == kind);
        let (Some(r), Some(f)) = (find(SegmentKind::Rise), find(SegmentKind::Return)) else {
            return Err(LoomError::field("shedding.cycle", "the cycle needs a rise and a return"));
        };
        let (rl, fl) = (r.length_rad.to_degrees(), f.length_rad.to_degrees());
        if (rl - fl).abs() > 1e-9 * rl.max(1.0) {
            return Err(LoomError::field(
                "shedding.cycle",
                format!("the rise lasts {rl}° and the return {fl}°: every frame move takes one motion angle"),
            ));
        }
        loomkin_shed::check_motion_deg(rl)?;
        let (Some((rs, rlaw)), Some((fs, flaw))) = (r.law.clone(), f.law.clone()) else {
            return Err(LoomError::field("shedding.cycle", "the rise and the return need laws"));
        };
        let label = if rs == fs { rs.label() } else { format!("rise {}, return {}", rs.label(), fs.label()) };
        Ok(Self { rise_spec: rs, rise: rlaw, fall_spec: fs, fall: flaw, motion_deg: rl, label })
    }

    /// The same law over another motion angle.
    pub fn with_motion_deg(mut self, motion_deg: f64) -> Result<Self> {
        self.motion_deg = loomkin_shed::check_motion_deg(motion_deg)?;
        Ok(self)
    }

    /// Motion angle `φ` in degrees of the main shaft.
    pub fn motion_deg(&self) -> f64 {
        self.motion_deg
    }

    /// The normalised law of a frame going up (`rising`) or down.
    pub fn law(&self, rising: bool) -> &Law {
        if rising { &self.rise } else { &self.fall }
    }

    /// The catalogue form of the law going up or down (what a cycle file of the law core holds).
    pub fn spec(&self, rising: bool) -> &LawSpec {
        if rising { &self.rise_spec } else { &self.fall_spec }
    }

    /// A short description.
    pub fn label(&self) -> &str {
        &self.label
    }
}
