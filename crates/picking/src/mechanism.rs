//! A picking mechanism with its cam: the physical parameters, the design and the cam law.

use crate::cam::BuiltCam;
use crate::{Cam, Design, DesignSpec, Params, PickError, RequiredVelocity, Result};
use loomkin_laws::LawSpec;
use serde::{Deserialize, Serialize};

/// A picking mechanism together with the design its cam was made for.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Mechanism {
    params: Params,
    spec: DesignSpec,
    required: RequiredVelocity,
    cam: Cam,
    design: Design,
}

/// The TOML description of a mechanism (all SI; see `docs/picking.md`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MechanismFile {
    mechanism: Params,
    design: DesignSpec,
    #[serde(default)]
    required: Option<RequiredVelocity>,
}

impl Mechanism {
    /// Builds and validates a mechanism with the compound cam designed for `spec`.
    pub fn new(params: Params, spec: DesignSpec) -> Result<Self> {
        params.validate()?;
        let design = Design::new(spec, params.constants())?;
        Ok(Self { params, spec, required: RequiredVelocity::default(), cam: Cam::Compound, design })
    }

    /// Jederán's mechanism and design (1959, §1.2): A ≈ 690 m/s², T' ≈ 0.033 s.
    pub fn paper_default() -> Self {
        // The paper's data are constants of this crate, valid by construction (tested), not input.
        Self::new(Params::paper(), DesignSpec::paper()).expect("the paper's mechanism is valid")
    }

    /// Reads a mechanism from TOML: tables `[mechanism]` (the fields of [`Params`]), `[design]`
    /// (the fields of [`DesignSpec`]) and optionally `[required]` ([`RequiredVelocity`]).
    pub fn from_toml(text: &str) -> Result<Self> {
        let f: MechanismFile = toml::from_str(text).map_err(|e| PickError::Toml { reason: e.to_string() })?;
        let m = Self::new(f.mechanism, f.design)?;
        match f.required {
            Some(r) => m.with_required(r),
            None => Ok(m),
        }
    }

    /// Replaces the required-velocity inputs.
    pub fn with_required(mut self, required: RequiredVelocity) -> Result<Self> {
        required.validate()?;
        self.required = required;
        Ok(self)
    }

    /// Replaces the cam law (checked by building it once).
    pub fn with_cam(mut self, cam: Cam) -> Result<Self> {
        BuiltCam::new(&cam, &self.design)?;
        self.cam = cam;
        Ok(self)
    }

    /// Uses a catalogue law as the nominal picker motion with the compound design's stroke
    /// s(T') − D and rise time T', so the two cams cover the same travel in the same time.
    pub fn with_law(self, spec: LawSpec) -> Result<Self> {
        let (stroke_m, rise_s) = (self.design.stroke_m(), self.design.t_end_s);
        self.with_cam(Cam::Law { spec, stroke_m, rise_s })
    }

    /// The physical parameters.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The design specification.
    pub fn design_spec(&self) -> &DesignSpec {
        &self.spec
    }

    /// The designed compound law (A, μ, τ, T' and the constants B, C, D it was designed for).
    pub fn design(&self) -> &Design {
        &self.design
    }

    /// The cam law in use.
    pub fn cam(&self) -> &Cam {
        &self.cam
    }

    /// The required-velocity inputs.
    pub fn required(&self) -> &RequiredVelocity {
        &self.required
    }

    pub(crate) fn built_cam(&self) -> Result<BuiltCam> {
        BuiltCam::new(&self.cam, &self.design)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn toml_round_trip_of_the_paper() {
        let m = Mechanism::paper_default();
        let text = format!(
            "[mechanism]\n{}\n[design]\n{}",
            toml::to_string(m.params()).unwrap(),
            toml::to_string(m.design_spec()).unwrap()
        );
        let r = Mechanism::from_toml(&text).unwrap();
        assert_eq!(r.design(), m.design());
    }

    #[test]
    fn toml_errors_are_clear() {
        let e = Mechanism::from_toml("[mechanism]\nc1_m_per_n = 1\n").unwrap_err().to_string();
        assert!(e.starts_with("mechanism file:"), "{e}");
        let m = Mechanism::paper_default();
        let mut p = *m.params();
        p.k_m = 1.0;
        let text = format!(
            "[mechanism]\n{}\n[design]\n{}",
            toml::to_string(&p).unwrap(),
            toml::to_string(m.design_spec()).unwrap()
        );
        assert!(Mechanism::from_toml(&text).unwrap_err().to_string().contains("k_m"));
    }
}
