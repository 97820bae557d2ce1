//! A shedding study as one value: the family of laws, the experiment design over its relative
//! lengths, the evaluated table and its Pareto front. The CLI (`shed table | pareto | best`) and
//! the workbench (`POST /api/shed/pareto`) both run it from here.

use crate::{
    Candidate, Conditions, Criteria, Dimensionless, PRESETS, Result, ShedError, Template, evaluate, evaluate_rows,
    fig1_design, grid_design, table1_design,
};
use loomkin_study::parts::PartError;
use loomkin_study::{Design, Progress};
use loomkin_units::Range;
use serde::{Deserialize, Serialize};

/// The named families of positive-phase shapes with free relative lengths.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Family {
    /// Rise, plateau, fall (3 parts).
    Trapezoid,
    /// Zero lead, rise, plateau, fall (4 parts).
    LeadTrapezoid,
    /// Linear rise, plateau, linear fall (3 parts).
    LinearTrapezoid,
}

impl Family {
    /// Kebab-case name (`lead-trapezoid`), as in files and requests.
    pub fn name(self) -> &'static str {
        match self {
            Self::Trapezoid => "trapezoid",
            Self::LeadTrapezoid => "lead-trapezoid",
            Self::LinearTrapezoid => "linear-trapezoid",
        }
    }

    /// The family's template.
    pub fn template(self) -> Template {
        match self {
            Self::Trapezoid => Template::trapezoid(),
            Self::LeadTrapezoid => Template::lead_trapezoid(),
            Self::LinearTrapezoid => Template::linear_trapezoid(),
        }
    }
}

/// Which experiment table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum DesignKind {
    /// The five named laws.
    Presets,
    /// The paper's Table 1 (eight three-part laws, k3 = 1 − k1 − k2).
    Table1,
    /// The family of the paper's Fig. 1: a lead k1 from 0 to 0.5, k2 = k4 = (1 − k1)/4, k3 = (1 − k1)/2.
    Fig1,
    /// The full grid over k_T1…k_Tn with a step, Σk = 1.
    Grid,
}

/// Step, least and largest relative length of a grid (the step also serves the Fig. 1 family).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GridSpec {
    /// Grid step of k.
    pub step: f64,
    /// Least relative length.
    pub min_k: f64,
    /// Largest relative length.
    pub max_k: f64,
}

impl GridSpec {
    /// The allowed relative length k of a part (fraction of the motion angle), and so of a grid's
    /// least and largest k.
    pub const K_RANGE: Range = Range::closed(0.0, 1.0, "");
    /// The allowed grid step of k: above 0, at most the whole motion.
    pub const STEP_RANGE: Range = Range::open_closed(0.0, 1.0, "");
    /// The paper's practical least relative length of a part, 0.005: a shorter part is a step of
    /// the acceleration in practice.
    pub const PRACTICAL_MIN_K: f64 = 0.005;

    /// The defaults of an experiment table or Pareto front: step 0.05, k ∈ [0.05, 0.9].
    pub const TABLE: Self = Self { step: 0.05, min_k: 0.05, max_k: 0.9 };
    /// The defaults of a search for the best law: step 0.01, k ∈ [0.01, 0.98].
    pub const BEST: Self = Self { step: 0.01, min_k: 0.01, max_k: 0.98 };
}

/// A family of laws and an experiment design over its relative lengths.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    /// The shapes whose lengths the design sets.
    pub template: Template,
    /// One row of relative lengths per law.
    pub design: Design,
}

