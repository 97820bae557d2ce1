//! The cam: which nominal picker motion s(u) drives the mechanism.

use crate::{Design, Nominal, Result};
use loomkin_laws::{Law, LawSpec};
use loomkin_units::Range;
use serde::Serialize;

/// The nominal law the picking cam gives the picker, as a function of design time u.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "cam", rename_all = "kebab-case")]
pub enum Cam {
    /// The paper's compound law (sine, then constant acceleration of the shuttle), designed by
    /// eqs. 18–20 for the mechanism's constants; closed form available.
    Compound,
    /// A law of the core as the nominal picker motion: s(u) = D + stroke·law(u/rise) for
    /// 0 ≤ u ≤ rise, held at D + stroke after (numerical route only).
    Law {
        /// The catalogue law.
        spec: LawSpec,
        /// Nominal picker travel over the rise, m.
        stroke_m: f64,
        /// Duration of the rise at the designed loom speed, s.
        rise_s: f64,
    },
}

impl Cam {
    /// A short name: `compound` or the catalogue label.
    pub fn label(&self) -> String {
        match self {
            Cam::Compound => "compound".into(),
            Cam::Law { spec, .. } => spec.label(),
        }
    }
}

/// A cam made ready for evaluation.
#[derive(Debug, Clone)]
pub(crate) enum BuiltCam {
    Compound(Design),
    Law { law: Law, label: String, d_m: f64, stroke_m: f64, rise_s: f64 },
}

impl BuiltCam {
    pub(crate) fn new(cam: &Cam, design: &Design) -> Result<Self> {
        Ok(match cam {
            Cam::Compound => BuiltCam::Compound(*design),
            Cam::Law { spec, stroke_m, rise_s } => {
                Range::open_closed(0.0, 10.0, "m").check("stroke_m", *stroke_m)?;
                Range::open_closed(0.0, 10.0, "s").check("rise_s", *rise_s)?;
                BuiltCam::Law {
                    law: spec.build()?,
                    label: spec.label(),
                    d_m: design.constants.d_m,
                    stroke_m: *stroke_m,
                    rise_s: *rise_s,
                }
            }
        })
    }

    /// Nominal motion at design time `u` ≥ 0.
    #[inline]
    pub(crate) fn eval(&self, u: f64) -> Nominal {
        match self {
            BuiltCam::Compound(d) => d.nominal(u),
            BuiltCam::Law { law, d_m, stroke_m, rise_s, .. } => {
                if u >= *rise_s {
                    return Nominal { s_m: d_m + stroke_m, v_m_s: 0.0, a_m_s2: 0.0 };
                }
                let k = law.eval(u / rise_s);
                Nominal {
                    s_m: d_m + stroke_m * k.s,
                    v_m_s: stroke_m * k.v / rise_s,
                    a_m_s2: stroke_m * k.a / (rise_s * rise_s),
                }
            }
        }
    }

    /// Design time at which the cam's rise ends (T' for the compound law).
    pub(crate) fn end_u(&self) -> f64 {
        match self {
            BuiltCam::Compound(d) => d.t_end_s,
            BuiltCam::Law { rise_s, .. } => *rise_s,
        }
    }

    /// Design times inside the rise where the nominal acceleration may jump (stage joints).
    pub(crate) fn joints_u(&self) -> Vec<f64> {
        match self {
            BuiltCam::Compound(d) => vec![d.tau_s],
            BuiltCam::Law { law, rise_s, .. } => law.joints().map(|x| x * rise_s).collect(),
        }
    }

    /// Design time u at which the nominal travel s(u) − s(0) first reaches `travel_m` (≥ 0),
    /// or `None` if the cam never reaches it before the end of its rise. Bisection on the
    /// non-decreasing nominal motion, to the last bit of u.
    pub(crate) fn time_of_travel(&self, travel_m: f64) -> Option<f64> {
        let s0 = self.eval(0.0).s_m;
        if travel_m <= 0.0 {
            return Some(0.0);
        }
        let end = self.end_u();
        if self.eval(end).s_m - s0 < travel_m {
            return None;
        }
        Some(loomkin_numeric::bisect_bracket(0.0, end, |mid| self.eval(mid).s_m - s0 < travel_m).1)
    }

    /// Nominal travel available over the rise, s(end) − s(0), m.
    pub(crate) fn reach_m(&self) -> f64 {
        self.eval(self.end_u()).s_m - self.eval(0.0).s_m
    }
}
