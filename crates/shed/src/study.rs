//! Experiment tables of shedding laws: the paper's designs, full grids over `k_T1 … k_Tn`, the
//! Pareto front (largest window, least peak acceleration) and the constrained optimum.

use crate::criteria::check_scales;
use crate::{Conditions, Criteria, Dimensionless, Result, ShedError, Template, check_motion_deg};
use loomkin_study::{Design, Progress, Sense, argmin_subject_to, evaluate_design, pareto_front};
use loomkin_units::{Field, Range, StopFlag};
use serde::Serialize;

/// The paper's Table 1: eight three-part laws, `k1` (rise) and `k2` (plateau) as printed, and
/// `k3 = 1 − k1 − k2` (which comes out equal to `k1`: a modified-trapezoid family running from
/// nearly constant acceleration, `k1 = 0.05`, to the cycloidal law, `k1 = 0.5`).
pub fn table1_design() -> Design {
    const K1: [f64; 8] = [0.05, 0.10, 0.15, 0.20, 0.35, 0.40, 0.45, 0.50];
    const K2: [f64; 8] = [0.90, 0.80, 0.70, 0.60, 0.30, 0.20, 0.10, 0.00];
    let rows: Vec<Vec<f64>> = K1.iter().zip(K2).map(|(&a, b)| vec![a, b, 1.0 - a - b]).collect();
    Design::from_rows(["k1", "k2", "k3"], &rows).expect("three values per row")
}

/// The family of the paper's Fig. 1 (for [`Template::lead_trapezoid`]): the lead `k1` from 0 to
/// 0.5 with a step, `k2 = k4 = (1 − k1)/4`, `k3 = (1 − k1)/2`.
pub fn fig1_design(step: f64) -> Result<Design> {
    let axis = loomkin_study::stepped_axis("k1", 0.0, 0.5, step)?;
    let rows: Vec<Vec<f64>> =
        axis.iter().map(|&k1| vec![k1, (1.0 - k1) / 4.0, (1.0 - k1) / 2.0, (1.0 - k1) / 4.0]).collect();
    Ok(Design::from_rows(["k1", "k2", "k3", "k4"], &rows)?)
}

/// The full grid over `k_T1 … k_Tn` (`n = parts`): every `k_1 … k_{n−1}` on `min, min + step, …`,
/// `k_n = 1 − Σ`, all within `[min, max]` (the paper's practical range is 0.005 … 0.95).
pub fn grid_design(parts: usize, min: f64, max: f64, step: f64) -> Result<Design> {
    Ok(Design::simplex(parts, min, max, step)?)
}

/// The number of laws [`grid_design`] makes with these arguments, counted without making them
/// (for an estimate of memory and time before a study runs).
pub fn grid_design_rows(parts: usize, min: f64, max: f64, step: f64) -> f64 {
    loomkin_study::simplex_rows(parts, min, max, step)
}

/// Dimensionless criteria of every row of a design (`None` where the row makes no law, e.g. only
/// a zero-acceleration part), evaluated in parallel.
pub fn evaluate_rows(
    template: &Template,
    design: &Design,
    threshold: f64,
    progress: Progress,
) -> Result<Vec<Option<Dimensionless>>> {
    crate::check_threshold(threshold)?;
    if design.dim() != template.parts() {
        return Err(ShedError::Parse {
            field: "design".into(),
            reason: format!("the family has {} parts, the design {} columns", template.parts(), design.dim()),
        });
    }
    Ok(evaluate_design(design, progress, "laws", |k| template.evaluate(k, threshold).ok()))
}

/// [`evaluate_rows`] for the rows `items` of the design only (one shard's share,
/// [`loomkin_units::Shard::items`]): the result is as long as the design, `None` outside `items`,
/// and inside it equal to [`evaluate_rows`]' rows bit for bit.
pub fn evaluate_rows_in(
    template: &Template,
    design: &Design,
    threshold: f64,
    progress: Progress,
    items: std::ops::Range<usize>,
) -> Result<Vec<Option<Dimensionless>>> {
    evaluate_rows_until(template, design, threshold, progress, items, &StopFlag::default())
}