impl Study {
    /// The design `kind` over `template` (default: the trapezoid family, or the lead trapezoid
    /// for [`DesignKind::Fig1`]); `grid` is used by [`DesignKind::Grid`] (all three values) and
    /// [`DesignKind::Fig1`] (its step). [`DesignKind::Presets`] has no design of lengths: it is an
    /// error here (see [`preset_table`]).
    pub fn new(kind: DesignKind, template: Option<Template>, grid: GridSpec) -> Result<Self> {
        let or = |default: fn() -> Template| template.clone().unwrap_or_else(default);
        let (template, design) = match kind {
            DesignKind::Table1 => (or(Template::trapezoid), table1_design()),
            DesignKind::Fig1 => (or(Template::lead_trapezoid), fig1_design(grid.step)?),
            DesignKind::Grid => {
                let t = or(Template::trapezoid);
                let d = grid_design(t.parts(), grid.min_k, grid.max_k, grid.step)?;
                (t, d)
            }
            DesignKind::Presets => {
                return Err(ShedError::Parse {
                    field: "design".into(),
                    reason: "the presets are named laws, not a design over a family's lengths".into(),
                });
            }
        };
        if design.dim() != template.parts() {
            return Err(ShedError::Parse {
                field: "family".into(),
                reason: format!(
                    "the {kind:?} design has {} lengths, the family '{}' {} parts",
                    design.dim(),
                    template.name(),
                    template.parts()
                ),
            });
        }
        Ok(Self { template, design })
    }

    /// The dimensionless criteria of every row (`None` where a row makes no law), in parallel.
    pub fn evaluate(&self, threshold: f64, progress: Progress) -> Result<Vec<Option<Dimensionless>>> {
        evaluate_rows(&self.template, &self.design, threshold, progress)
    }

    /// [`Study::evaluate`] that ends with [`crate::ShedError::Stopped`] once `stop` is set (a
    /// client gone, a time budget spent); run to its end it gives the same rows bit for bit.
    pub fn evaluate_until(
        &self,
        threshold: f64,
        progress: Progress,
        stop: &loomkin_units::StopFlag,
    ) -> Result<Vec<Option<Dimensionless>>> {
        crate::evaluate_rows_until(&self.template, &self.design, threshold, progress, 0..self.design.len(), stop)
    }

    /// Every law of the design at every motion angle, evaluated (see [`crate::table`]).
    pub fn table(&self, motions_deg: &[f64], cond: &Conditions, progress: Progress) -> Result<StudyTable> {
        self.table_in(motions_deg, cond, progress, 0..self.design.len())
    }

    /// [`Study::table`] of the design rows `items` only (one shard's share,
    /// [`loomkin_units::Shard::items`]), each at every motion angle.
    pub fn table_in(
        &self,
        motions_deg: &[f64],
        cond: &Conditions,
        progress: Progress,
        items: std::ops::Range<usize>,
    ) -> Result<StudyTable> {
        let rows = crate::evaluate_rows_in(&self.template, &self.design, cond.threshold(), progress, items)?;
        let rows = crate::table(&self.design, &rows, motions_deg, cond)?;
        Ok(StudyTable::unnamed(&self.design, rows))
    }

    /// The rows of [`Study::table_in`] made one at a time, in the same order and bit for bit: the
    /// laws of `items` are evaluated first (held: one set of criteria per law), then each row is
    /// made as the iterator is read, so a table of 10⁷ rows is printed without being held.
    pub fn rows_in<'a>(
        &'a self,
        motions_deg: &'a [f64],
        cond: &'a Conditions,
        progress: Progress,
        items: std::ops::Range<usize>,
    ) -> Result<impl Iterator<Item = StudyRow> + 'a> {
        let dims = crate::evaluate_rows_in(&self.template, &self.design, cond.threshold(), progress, items)?;
        crate::study::check_motions_at(motions_deg, cond)?;
        let design = &self.design;
        Ok(dims.into_iter().enumerate().filter_map(|(i, d)| d.map(|d| (i, d))).flat_map(move |(i, d)| {
            motions_deg.iter().map(move |&m| StudyRow {
                law: None,
                candidate: Candidate { row: i, lengths: design.row(i).to_vec(), criteria: Criteria::new(m, &d, cond) },
            })
        }))
    }

    /// The Pareto front (largest window, least peak acceleration) over the design and the motion
    /// angles (see [`crate::pareto`]).
    pub fn pareto(&self, motions_deg: &[f64], cond: &Conditions, progress: Progress) -> Result<StudyTable> {
        let rows = self.evaluate(cond.threshold(), progress)?;
        let front = crate::pareto(&self.design, &rows, motions_deg, cond)?;
        Ok(StudyTable::unnamed(&self.design, front))
    }
}

