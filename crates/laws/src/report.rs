//! What `loomkin law list | info --json` print and the Python module returns: the reports as
//! structs that serialise themselves, so both front ends give one value one key.

use crate::catalogue::{CATALOGUE, LawSpec, ParamValue};
use crate::continuity::{Continuity, Joint};
use crate::error::Result;
use crate::law::Law;
use crate::metrics::Metrics;
use serde::Serialize;
use std::collections::BTreeMap;

/// Which of s, v, a, j are continuous at a joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct ContinuousFlags {
    /// Displacement.
    pub s: bool,
    /// Velocity.
    pub v: bool,
    /// Acceleration.
    pub a: bool,
    /// Jerk.
    pub j: bool,
}

/// A joint of the continuity report: the jumps (right − left) and what is continuous.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct JointReport {
    /// Where (fraction of the motion angle).
    pub x: f64,
    /// Jump of s.
    pub ds: f64,
    /// Jump of v.
    pub dv: f64,
    /// Jump of a.
    pub da: f64,
    /// Jump of j.
    pub dj: f64,
    /// Which are continuous ([`Joint::flags`]).
    pub continuous: ContinuousFlags,
    /// Highest derivative continuous there (−1: s jumps).
    pub continuous_up_to: i32,
}

impl From<&Joint> for JointReport {
    fn from(j: &Joint) -> Self {
        let [s, v, a, jj] = j.flags();
        Self {
            x: j.x,
            ds: j.ds,
            dv: j.dv,
            da: j.da,
            dj: j.dj,
            continuous: ContinuousFlags { s, v, a, j: jj },
            continuous_up_to: j.continuous_up_to,
        }
    }
}

/// A law's continuity report (`law info --json`'s `continuity`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContinuityReport {
    /// Continuity class in a dwell-rise-dwell cycle.
    pub class: i32,
    /// At x = 0 against a dwell at s = 0.
    pub start: JointReport,
    /// At every joint of the segments.
    pub joints: Vec<JointReport>,
    /// At x = 1 against a dwell at s = 1.
    pub end: JointReport,
}

impl From<&Continuity> for ContinuityReport {
    fn from(c: &Continuity) -> Self {
        Self {
            class: c.class,
            start: (&c.start).into(),
            joints: c.joints.iter().map(JointReport::from).collect(),
            end: (&c.end).into(),
        }
    }
}

/// One law of the catalogue with its metrics (`law list --json`'s `laws`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ListedLaw {
    /// Catalogue name.
    pub name: &'static str,
    /// One-line description.
    pub description: &'static str,
    /// Its parameters (empty: none).
    pub params: &'static str,
    /// Metrics at the default parameters (dimensionless).
    #[serde(flatten)]
    pub metrics: Metrics,
    /// Continuity class in a dwell-rise-dwell cycle.
    pub continuity_class: i32,
}

impl ListedLaw {
    /// Every catalogue law that needs no parameter given, built at its defaults, in catalogue
    /// order.
    pub fn catalogue() -> Result<Vec<Self>> {
        CATALOGUE
            .iter()
            .filter(|e| !e.required)
            .map(|e| {
                let law = LawSpec::parse::<&str, &str>(e.name, &[])?.build()?;
                Ok(Self {
                    name: e.name,
                    description: e.description,
                    params: e.params,
                    metrics: law.metrics(),
                    continuity_class: law.continuity().class,
                })
            })
            .collect()
    }
}

/// Everything about one law (`law info --json`): parameters typed (`"ramp": 0.1`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InfoReport {
    /// Catalogue name.
    pub law: String,
    /// Its parameters.
    pub params: BTreeMap<String, ParamValue>,
    /// Its metrics (dimensionless).
    #[serde(flatten)]
    pub metrics: Metrics,
    /// Segments of the law.
    pub segments: usize,
    /// Its continuity report.
    pub continuity: ContinuityReport,
}

impl InfoReport {
    /// The report of `law`, named `name` with `params` (metrics and continuity computed here).
    pub fn new(name: &str, params: BTreeMap<String, ParamValue>, law: &Law) -> Self {
        Self {
            law: name.to_string(),
            params,
            metrics: law.metrics(),
            segments: law.segments().len(),
            continuity: (&law.continuity()).into(),
        }
    }
}