/// [`evaluate_rows_in`] that ends with [`ShedError::Stopped`] once `stop` is set (looked at
/// between chunks of laws, see [`loomkin_study::evaluate_indexed_until`]).
pub fn evaluate_rows_until(
    template: &Template,
    design: &Design,
    threshold: f64,
    progress: Progress,
    items: std::ops::Range<usize>,
    stop: &StopFlag,
) -> Result<Vec<Option<Dimensionless>>> {
    crate::check_threshold(threshold)?;
    if design.dim() != template.parts() {
        return Err(ShedError::Parse {
            field: "design".into(),
            reason: format!("the family has {} parts, the design {} columns", template.parts(), design.dim()),
        });
    }
    let (lo, hi) = (items.start.min(design.len()), items.end.min(design.len()));
    let part = loomkin_study::evaluate_indexed_until(hi.saturating_sub(lo), progress, "laws", stop, |i| {
        template.evaluate(design.row(lo + i), threshold).ok()
    })?;
    let mut out: Vec<Option<Dimensionless>> = vec![None; lo];
    out.extend(part);
    out.resize(design.len(), None);
    Ok(out)
}

/// One evaluated law of a table: its row in the design, its lengths and its criteria.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Candidate {
    /// Row of the design.
    pub row: usize,
    /// The relative lengths `k_T1 … k_Tn`.
    pub lengths: Vec<f64>,
    /// The criteria (with the motion angle).
    pub criteria: Criteria,
}

fn candidate(design: &Design, row: usize, motion_deg: f64, d: &Dimensionless, c: &Conditions) -> Candidate {
    Candidate { row, lengths: design.row(row).to_vec(), criteria: Criteria::new(motion_deg, d, c) }
}

fn check_motions(motions: &[f64]) -> Result<()> {
    if motions.is_empty() {
        return Err(ShedError::Parse { field: "motion_deg".into(), reason: "no motion angle given".into() });
    }
    motions.iter().try_for_each(|&m| check_motion_deg(m).map(|_| ()))
}

/// [`check_motions`] and finite physical values at every angle.
pub(crate) fn check_motions_at(motions: &[f64], conditions: &Conditions) -> Result<()> {
    check_motions(motions)?;
    motions.iter().try_for_each(|&m| check_scales(m, conditions))
}

/// Every row at every motion angle (rows that make no law are left out).
pub fn table(
    design: &Design,
    rows: &[Option<Dimensionless>],
    motions: &[f64],
    conditions: &Conditions,
) -> Result<Vec<Candidate>> {
    check_motions_at(motions, conditions)?;
    let mut out = Vec::new();
    for (i, d) in rows.iter().enumerate() {
        if let Some(d) = d {
            out.extend(motions.iter().map(|&m| candidate(design, i, m, d, conditions)));
        }
    }
    Ok(out)
}

/// The Pareto front of the rows at the given motion angles: no other law has both a window at
/// least as large and a peak acceleration at most as large (one strictly). Sorted by window,
/// largest first. Computed per motion angle, then over the union of those fronts.
pub fn pareto(
    design: &Design,
    rows: &[Option<Dimensionless>],
    motions: &[f64],
    conditions: &Conditions,
) -> Result<Vec<Candidate>> {
    pareto_within(design, rows, motions, conditions, None)
}

/// Whether a law at motion angle `motion_deg` keeps its peak jerk `h·Cj·(ω/Φ)³` within
/// `max_jerk_m_s3`; a law whose acceleration jumps has an unbounded jerk and never does (as in
/// [`best`]). Every law does when there is no limit.
pub fn within_jerk_limit(
    d: &Dimensionless,
    motion_deg: f64,
    max_jerk_m_s3: Option<f64>,
    conditions: &Conditions,
) -> bool {
    match max_jerk_m_s3 {
        None => true,
        Some(j) => !d.accel_jumps() && d.cj * conditions.scale(motion_deg, 3) <= j,
    }
}