/// Seconds to evaluate one law of a design (its dwell and window roots, its exact extremes): the
/// `criteria_generic_one_law` bench (release, fastest of 100: 6.9 µs; the closed-form path of the
/// named families takes 0.51 µs), taken into estimates by [`loomkin_units::Cost::cpu_items`].
pub const STUDY_S_PER_LAW: f64 = 7e-6;
/// Bytes held per law of a design: its criteria (an `Option<Dimensionless>`) besides its lengths.
pub const STUDY_BYTES_PER_LAW: f64 = 112.0;

/// What a study will cost, estimated before its design is made.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StudyEstimate {
    /// Laws in the design (counted, not made: [`crate::grid_design_rows`]).
    pub laws: f64,
    /// Memory and time.
    pub cost: loomkin_units::Cost,
}

impl Study {
    /// The cost of a study of `kind` over a family of `parts` parts: the design made whole, the
    /// fraction `share` of its laws evaluated on `cores` threads, each at `motions` angles, each
    /// output row costing `row` (what the caller holds and spends per row: nothing held for a
    /// streamed table, the time to print it) — refuse it with [`loomkin_units::Budget::check`]
    /// before [`Study::new`] allocates anything.
    pub fn estimate(
        kind: DesignKind,
        parts: usize,
        grid: GridSpec,
        motions: usize,
        share: f64,
        row: loomkin_units::Cost,
        cores: usize,
    ) -> StudyEstimate {
        let laws = match kind {
            DesignKind::Table1 => 8.0,
            DesignKind::Presets => PRESETS.len() as f64,
            DesignKind::Fig1 if grid.step > 0.0 => (0.5 / grid.step + 1e-9).floor() + 1.0,
            DesignKind::Fig1 => 0.0,
            DesignKind::Grid => crate::grid_design_rows(parts, grid.min_k, grid.max_k, grid.step),
        };
        let (p, mine, rows) = (parts as f64, laws * share, laws * share * motions as f64);
        let cores = cores.max(1) as f64;
        // The design, the motion angles, the criteria of the evaluated laws, then the rows.
        let cost = loomkin_units::Cost::items(laws, p * 8.0, 0.0)
            .plus(loomkin_units::Cost::items(motions as f64, 8.0, 0.0))
            .plus(loomkin_units::Cost::cpu_items(mine, STUDY_BYTES_PER_LAW, STUDY_S_PER_LAW / cores))
            .plus(row.times(rows));
        StudyEstimate { laws, cost }
    }
}

/// One row of a study table: the preset's name (for named laws) and the candidate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyRow {
    /// The preset's name, for a table of named laws.
    pub law: Option<String>,
    /// Row of the design, lengths and criteria.
    pub candidate: Candidate,
}

/// An evaluated experiment table (or front).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyTable {
    /// Names of the length columns (`k1`, `k2`, …); empty for named laws.
    pub k_names: Vec<String>,
    /// The rows.
    pub rows: Vec<StudyRow>,
}

/// The criteria columns of [`StudyTable::to_csv`], in order (after the row and length columns).
pub const CRITERIA_COLUMNS: [&str; 18] = [
    "motion_deg",
    "dwell_deg",
    "conditional_dwell_deg",
    "window_deg",
    "threshold",
    "cv",
    "ca",
    "cj",
    "cm",
    "ca_rms",
    "ca_turn",
    "peak_velocity_m_s",
    "peak_accel_m_s2",
    "peak_jerk_m_s3",
    "peak_power_w_kg",
    "rms_accel_m_s2",
    "a_jump",
    "accel_jump_m_s2",
];

fn criteria_values(c: &Criteria) -> [f64; 18] {
    [
        c.motion_deg,
        c.dwell_deg,
        c.conditional_dwell_deg,
        c.window_deg,
        c.threshold,
        c.cv,
        c.ca,
        c.cj,
        c.cm,
        c.ca_rms,
        c.ca_turn,
        c.peak_velocity_m_s,
        c.peak_accel_m_s2,
        c.peak_jerk_m_s3,
        c.peak_power_w_kg,
        c.rms_accel_m_s2,
        c.a_jump,
        c.accel_jump_m_s2,
    ]
}

/// The five named laws evaluated under `cond`.
pub fn preset_table(cond: &Conditions) -> Result<StudyTable> {
    preset_table_in(cond, 0..PRESETS.len())
}

