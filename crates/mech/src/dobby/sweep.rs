//! The α sweep of the paper (30…60°): analysis of a cam and synthesis of a law for each lever angle.

use super::analysis::{AnalysisOptions, analyze};
use super::cam::Cam;
use super::geometry::ModulatorGeometry;
use super::law::OutputLawSpec;
use super::synthesis::{SynthesisOptions, synthesize};
use crate::Result;
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