/// The allowed jerk limit of [`pareto_within`] (m/s³): any positive number.
pub const JERK_LIMIT_RANGE: Range = Range::open_closed(0.0, f64::MAX, "m/s³");

/// [`pareto`] over the (law, motion angle) pairs [`within_jerk_limit`] only: the front an
/// engineer may choose from when the frame's drive bounds the jerk.
pub fn pareto_within(
    design: &Design,
    rows: &[Option<Dimensionless>],
    motions: &[f64],
    conditions: &Conditions,
    max_jerk_m_s3: Option<f64>,
) -> Result<Vec<Candidate>> {
    check_motions_at(motions, conditions)?;
    if let Some(j) = max_jerk_m_s3 {
        JERK_LIMIT_RANGE.check("max_jerk_m_s3", j)?;
    }
    let senses = [Sense::Maximize, Sense::Minimize];
    let mut pool: Vec<(usize, f64)> = Vec::new();
    for &m in motions {
        let ok: Vec<usize> = (0..rows.len())
            .filter(|&i| rows[i].as_ref().is_some_and(|d| within_jerk_limit(d, m, max_jerk_m_s3, conditions)))
            .collect();
        if ok.is_empty() {
            continue;
        }
        // The criteria's own window and acceleration (the numbers a table prints), so that the
        // front is exactly the front of the table's rows (`crate::front_of_table`).
        let pts: Vec<[f64; 2]> = ok
            .iter()
            .map(|&i| {
                let c = Criteria::new(m, rows[i].as_ref().expect("filtered"), conditions);
                [c.window_deg, c.peak_accel_m_s2]
            })
            .collect();
        pool.extend(pareto_front(&pts, &senses)?.into_iter().map(|j| (ok[j], m)));
    }
    if pool.is_empty() {
        return Ok(Vec::new());
    }
    let cands: Vec<Candidate> =
        pool.iter().map(|&(i, m)| candidate(design, i, m, rows[i].as_ref().expect("filtered"), conditions)).collect();
    let pts: Vec<[f64; 2]> = cands.iter().map(|c| [c.criteria.window_deg, c.criteria.peak_accel_m_s2]).collect();
    let mut front: Vec<Candidate> = pareto_front(&pts, &senses)?.into_iter().map(|j| cands[j].clone()).collect();
    front.sort_by(|a, b| b.criteria.window_deg.total_cmp(&a.criteria.window_deg));
    Ok(front)
}

/// Whether `a = [window_deg, peak_accel]` dominates `b`: a window at least as large and a peak
/// acceleration at most as large, one of them strictly.
pub fn dominates_in(a: &[f64; 2], b: &[f64; 2]) -> bool {
    loomkin_study::dominates(a, b, &[Sense::Maximize, Sense::Minimize])
}

/// Indices of the Pareto front of `[window_deg, peak_accel]` points (largest window, least
/// acceleration), in the order of decreasing window.
pub fn pareto_indices(points: &[[f64; 2]]) -> Result<Vec<usize>> {
    let mut f = pareto_front(points, &[Sense::Maximize, Sense::Minimize])?;
    f.sort_by(|&a, &b| points[b][0].total_cmp(&points[a][0]));
    Ok(f)
}

/// The required window of `shed best --window-deg`: `0 < W < 360°`, as 10⁻⁹ … 359.999° (the
/// window is reported to 0.001°, so a window of 360° − 0.001° is the widest one that leaves a
/// motion to read).
pub const WINDOW_DEG: Field = Field::new(
    "window_deg",
    Range::closed(1e-9, 359.999, "deg"),
    "Required clear-shed window φ_пп* of the law sought, deg: 1e-9 … 359.999 (a window of the whole turn \
     leaves no motion; windows are reported to 0.001°); no default (give it or the loom data).",
);