/// [`preset_table`] of the presets `items` only (rows keep their place in [`PRESETS`]).
pub fn preset_table_in(cond: &Conditions, items: std::ops::Range<usize>) -> Result<StudyTable> {
    let mut rows = Vec::new();
    let (lo, hi) = (items.start.min(PRESETS.len()), items.end.min(PRESETS.len()));
    for (row, p) in PRESETS.iter().enumerate().take(hi).skip(lo) {
        let law = p.law()?;
        let criteria = evaluate(&law, cond)?;
        let lengths = law.positive().iter().map(|s| s.length).collect();
        let candidate = Candidate { row, lengths, criteria };
        rows.push(StudyRow { law: Some(p.name.to_string()), candidate });
    }
    Ok(StudyTable { k_names: Vec::new(), rows })
}

impl StudyTable {
    fn unnamed(design: &Design, rows: Vec<Candidate>) -> Self {
        let rows = rows.into_iter().map(|candidate| StudyRow { law: None, candidate }).collect();
        Self { k_names: design.names().to_vec(), rows }
    }

    /// Whether the rows are named laws (presets) rather than rows of a design (which have length
    /// columns), also for a shard without rows.
    pub fn is_named(&self) -> bool {
        self.k_names.is_empty()
    }

    /// The table with only the rows at `indices` (e.g. a Pareto front of it).
    pub fn select(&self, indices: &[usize]) -> Self {
        Self { k_names: self.k_names.clone(), rows: indices.iter().map(|&i| self.rows[i].clone()).collect() }
    }

    /// The first non-finite length or criterion: `(row of the design, value)`.
    pub fn non_finite(&self) -> Option<(usize, f64)> {
        self.rows.iter().find_map(|r| {
            let c = &r.candidate;
            c.lengths.iter().chain(&criteria_values(&c.criteria)).find(|v| !v.is_finite()).map(|&v| (c.row, v))
        })
    }

    /// CSV: `law` (named laws) or `row` and the length columns, then [`CRITERIA_COLUMNS`]; numbers
    /// in shortest round-trip form (check [`StudyTable::non_finite`] first).
    pub fn to_csv(&self) -> String {
        self.to_csv_with(true)
    }

    /// [`StudyTable::to_csv`] with or without the header line (shards after the first).
    pub fn to_csv_with(&self, header_line: bool) -> String {
        let mut out = if header_line { csv_header(&self.k_names) } else { String::new() };
        for r in &self.rows {
            csv_line(r, self.is_named(), &mut out);
        }
        out
    }
}

/// The header line of [`StudyTable::to_csv`] (with its newline): `law` for named laws (no
/// `k_names`), else `row` and the length columns, then [`CRITERIA_COLUMNS`].
pub fn csv_header(k_names: &[String]) -> String {
    let mut header = vec![if k_names.is_empty() { "law" } else { "row" }.to_string()];
    header.extend(k_names.iter().cloned());
    header.extend(CRITERIA_COLUMNS.iter().map(|s| s.to_string()));
    let mut line = String::new();
    loomkin_io::csv::push_line(&mut line, &header);
    line
}

/// Appends one row of [`StudyTable::to_csv`] (with its newline) to `out`; `named`: a table of
/// named laws (no length columns).
pub fn csv_line(r: &StudyRow, named: bool, out: &mut String) {
    let c = &r.candidate;
    let first = r.law.clone().unwrap_or_else(|| c.row.to_string());
    let ks = if named { &[][..] } else { &c.lengths[..] };
    // `{}` display: the shortest text that reads back (a `-0` stays `-0`, as before).
    let values = ks.iter().chain(&criteria_values(&c.criteria)).map(|v| format!("{v}")).collect::<Vec<_>>();
    loomkin_io::csv::push_line(out, std::iter::once(first).chain(values));
}

