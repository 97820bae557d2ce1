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
        check_constants(&params)?;
        let design = Design::new(spec, params.constants())?;
        Ok(Self { params, spec, required: RequiredVelocity::default(), cam: Cam::Compound, design })
    }

    /// Jederán's mechanism and design (1959, §1.2): A ≈ 690 m/s², T' ≈ 0.033 s.
    pub fn paper_default() -> Self {
        // The paper's data are constants of this crate, valid by construction (tested), not input.
        Self::new(Params::paper(), DesignSpec::paper()).expect("the paper's mechanism is valid")
    }

    /// Reads a mechanism from TOML (an error is one line, `line L, column C: what`, without the
    /// source line, which may be huge): tables `[mechanism]` (the fields of [`Params`]), `[design]`
    /// (the fields of [`DesignSpec`]) and optionally `[required]` ([`RequiredVelocity`]).
    pub fn from_toml(text: &str) -> Result<Self> {
        let f: MechanismFile =
            toml::from_str(text).map_err(|e| PickError::Toml { reason: loomkin_units::toml_reason(text, &e) })?;
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

/// B, C, D (eq. 4) must be finite: an input inside its range may still overflow them (a return
/// spring compliance of 1e-320 m/N). The input to blame is the one whose paper value, put back
/// alone, makes them finite.
fn check_constants(params: &Params) -> Result<()> {
    let finite = |p: &Params| {
        let c = p.constants();
        [c.b_s2, c.c, c.d_m].iter().all(|v| v.is_finite())
    };
    if finite(params) {
        return Ok(());
    }
    let paper = Params::paper();
    type Field = (&'static str, fn(&Params) -> f64, fn(&mut Params, f64));
    let fields: [Field; 9] = [
        ("c1_m_per_n", |p| p.c1_m_per_n, |p, v| p.c1_m_per_n = v),
        ("c23_m_per_n", |p| p.c23_m_per_n, |p, v| p.c23_m_per_n = v),
        ("c4_m_per_n", |p| p.c4_m_per_n, |p, v| p.c4_m_per_n = v),
        ("theta_kg_m2", |p| p.theta_kg_m2, |p, v| p.theta_kg_m2 = v),
        ("shuttle_kg", |p| p.shuttle_kg, |p, v| p.shuttle_kg = v),
        ("k_m", |p| p.k_m, |p, v| p.k_m = v),
        ("r_m", |p| p.r_m, |p, v| p.r_m = v),
        ("checking_n", |p| p.checking_n, |p, v| p.checking_n = v),
        ("l_m", |p| p.l_m, |p, v| p.l_m = v),
    ];
    let blame = fields.iter().find(|(_, get, set)| {
        let mut trial = *params;
        set(&mut trial, get(&paper));
        trial.validate().is_ok() && finite(&trial)
    });
    let (field, get, _) = blame.unwrap_or(&fields[2]);
    Err(PickError::NonFiniteResult { field: (*field).into(), value: get(params), quantity: "B, C, D (eq. 4)".into() })
}

/// The designed pick and the mechanism's constants (`loomkin pick design --json`): the compound
/// law's `a_m_s2`, `mu_1_s`, `tau_s`, `t_end_s` (eqs. 18–20), the constants `b_s2`, `c`, `d_m`,
/// `natural_1_s` (eq. 4), the nominal `stroke_m`, the specification and the cam's label.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct DesignReport {
    /// A: peak (and second-stage) acceleration, m/s².
    pub a_m_s2: f64,
    /// μ: circular frequency of the sine stage, 1/s.
    pub mu_1_s: f64,
    /// τ = π/(2μ): end of the sine stage, s.
    pub tau_s: f64,
    /// T': end of the pick, s.
    pub t_end_s: f64,
    /// B, s².
    pub b_s2: f64,
    /// C.
    pub c: f64,
    /// D, m.
    pub d_m: f64,
    /// ψ = √((C+1)/B), 1/s.
    pub natural_1_s: f64,
    /// Nominal stroke s(T') − D, m.
    pub stroke_m: f64,
    /// V: shuttle velocity at the end of the pick, m/s.
    pub velocity_m_s: f64,
    /// X: distance of the pick, m.
    pub distance_m: f64,
    /// X₁: distance of the sine stage, m.
    pub first_stage_m: f64,
    /// Designed loom speed, rpm.
    pub speed_rpm: f64,
    /// Required velocity at the designed speed, m/s.
    pub required_velocity_m_s: f64,
    /// The cam law ([`crate::Cam::label`]).
    pub cam: String,
}

impl Mechanism {
    /// The designed pick and constants as one report.
    pub fn design_report(&self) -> DesignReport {
        let d = self.design();
        let (k, spec) = (d.constants, d.spec);
        DesignReport {
            a_m_s2: d.a_m_s2,
            mu_1_s: d.mu_1_s,
            tau_s: d.tau_s,
            t_end_s: d.t_end_s,
            b_s2: k.b_s2,
            c: k.c,
            d_m: k.d_m,
            natural_1_s: k.natural_1_s(),
            stroke_m: d.stroke_m(),
            velocity_m_s: spec.velocity_m_s,
            distance_m: spec.distance_m,
            first_stage_m: spec.first_stage_m,
            speed_rpm: spec.speed_rpm,
            required_velocity_m_s: self.required().at(spec.speed_rpm),
            cam: self.cam().label(),
        }
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
