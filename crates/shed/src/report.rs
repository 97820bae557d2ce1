//! What `loomkin shed list | law | table | pareto | best | window --json` print and the Python
//! module returns: the reports as structs that serialise themselves, so both front ends give one
//! value one key.

use crate::conditions::Conditions;
use crate::criteria::Criteria;
use crate::experiment::StudyRow;
use crate::presets::PRESETS;
use crate::requirement::LoomRequirement;
use crate::shedlaw::ShedLaw;
use crate::{Result, Template};
use serde::Serialize;

/// Criteria with the stroke (mm) and speed (rpm) they were evaluated at.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CriteriaReport<'a> {
    /// The criteria.
    #[serde(flatten)]
    pub criteria: &'a Criteria,
    /// Stroke (mm).
    pub stroke_mm: f64,
    /// Main-shaft speed (rpm).
    pub speed_rpm: f64,
}

impl<'a> CriteriaReport<'a> {
    /// `criteria` at `cond`.
    pub fn of(criteria: &'a Criteria, cond: &Conditions) -> Self {
        Self { criteria, stroke_mm: cond.stroke_m() * 1000.0, speed_rpm: cond.speed_rpm() }
    }
}

/// A law's definition: motion angle (deg), symmetry and both phases as text.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Definition {
    /// Motion angle (deg).
    pub motion_deg: f64,
    /// The negative phase mirrors the positive one.
    pub symmetric: bool,
    /// Share of the motion in the positive phase.
    pub positive_fraction: f64,
    /// The positive phase, `LEN:SHAPE[:LEVEL…],…`.
    pub positive: String,
    /// The negative phase.
    pub negative: String,
}

impl Definition {
    /// The definition of `law`.
    pub fn of(law: &ShedLaw) -> Self {
        Self {
            motion_deg: law.motion_deg(),
            symmetric: law.is_symmetric(),
            positive_fraction: law.positive_fraction(),
            positive: law.positive_text(),
            negative: law.negative_text(),
        }
    }
}

/// One preset (`shed list --json`'s `laws`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PresetReport {
    /// Name used in the library and the CLI.
    pub name: &'static str,
    /// The paper's Russian name.
    pub name_ru: &'static str,
    /// Motion angle (deg).
    pub motion_deg: f64,
    /// Dwell, 360° less the motion (deg).
    pub dwell_deg: f64,
    /// The shape as Table 3 writes it.
    pub table_shape: &'static str,
    /// Positive phase of the acceleration.
    pub positive: &'static str,
}

impl PresetReport {
    /// Every preset, in [`PRESETS`] order.
    pub fn all() -> Vec<Self> {
        PRESETS
            .iter()
            .map(|p| Self {
                name: p.name,
                name_ru: p.name_ru,
                motion_deg: p.motion_deg,
                dwell_deg: 360.0 - p.motion_deg,
                table_shape: p.table_shape,
                positive: p.positive,
            })
            .collect()
    }
}

/// One law evaluated (`shed law --json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LawReport<'a> {
    /// The law's name (a preset, or the spec file's name).
    pub law: String,
    /// Its criteria.
    #[serde(flatten)]
    pub criteria: CriteriaReport<'a>,
    /// Its definition.
    pub definition: Definition,
    /// The positive phase as text.
    pub segments: String,
}

impl<'a> LawReport<'a> {
    /// `law`, named `name`, with its `criteria` at `cond`.
    pub fn new(name: String, law: &ShedLaw, criteria: &'a Criteria, cond: &Conditions) -> Self {
        Self {
            law: name,
            criteria: CriteriaReport::of(criteria, cond),
            definition: Definition::of(law),
            segments: law.positive_text(),
        }
    }
}

/// One row of `shed table | pareto --json`: the preset's name or the design row, the criteria and
/// the lengths.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowReport<'a> {
    /// The preset's name (a table of named laws).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub law: Option<&'a str>,
    /// The design's row (a table of a family).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub row: Option<usize>,
    /// The criteria.
    #[serde(flatten)]
    pub criteria: CriteriaReport<'a>,
    /// Relative lengths of the positive phase's parts.
    pub lengths: &'a [f64],
}

impl StudyRow {
    /// The row as reported at `cond`.
    pub fn report<'a>(&'a self, cond: &Conditions) -> RowReport<'a> {
        RowReport {
            law: self.law.as_deref(),
            row: self.law.is_none().then_some(self.candidate.row),
            criteria: CriteriaReport::of(&self.candidate.criteria, cond),
            lengths: &self.candidate.lengths,
        }
    }
}

/// The law of least peak acceleration for a window (`shed best --json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BestReport<'a> {
    /// The law's criteria.
    #[serde(flatten)]
    pub criteria: CriteriaReport<'a>,
    /// The window asked for (deg).
    pub required_window_deg: f64,
    /// The family searched.
    pub family: &'a str,
    /// The law's relative lengths.
    pub lengths: &'a [f64],
    /// Its positive phase as text.
    pub segments: String,
    /// Its definition.
    pub definition: Definition,
    /// Laws of the family searched.
    pub laws_searched: usize,
    /// The jerk limit, if one was set (m/s³).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_jerk_m_s3: Option<f64>,
    /// The loom data the window came from, if it did.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub loom: Option<&'a LoomRequirement>,
}

/// What [`BestReport::new`] reports beside the law found.
#[derive(Debug, Clone, Copy)]
pub struct BestSearch<'a> {
    /// The family searched.
    pub template: &'a Template,
    /// Laws of the family searched.
    pub laws_searched: usize,
    /// The window asked for (deg).
    pub required_window_deg: f64,
    /// The jerk limit (m/s³).
    pub max_jerk_m_s3: Option<f64>,
    /// The loom data the window came from.
    pub loom: Option<&'a LoomRequirement>,
}

impl<'a> BestReport<'a> {
    /// The candidate `row` found by `search`, `law` its law (`search.template.law(motion, lengths)`),
    /// at `cond`.
    pub fn new(search: BestSearch<'a>, row: &'a crate::Candidate, law: &ShedLaw, cond: &Conditions) -> Self {
        Self {
            criteria: CriteriaReport::of(&row.criteria, cond),
            required_window_deg: search.required_window_deg,
            family: search.template.name(),
            lengths: &row.lengths,
            segments: law.positive_text(),
            definition: Definition::of(law),
            laws_searched: search.laws_searched,
            max_jerk_m_s3: search.max_jerk_m_s3,
            loom: search.loom,
        }
    }
}

/// The window a loom needs (`shed window --json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WindowReport<'a> {
    /// The loom data.
    #[serde(flatten)]
    pub loom: &'a LoomRequirement,
    /// Flight of the carrier through the warp (deg).
    pub flight_deg: f64,
    /// The window needed (deg).
    pub required_window_deg: f64,
    /// The dwell threshold.
    pub threshold: f64,
    /// The threshold with both sheets moving.
    pub threshold_both_sheets: f64,
}

impl<'a> WindowReport<'a> {
    /// The window `loom` needs.
    pub fn of(loom: &'a LoomRequirement) -> Result<Self> {
        Ok(Self {
            loom,
            flight_deg: loom.flight_deg(),
            required_window_deg: loom.required_window_deg()?,
            threshold: loom.threshold(),
            threshold_both_sheets: loom.threshold_both_sheets(),
        })
    }
}