/// Checks a required window against [`WINDOW_DEG`].
pub fn check_window_deg(window_deg: f64) -> Result<f64> {
    Ok(WINDOW_DEG.check(window_deg)?)
}

/// The law of least peak acceleration whose window is at least `window_deg`.
///
/// With `motions = None` the motion angle is free: for a shape with window fraction `c`
/// (see [`Dimensionless::window_fraction`]) the window `360° − Φ(1 − c)` falls and the peak
/// acceleration `∝ Ca/Φ²` falls as `Φ` grows, so the best angle is the largest allowed,
/// `Φ* = min(360°, (360° − W)/(1 − c))`, and the search runs over the shapes only. With a list of
/// motion angles, every (shape, angle) pair is tried. `None` when no law qualifies.
///
/// Least acceleration alone drives the choice towards constant acceleration (Ca → 4) with its
/// jumps of acceleration; `max_jerk_m_s3` bounds the peak jerk `h·Cj·(ω/Φ)³` and excludes laws
/// whose acceleration jumps (checked at the chosen angle, where the jerk is least since it falls
/// as `Φ` grows).
pub fn best(
    design: &Design,
    rows: &[Option<Dimensionless>],
    motions: Option<&[f64]>,
    window_deg: f64,
    max_jerk_m_s3: Option<f64>,
    conditions: &Conditions,
) -> Result<Option<Candidate>> {
    check_window_deg(window_deg)?;
    if let Some(j) = max_jerk_m_s3 {
        JERK_LIMIT_RANGE.check("max_jerk_m_s3", j)?;
    }
    let jmax = max_jerk_m_s3.unwrap_or(f64::INFINITY);
    let jerk_ok =
        |d: &Dimensionless, m: f64| jmax.is_infinite() || (!d.accel_jumps() && d.cj * conditions.scale(m, 3) <= jmax);
    let h_w2 = conditions.scale(180.0, 2) * std::f64::consts::PI.powi(2);
    // Peak acceleration for a motion angle: h·Ca·ω²/Φ².
    let accel = |d: &Dimensionless, m: f64| d.ca * h_w2 / m.to_radians().powi(2);
    match motions {
        None => {
            let phi: Vec<Option<f64>> = rows
                .iter()
                .map(|d| {
                    d.as_ref().map(|d| {
                        let open = 1.0 - d.window_fraction();
                        if open <= 0.0 { 360.0 } else { ((360.0 - window_deg) / open).min(360.0) }
                    })
                })
                .collect();
            let idx: Vec<usize> = (0..rows.len()).collect();
            let best = argmin_subject_to(
                &idx,
                |&i| accel(rows[i].as_ref().expect("feasible"), phi[i].expect("feasible")),
                // The motion angle must be one a law may have (at least 1°: [`crate::MOTION_DEG`]).
                |&i| matches!(phi[i], Some(p) if crate::MOTION_DEG.contains(p) && jerk_ok(rows[i].as_ref().expect("some"), p)),
            );
            Ok(best.map(|i| {
                candidate(design, i, phi[i].expect("feasible"), rows[i].as_ref().expect("feasible"), conditions)
            }))
        }
        Some(ms) => {
            check_motions_at(ms, conditions)?;
            let pairs: Vec<(usize, f64)> =
                (0..rows.len()).filter(|&i| rows[i].is_some()).flat_map(|i| ms.iter().map(move |&m| (i, m))).collect();
            let d = |i: usize| rows[i].as_ref().expect("filtered");
            let best = argmin_subject_to(
                &pairs,
                |&(i, m)| accel(d(i), m),
                |&(i, m)| d(i).window_deg(m) >= window_deg && jerk_ok(d(i), m),
            );
            Ok(best.map(|j| {
                let (i, m) = pairs[j];
                candidate(design, i, m, d(i), conditions)
            }))
        }
    }
}

