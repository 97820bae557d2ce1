//! The α sweep of the paper (30…60°): analysis of a cam and synthesis of a law for each lever angle.

use super::analysis::{AnalysisOptions, analyze};
use super::cam::Cam;
use super::geometry::ModulatorGeometry;
use super::law::OutputLawSpec;
use super::synthesis::{SynthesisOptions, synthesize};
use crate::Result;
use loomkin_units::{Field, Range};
use serde::Serialize;

/// The α sweep as `loomkin dobby sweep --json` prints it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SweepReport<'a> {
    /// One row per lever angle.
    pub rows: &'a [SweepRow],
}

/// One lever angle of the sweep; a failed task leaves its fields `None` and gives its error text.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepRow {
    /// Lever angle α = θ (deg).
    pub alpha_deg: f64,
    /// Analysis error, if the cam cannot drive the mechanism at this α.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub an_error: Option<String>,
    /// Analysis: smallest ω6 (rad/s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub an_omega6_min_rad_s: Option<f64>,
    /// Analysis: largest ω6 (rad/s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub an_omega6_max_rad_s: Option<f64>,
    /// Analysis: largest output pressure angle (deg).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub an_mu_out_max_deg: Option<f64>,
    /// Analysis: largest pressure angle at roller B (deg).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub an_mu_b_max_deg: Option<f64>,
    /// Analysis: largest pressure angle at roller C (deg).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub an_mu_c_max_deg: Option<f64>,
    /// Analysis: smallest radius of curvature of the derived counter-cam Γ′ (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub an_rho_c_min_m: Option<f64>,
    /// Synthesis error, if the law cannot be built at this α.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub syn_error: Option<String>,
    /// Synthesis: largest pressure angle at roller B (deg).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub syn_mu_b_max_deg: Option<f64>,
    /// Synthesis: largest pressure angle at roller C (deg).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub syn_mu_c_max_deg: Option<f64>,
    /// Synthesis: smallest radius of curvature of Γ (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub syn_rho_b_min_m: Option<f64>,
    /// Synthesis: smallest radius of curvature of Γ′ (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub syn_rho_c_min_m: Option<f64>,
    /// Synthesis: undercut of either cam by the roller.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub syn_undercut: Option<bool>,
}

/// The α sweep's inputs: from, to, by (deg) and how many values.
pub struct AlphaSweep;

impl AlphaSweep {
    /// `from`: the first α, a lever angle (0°, 180°); 30° (the paper's range starts there).
    pub const FROM: Field =
        Field::new("from", Range::open(0.0, 180.0, "°"), "First α = θ: 0 < α < 180°; 30° (the paper's) when left out.")
            .with_default(30.0);
    /// `to`: the last α, (0°, 180°) and not below `from`; 60°.
    pub const TO: Field = Field::new(
        "to",
        Range::open(0.0, 180.0, "°"),
        "Last α = θ: 0 < α < 180°, not below from; 60° (the paper's) when left out.",
    )
    .with_default(60.0);
    /// `by`: the α step, > 0; 5°.
    pub const BY: Field = Field::new("by", Range::above(0.0, "°"), "α step: > 0°; 5° when left out.").with_default(5.0);
    /// `alpha_deg`: how many α a sweep takes, 1 … 1000 (each an analysis and a synthesis).
    pub const ALPHAS: Field = Field::count(
        "alpha_deg",
        Range::closed(1.0, 1000.0, ""),
        "Values of α in one sweep: 1 … 1000 (each an analysis and a synthesis).",
    );

    /// The α values `from, from + by, …` up to `to`, each named by `names` (the front end's
    /// from, to and by): at most [`AlphaSweep::ALPHAS`].
    pub fn values(names: [&str; 3], from: f64, to: f64, by: f64) -> Result<Vec<f64>> {
        Self::FROM.check_as(names[0], from)?;
        Self::TO.check_as(names[1], to)?;
        Self::BY.check_as(names[2], by)?;
        let key = |name: &str| name.trim_start_matches('-').replace('-', "_");
        if to < from {
            return Err(crate::MechError::Invalid {
                field: key(names[1]),
                reason: format!(
                    "{} {} {} {} {} {}: need from ≤ to and by > 0",
                    names[0],
                    loomkin_units::compact(from),
                    names[1],
                    loomkin_units::compact(to),
                    names[2],
                    loomkin_units::compact(by)
                ),
            });
        }
        let n = ((to - from) / by + 1e-9).floor() + 1.0;
        if !Self::ALPHAS.range.contains(n) {
            return Err(crate::MechError::Invalid {
                field: key(names[2]),
                reason: format!(
                    "{} {} gives {} values of α: allowed at most {}",
                    names[2],
                    loomkin_units::compact(by),
                    loomkin_units::compact(n),
                    Self::ALPHAS.range.describe("n").rsplit(' ').next().unwrap_or("")
                ),
            });
        }
        Ok((0..n as usize).map(|i| from + i as f64 * by).collect())
    }
}

/// Runs the analysis of `cam` and the synthesis of `law` for each α (θ = α) in `alphas_deg`.
/// Invalid options are errors; a mechanism that cannot be built at some α is reported in its row.
pub fn alpha_sweep(
    g: &ModulatorGeometry,
    cam: &Cam,
    law: &OutputLawSpec,
    alphas_deg: &[f64],
    an: &AnalysisOptions,
    syn: &SynthesisOptions,
) -> Result<Vec<SweepRow>> {
    let mut rows = Vec::with_capacity(alphas_deg.len());
    for &alpha in alphas_deg {
        let ga = g.with_alpha_deg(alpha)?;
        let mut row = SweepRow {
            alpha_deg: alpha,
            an_error: None,
            an_omega6_min_rad_s: None,
            an_omega6_max_rad_s: None,
            an_mu_out_max_deg: None,
            an_mu_b_max_deg: None,
            an_mu_c_max_deg: None,
            an_rho_c_min_m: None,
            syn_error: None,
            syn_mu_b_max_deg: None,
            syn_mu_c_max_deg: None,
            syn_rho_b_min_m: None,
            syn_rho_c_min_m: None,
            syn_undercut: None,
        };
        match analyze(&ga, cam, an) {
            Ok(a) => {
                let c = &a.summary.checks;
                row.an_omega6_min_rad_s = Some(c.omega6_min_rad_s);
                row.an_omega6_max_rad_s = Some(c.omega6_max_rad_s);
                row.an_mu_out_max_deg = Some(c.mu_out_max_deg);
                row.an_mu_b_max_deg = Some(c.mu_b_max_deg);
                row.an_mu_c_max_deg = Some(c.mu_c_max_deg);
                row.an_rho_c_min_m = c.rho_c_min_m;
            }
            Err(e @ crate::MechError::CannotBuild { .. }) => row.an_error = Some(e.to_string()),
            Err(e) => return Err(e),
        }
        match synthesize(&ga, law, syn) {
            Ok(s) => {
                let c = &s.summary.checks;
                row.syn_mu_b_max_deg = Some(c.mu_b_max_deg);
                row.syn_mu_c_max_deg = Some(c.mu_c_max_deg);
                row.syn_rho_b_min_m = c.rho_b_min_m;
                row.syn_rho_c_min_m = c.rho_c_min_m;
                row.syn_undercut = Some(s.summary.undercut);
            }
            Err(e @ crate::MechError::CannotBuild { .. }) => row.syn_error = Some(e.to_string()),
            Err(e) => return Err(e),
        }
        rows.push(row);
    }
    Ok(rows)
}