/// The Pareto front (largest window, least peak acceleration) of a table of any size, read as a
/// stream from its CSV (`shed table --csv`: one file, the shards' outputs, the parts of
/// `--parts`, or standard input): what is held is the front, not the table. The rows, their order
/// and the numbers are those of [`Study::pareto`] (or of the presets' front) run on one machine
/// at the same conditions: the front of every (law, motion angle) row by its printed window and
/// acceleration, sorted by window (largest first), equal points in the order of the motion
/// angles, then of the rows. The table must have been made at `cond` (its threshold, and each
/// row's acceleration from its `ca` at `cond`'s stroke and speed), else it is refused.
pub fn front_of_table(
    lines: &loomkin_study::parts::Lines,
    cond: &Conditions,
) -> std::result::Result<StudyTable, PartError> {
    let bad = |m: String| PartError::Input(m);
    let k_names = std::cell::RefCell::new(Vec::<String>::new());
    let (named, width) = (std::cell::Cell::new(false), std::cell::Cell::new(0usize));
    let header = |h: &str| -> std::result::Result<(), PartError> {
        let cols: Vec<&str> = h.split(',').collect();
        let n = cols.len();
        let criteria_at = n.checked_sub(CRITERIA_COLUMNS.len()).filter(|&at| at >= 1);
        match (cols.first(), criteria_at) {
            (Some(&first), Some(at)) if (first == "law" || first == "row") && cols[at..] == CRITERIA_COLUMNS[..] => {
                named.set(first == "law");
                if named.get() && at > 1 {
                    return Err(bad("a table of named laws has no length columns".into()));
                }
                *k_names.borrow_mut() = cols[1..at].iter().map(|s| s.to_string()).collect();
                width.set(n);
                Ok(())
            }
            _ => Err(bad(format!(
                "the first line is not the header of shed table --csv (law or row, the length columns, then {})",
                CRITERIA_COLUMNS.join(",")
            ))),
        }
    };
    let mut front = loomkin_study::StreamFront::new([loomkin_study::Sense::Maximize, loomkin_study::Sense::Minimize]);
    // The motion angles in the order they first appear (a law's rows list them in order).
    let mut motions: std::collections::HashMap<u64, usize> = std::collections::HashMap::new();
    let scan = |path: &std::path::Path, n: u64, text: &str| -> std::result::Result<(), PartError> {
        let (named, width) = (named.get(), width.get());
        let name = path.display();
        let cols: Vec<&str> = text.split(',').collect();
        if cols.len() != width {
            return Err(bad(format!("{name}: line {n}: {} columns where the header has {width}", cols.len())));
        }
        let num = |t: &str| t.trim().parse::<f64>().ok().filter(|v| v.is_finite());
        let values: Option<Vec<f64>> = cols[1..].iter().map(|t| num(t)).collect();
        let Some(values) = values else {
            return Err(bad(format!("{name}: line {n}: not {} finite numbers after the first column", width - 1)));
        };
        let (lengths, c) = values.split_at(values.len() - CRITERIA_COLUMNS.len());
        let criteria = Criteria {
            motion_deg: c[0],
            dwell_deg: c[1],
            conditional_dwell_deg: c[2],
            window_deg: c[3],
            threshold: c[4],
            cv: c[5],
            ca: c[6],
            cj: c[7],
            cm: c[8],
            ca_rms: c[9],
            ca_turn: c[10],
            peak_velocity_m_s: c[11],
            peak_accel_m_s2: c[12],
            peak_jerk_m_s3: c[13],
            peak_power_w_kg: c[14],
            rms_accel_m_s2: c[15],
            a_jump: c[16],
            accel_jump_m_s2: c[17],
        };
        debug_assert_eq!(criteria_values(&criteria), *c);
        if criteria.threshold != cond.threshold()
            || criteria.peak_accel_m_s2 != criteria.ca * cond.scale(criteria.motion_deg, 2)
        {
            return Err(bad(format!(
                "{name}: line {n}: made at other conditions than these (threshold {}, or another stroke or speed): give the table's --threshold, --stroke-mm and --speed-rpm",
                criteria.threshold
            )));
        }
        let point = [criteria.window_deg, criteria.peak_accel_m_s2];
        let next = motions.len();
        let at = *motions.entry(criteria.motion_deg.to_bits()).or_insert(next);
        if !front.admits(point) {
            return Ok(());
        }
        let (law, row, lengths) = if named {
            // A named law's lengths are its preset's (the table prints its name only).
            let at = PRESETS
                .iter()
                .position(|p| p.name == cols[0])
                .ok_or_else(|| bad(format!("{name}: line {n}: '{}' is not a preset law", cols[0])))?;
            let law = PRESETS[at].law().map_err(|e| bad(e.to_string()))?;
            (Some(cols[0].to_string()), at, law.positive().iter().map(|s| s.length).collect())
        } else {
            let row = cols[0]
                .trim()
                .parse::<usize>()
                .map_err(|_| bad(format!("{name}: line {n}: row '{}' is not a row number", cols[0])))?;
            (None, row, lengths.to_vec())
        };
        let candidate = Candidate { row, lengths, criteria };
        front.push(point, ((if named { 0 } else { at }, row), StudyRow { law, candidate }));
        Ok(())
    };
    lines.for_each(header, scan)?;
    let mut rows = front.into_items();
    // As the one-machine front: by window (largest first), then acceleration, then the motion
    // angle's place and the row.
    rows.sort_by(|(ka, a), (kb, b)| {
        let (a, b) = (&a.candidate.criteria, &b.candidate.criteria);
        b.window_deg.total_cmp(&a.window_deg).then(a.peak_accel_m_s2.total_cmp(&b.peak_accel_m_s2)).then(ka.cmp(kb))
    });
    Ok(StudyTable { k_names: k_names.into_inner(), rows: rows.into_iter().map(|(_, r)| r).collect() })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn families_name_their_templates() {
        for f in [Family::Trapezoid, Family::LeadTrapezoid, Family::LinearTrapezoid] {
            assert_eq!(f.template(), Template::named(f.name()).unwrap());
            let json = serde_json::to_string(&f).unwrap();
            assert_eq!(json, format!("\"{}\"", f.name()));
        }
    }

    #[test]
    fn a_table_s_front_is_the_pareto_front_of_its_rows() {
        let cond = Conditions::new(0.95, 0.1, 300.0).unwrap();
        let s = Study::new(DesignKind::Grid, None, GridSpec { step: 0.1, ..GridSpec::TABLE }).unwrap();
        let all = s.table(&[240.0, 300.0], &cond, Progress::Hidden).unwrap();
        let front = s.pareto(&[240.0, 300.0], &cond, Progress::Hidden).unwrap();
        // Independent route: the non-dominated rows of the whole table, by brute force.
        let pts: Vec<[f64; 2]> =
            all.rows.iter().map(|r| [r.candidate.criteria.window_deg, -r.candidate.criteria.peak_accel_m_s2]).collect();
        let brute: Vec<[f64; 2]> = pts
            .iter()
            .filter(|p| !pts.iter().any(|q| q[0] >= p[0] && q[1] >= p[1] && (q[0] > p[0] || q[1] > p[1])))
            .copied()
            .collect();
        assert_eq!(front.rows.len(), brute.len());
        for r in &front.rows {
            let p = [r.candidate.criteria.window_deg, -r.candidate.criteria.peak_accel_m_s2];
            assert!(brute.contains(&p), "{p:?}");
        }
        assert_eq!(all.non_finite(), None);
        let csv = all.to_csv();
        assert!(csv.starts_with("row,k1,k2,k3,motion_deg,"));
        assert_eq!(csv.lines().count(), all.rows.len() + 1);
    }

    #[test]
    fn mismatched_designs_and_presets_are_refused() {
        let e = Study::new(DesignKind::Table1, Some(Template::lead_trapezoid()), GridSpec::TABLE).unwrap_err();
        assert!(e.to_string().starts_with("family: the Table1 design has 3 lengths"), "{e}");
        assert!(Study::new(DesignKind::Presets, None, GridSpec::TABLE).is_err());
        let cond = Conditions::new(0.95, 0.1, 300.0).unwrap();
        let t = preset_table(&cond).unwrap();
        assert!(t.is_named() && t.to_csv().starts_with("law,motion_deg,"));
        // Shards: the rows keep their place, only the first writes the header.
        let (a, b) = (preset_table_in(&cond, 0..2).unwrap(), preset_table_in(&cond, 2..5).unwrap());
        assert_eq!([a.rows.clone(), b.rows.clone()].concat(), t.rows);
        assert_eq!(a.to_csv_with(true) + &b.to_csv_with(false), t.to_csv());
    }
}