/// The motion angles of `shed table` when none are given (deg): 300, the paper's experiments'.
pub const TABLE_MOTION_DEG: &str = "300";
/// The motion angles of `shed pareto` when none are given (deg): 180 … 360 every 10.
pub const PARETO_MOTION_DEG: &str = "180:360:10";

/// Reads a list of motion angles: `300`, `180,270,300` or `MIN:MAX:STEP` (e.g. `180:360:10`),
/// each in (0, 360] deg.
pub fn parse_motion_angles(text: &str) -> Result<Vec<f64>> {
    let bad = |t: &str| ShedError::Parse {
        field: "motion_deg".into(),
        reason: format!("cannot read '{t}': expected DEG, DEG,DEG,… or MIN:MAX:STEP in degrees"),
    };
    let num = |t: &str| t.trim().parse::<f64>().map_err(|_| bad(text));
    let out: Vec<f64> = if text.contains(':') {
        let p: Vec<&str> = text.split(':').collect();
        if p.len() != 3 {
            return Err(bad(text));
        }
        loomkin_study::stepped_axis("motion_deg", num(p[0])?, num(p[1])?, num(p[2])?)?
    } else {
        text.split(',').map(num).collect::<Result<_>>()?
    };
    check_motions(&out)?;
    Ok(out)
}

#[cfg(test)]
mod jerk_limit_tests {
    use super::*;

    /// The front within a jerk limit: its members keep the limit, no admissible pair beats one of
    /// them in both criteria (checked by brute force over every pair), no limit gives the plain
    /// front, and a limit below every law leaves none.
    #[test]
    fn the_front_within_a_jerk_limit_is_the_front_of_the_admissible_laws() {
        let cond = Conditions::new(0.95, 0.1, 300.0).expect("conditions");
        let t = Template::linear_trapezoid();
        let design = grid_design(t.parts(), 0.0, 1.0, 0.08).expect("grid");
        let rows = evaluate_rows(&t, &design, cond.threshold(), Progress::Hidden).expect("rows");
        let motions = [200.0, 260.0];
        assert_eq!(
            pareto_within(&design, &rows, &motions, &cond, None).unwrap(),
            pareto(&design, &rows, &motions, &cond).unwrap()
        );
        let pairs: Vec<Candidate> = table(&design, &rows, &motions, &cond).unwrap();
        let jerks: Vec<f64> =
            pairs.iter().filter(|c| c.criteria.accel_jump_m_s2 == 0.0).map(|c| c.criteria.peak_jerk_m_s3).collect();
        assert!(!jerks.is_empty(), "some laws of the grid have no steps");
        let mut sorted = jerks.clone();
        sorted.sort_by(f64::total_cmp);
        let limit = sorted[sorted.len() / 2];
        let front = pareto_within(&design, &rows, &motions, &cond, Some(limit)).unwrap();
        assert!(!front.is_empty());
        let ok =
            |c: &Candidate| c.criteria.accel_jump_m_s2 == 0.0 && c.criteria.peak_jerk_m_s3 <= limit * (1.0 + 1e-12);
        for f in &front {
            assert!(ok(f), "front member over the limit: {:?}", f.criteria);
            let (w, a) = (f.criteria.window_deg, f.criteria.peak_accel_m_s2);
            let beaten = pairs.iter().filter(|c| ok(c)).any(|c| {
                let (cw, ca) = (c.criteria.window_deg, c.criteria.peak_accel_m_s2);
                cw >= w && ca <= a && (cw > w * (1.0 + 1e-12) || ca < a * (1.0 - 1e-12))
            });
            assert!(!beaten, "({w}, {a}) is dominated by an admissible law");
        }
        assert!(pareto_within(&design, &rows, &motions, &cond, Some(sorted[0] * 0.5)).unwrap().is_empty());
        assert!(pareto_within(&design, &rows, &motions, &cond, Some(0.0)).is_err());
    }
}
