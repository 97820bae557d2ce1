//! The weft carrier on the whole loom: the time budget of a loom file, and the carrier's
//! clearance in the shed over a pattern repeat.

use crate::{InsertionKind, Loom, LoomError, Motion, Pattern, Result, Timing};
use loomkin_insertion::{InsertionError, PickBudget, Rapier, RapierReport, WindowSource};
use loomkin_numeric::{Max, WordMap};
use loomkin_plot::{Figure, Note, Panel, Rule, Series, XBand, sig4};
use loomkin_units::ShaftSpeed;
use serde::Serialize;

/// The time budget of a loom file's carrier: its reed space and length, its mean speed at the
/// loom's speed, the loom's speed, and the window — the clear-shed window of `pattern` (as
/// `loom check` finds it) when one is given, else the file's entry and exit angles.
pub fn budget_of(loom: &Loom, pattern: Option<&Pattern>) -> Result<PickBudget> {
    let ins = &loom.insertion;
    let (window_deg, window_source) = match pattern {
        Some(p) => {
            let motion = Motion::new(loom, p)?;
            (Timing::new(loom, &motion, p)?.report()?.window_deg, WindowSource::ClearShed)
        }
        None => (ins.exit_deg - ins.entry_deg, WindowSource::EntryExit),
    };
    Ok(PickBudget {
        reed_width_mm: ins.written_mm[0],
        carrier_length_mm: ins.written_mm[1],
        window_deg,
        window_source,
        speed_m_s: ins.mean_speed_m_s(loom.speed.rpm()),
        speed_rpm: Some(loom.speed.rpm()),
        carrier_mass_g: None,
    })
}

/// A carrier's path through the shed in one turn of the main shaft: when it is in the shed and
/// where it is across the reed. The clearance over a repeat ([`clearance`]) takes any path: the
/// rapier's heads, a projectile's guide teeth.
pub trait CarrierPath {
    /// The main-shaft angles (deg, `from < to`, in a pick's turn, 0° the previous beat-up; they may
    /// reach below 0° or past 360°) between which the carrier is in the shed.
    fn in_shed_deg(&self) -> (f64, f64);
    /// Where the carrier is across the reed at `angle_deg`, m from the selvedge where the weft enters.
    fn position_m(&self, angle_deg: f64) -> f64;
}

impl CarrierPath for loomkin_insertion::Rapier {
    /// From the first head's entry to the last head's exit.
    fn in_shed_deg(&self) -> (f64, f64) {
        let spans: Vec<(f64, f64)> = (0..2).filter_map(|k| self.in_shed(k)).collect();
        let from = spans.iter().map(|s| s.0).fold(f64::INFINITY, f64::min);
        let to = spans.iter().map(|s| s.1).fold(f64::NEG_INFINITY, f64::max);
        (from.to_degrees(), to.to_degrees())
    }

    /// The bringer's tip while it is inside its selvedge, else the taker's (from the bringer's
    /// selvedge).
    fn position_m(&self, angle_deg: f64) -> f64 {
        let phi = angle_deg.to_radians();
        let b = self.tip(0, phi).u_m;
        if b >= 0.0 { b } else { self.reed_width_m - self.tip(1, phi).u_m }
    }
}

/// The least clearance of a carrier in the shed over a pattern repeat.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Clearance {
    /// The least clearance over every angle in the shed of every pick, mm (negative: it touches).
    pub min_clearance_mm: f64,
    /// The pick where it is least (1 = first; the first such pick).
    pub worst_pick: usize,
    /// The angle in that pick's turn, deg.
    pub worst_angle_deg: f64,
    /// Where the carrier is across the reed then, mm from the weft's entry selvedge.
    pub worst_position_mm: f64,
    /// The angles between which the carrier is in the shed, deg.
    pub in_shed_deg: [f64; 2],
    /// The distinct frame states (the picks whose frames move alike) computed.
    pub distinct_states: usize,
}

/// The shed seen by a carrier moving with the reed: its front edge's distance from the fell at
/// each angle (the reed's distance less the carrier's width; with a `[sley]`, the reed moves).
pub struct CarrierShed<'a> {
    timing: Timing<'a>,
    loom: &'a Loom,
}

impl<'a> CarrierShed<'a> {
    /// The shed of `loom` moving `motion` (weaving `pattern`).
    pub fn new(loom: &'a Loom, motion: &'a Motion, pattern: &Pattern) -> Result<Self> {
        Ok(Self { timing: Timing::new(loom, motion, pattern)?, loom })
    }

    /// The carrier's front edge from the fell at `angle_deg`, m: `x_r(φ) − w`, the reed at its
    /// insertion position (`geometry.reed_mm`) less the sley's displacement from its back dead centre.
    pub fn front_edge_m(&self, angle_deg: f64) -> f64 {
        let back = self.loom.geometry.reed_m - self.loom.insertion.carrier_width_m;
        match &self.loom.sley {
            Some(s) => back - s.reed(angle_deg.to_radians()).x_m,
            None => back,
        }
    }

    /// The clearance at `angle_deg` of pick `pick`'s turn, m: the clear shed at the front edge
    /// less the carrier's height.
    pub fn clearance_m(&self, pick: usize, angle_deg: f64) -> f64 {
        self.timing.clear_m(pick, self.front_edge_m(angle_deg), 360.0 * pick as f64 + angle_deg)
            - self.loom.insertion.carrier_height_m
    }
}

/// Grid step of the clearance's scan, deg: the local minima of the grid that could be the least
/// are refined by golden section.
const SCAN_STEP_DEG: f64 = 1.0;

/// The least clearance of `path` in the shed over every pick of `pattern`.
///
/// The clearance of pick `p` at angle φ is `x(φ)·(min_up y_i/d_i − max_down y_j/d_j) − h` (see
/// `loomkin_loom::timing`): the carrier's front edge `x(φ)` is the same in every pick, and frame `i`'s
/// slope `y_i/d_i` over the carrier's span depends only on what that frame does in the picks the
/// span reads (the move nearest each angle and the state before it). So the scan's 1° grid is
/// worked out once: the front edge once per angle, each frame's slopes once per distinct run of
/// its states, and a pick's grid is the min/max of its frames' rows — computed once per distinct
/// set of frame states (the picks that move alike). Every local minimum of the grids that could
/// be the least ([`loomkin_numeric::GridPeak::reach`] against the best value found so far) is
/// refined by golden section on the exact clearance; the span's ends are grid points.
pub fn clearance(loom: &Loom, pattern: &Pattern, path: &impl CarrierPath) -> Result<Clearance> {
    let motion = Motion::new(loom, pattern)?;
    let shed = CarrierShed::new(loom, &motion, pattern)?;
    let (from, to) = path.in_shed_deg();
    let picks = pattern.picks();
    // The picks (relative) whose states any frame's position in [from, to] reads, and the pick
    // itself (its sheets).
    let n = loom.frame_count();
    let rel = |a: f64, i: usize| ((a - motion.centre0_deg(i)) / 360.0).round() as i64;
    let lo = ((0..n).map(|i| rel(from, i)).min().unwrap_or(0) - 1).min(0);
    let hi = (0..n).map(|i| rel(to, i)).max().unwrap_or(0).max(0);
    let span = (hi - lo + 1) as usize;
    if span > 64 {
        return Err(LoomError::field(
            "insertion",
            format!("the carrier is in the shed from {from}° to {to}°: more than 64 picks' turns"),
        ));
    }
    let intervals = ((to - from) / SCAN_STEP_DEG).ceil().max(2.0) as usize;
    let nodes = intervals + 1;
    let angle = |j: usize| loomkin_numeric::grid_node(from, to, intervals, j);
    let edge: Vec<f64> = (0..nodes).map(|j| shed.front_edge_m(angle(j))).collect();
    // Rows of frame slopes (`nodes` each), one per frame and run of states, named by the run's
    // bits (bit q: up at pick p + lo + q; a frame meets a few runs: a short list is searched).
    let mut rows: Vec<f64> = Vec::new();
    let mut runs: Vec<Vec<(u64, u32)>> = vec![Vec::new(); n];
    let mut state = vec![0u32; n];
    let mut states: WordMap<Vec<u32>, usize> = WordMap::default();
    // Per distinct state: its first pick, and its grid's local minima that may be refined.
    let mut firsts: Vec<usize> = Vec::new();
    let mut peaks: Vec<(usize, usize, f64, [f64; 3])> = Vec::new();
    let mut best = Max { at: from, value: f64::NEG_INFINITY };
    // Per state, its largest −clearance found and where.
    let mut found: Vec<Max> = Vec::new();
    let (mut up_min, mut down_max, mut w) = (vec![0.0; nodes], vec![0.0; nodes], vec![0.0; nodes]);
    let h = loom.insertion.carrier_height_m;
    // Each frame's run of states at pick p: bit q is its state at pick p + lo + q, shifted in
    // pick by pick.
    let up = |i: usize, q: i64| motion.is_up(i, q);
    let mut bits: Vec<u64> =
        (0..n).map(|i| (0..span - 1).filter(|&q| up(i, lo + q as i64)).fold(0u64, |b, q| b | 1 << q)).collect();
    for p in 0..picks {
        let newest = (p as i64 + hi).rem_euclid(picks as i64);
        for (i, slot) in state.iter_mut().enumerate() {
            if p > 0 {
                bits[i] >>= 1;
            }
            bits[i] |= u64::from(up(i, newest)) << (span - 1);
            let run = bits[i];
            *slot = match runs[i].iter().find(|r| r.0 == run) {
                Some(r) => r.1,
                None => {
                    let id = (rows.len() / nodes) as u32;
                    let (base, d) = (360.0 * p as f64, loom.geometry.frame_m[i]);
                    rows.extend((0..nodes).map(|j| motion.frame(i, base + angle(j)).y_m / d));
                    runs[i].push((run, id));
                    id
                }
            };
        }
        if states.contains_key(&state) {
            continue;
        }
        let s = firsts.len();
        states.insert(state.clone(), s);
        firsts.push(p);
        found.push(Max { at: from, value: f64::NEG_INFINITY });
        // −clearance on the grid, as `Timing::clear_m` works it out: x·(lo_up − hi_down) − h.
        up_min.fill(f64::INFINITY);
        down_max.fill(f64::NEG_INFINITY);
        for (i, &id) in state.iter().enumerate() {
            let row = &rows[id as usize * nodes..][..nodes];
            if pattern.is_up(p, i) {
                up_min.iter_mut().zip(row).for_each(|(m, &y)| *m = m.min(y));
            } else {
                down_max.iter_mut().zip(row).for_each(|(m, &y)| *m = m.max(y));
            }
        }
        for j in 0..nodes {
            let clear = if up_min[j].is_finite() && down_max[j].is_finite() {
                edge[j] * (up_min[j] - down_max[j])
            } else {
                0.0
            };
            w[j] = -(clear - h);
        }
        for peak in loomkin_numeric::grid_peaks(&w) {
            let j = peak.index;
            offer(&mut found[s], &mut best, w[j], angle(j));
            if peak.reach >= best.value - TIE_M {
                let c = j.clamp(1, intervals - 1) - 1;
                peaks.push((s, j, peak.reach, [w[c], w[c + 1], w[c + 2]]));
            }
        }
    }
    // Refine, in the order of the picks, the minima that may still beat the best found. Picks of
    // different states often meet the same minimum (the same frames set the sheets' ends there):
    // brackets whose three nearest grid values are the same are the same parabola at the grid's
    // scale — what the reach already assumes — and are searched once.
    let mut searched: WordMap<[u64; 4], Max> = WordMap::default();
    for &(s, j, reach, near) in &peaks {
        if reach < best.value - TIE_M {
            continue;
        }
        let p = firsts[s];
        let (a, b) = (angle(j.saturating_sub(1)), angle((j + 1).min(intervals)));
        let key = [j as u64, near[0].to_bits(), near[1].to_bits(), near[2].to_bits()];
        let m = *searched.entry(key).or_insert_with(|| {
            let value = near[j + 1 - j.clamp(1, intervals - 1)];
            loomkin_numeric::golden_max_from(|t| -shed.clearance_m(p, t), a, b, (angle(j), value))
        });
        offer(&mut found[s], &mut best, m.value, m.at);
    }
    // The first pick whose least clearance is the least to within TIE_M (picks alike up to
    // rounding are one answer, the first).
    let s = found.iter().position(|m| m.value >= best.value - TIE_M).unwrap_or(0);
    let (pick, at) = (firsts[s], found[s].at);
    Ok(Clearance {
        min_clearance_mm: shed.clearance_m(pick, at) * 1e3,
        worst_pick: pick + 1,
        worst_angle_deg: at,
        worst_position_mm: path.position_m(at) * 1e3,
        in_shed_deg: [from, to],
        distinct_states: firsts.len(),
    })
}

/// Clearances of two picks closer than this are the same, m: the rounding of a pick's absolute
/// angle (360° times the pick) moves the clearance by ~10⁻¹⁶ m at 10⁴ picks.
const TIE_M: f64 = 1e-12;

/// Keeps `value` at `at` if it beats a state's best found so far, and the overall best.
fn offer(state: &mut Max, best: &mut Max, value: f64, at: f64) {
    if value > state.value {
        *state = Max { at, value };
    }
    if value > best.value {
        *best = Max { at, value };
    }
}

/// A carrier's error (rapier, projectile, air jet) as a loom error (the field kept).
pub(crate) fn insertion_error(e: InsertionError) -> LoomError {
    match e {
        InsertionError::Range(r) => LoomError::Range(r),
        other => field_error(other.field_name(), &other.to_string()),
    }
}

/// A carrier's `field: reason` message as a loom error on that field.
pub(crate) fn field_error(field: &str, text: &str) -> LoomError {
    let reason = text.strip_prefix(&format!("{field}: ")).unwrap_or(text).to_string();
    LoomError::field(field, reason)
}

/// Step of [`worst_pick_clearance`]'s samples, deg (at most: the span is cut into equal steps).
pub const CLEARANCE_CURVE_STEP_DEG: f64 = 0.5;

/// The clearance of the worst pick of `cl` (`cl.worst_pick`) while the carrier is in the shed:
/// `(angle deg, clearance mm)` from the span's start to its end, both included, at most
/// [`CLEARANCE_CURVE_STEP_DEG`] apart — what the carriers' plots and the workbench draw. The located
/// least value (`cl.min_clearance_mm`) is at or below every sample.
pub fn worst_pick_clearance(shed: &CarrierShed, cl: &Clearance) -> Vec<(f64, f64)> {
    let [from, to] = cl.in_shed_deg;
    let n = ((to - from) / CLEARANCE_CURVE_STEP_DEG).ceil().max(2.0) as usize;
    (0..=n)
        .map(|k| from + (to - from) * k as f64 / n as f64)
        .map(|a| (a, shed.clearance_m(cl.worst_pick - 1, a) * 1e3))
        .collect()
}

/// The clearance of the worst pick while the carrier is in the shed, its least value marked, with
/// `bands` (the span in the shed first).
pub(crate) fn clearance_panel(shed: &CarrierShed, cl: &Clearance, bands: Vec<XBand>) -> Panel {
    let worst = worst_pick_clearance(shed, cl);
    Panel::new(format!("clearance, pick {} [mm]", cl.worst_pick), vec![Series::line("clearance", worst)])
        .with_x_bands(bands)
        .with_rule(Rule::y(0.0, "touching").with_color(Rule::LIMIT))
        .with_notes([Note::new(
            cl.worst_angle_deg,
            cl.min_clearance_mm,
            format!("least {} mm at {}°", sig4(cl.min_clearance_mm), sig4(cl.worst_angle_deg)),
        )])
}

/// The colours of the selvedges' rules in the carriers' plots: the entering selvedge's and the far one's.
const SELVEDGE_COLORS: [[u8; 3]; 2] = [[0, 158, 115], [204, 121, 167]];

/// A panel of a position across the reed (mm) with the two selvedges as rules, each in its own
/// colour and named in the legend: `near` at 0, `far` at `width_mm`.
pub(crate) fn with_selvedges(panel: Panel, width_mm: f64, near: &str, far: &str) -> Panel {
    panel
        .with_rule(Rule::y(0.0, near).with_color(SELVEDGE_COLORS[0]))
        .with_rule(Rule::y(width_mm, far).with_color(SELVEDGE_COLORS[1]))
}

/// The loom file's rapier, or an error naming `insertion.kind` when its carrier is another.
pub fn rapier_of(loom: &Loom) -> Result<&Rapier> {
    match &loom.insertion.kind {
        InsertionKind::Rapier(r) => Ok(r),
        other => Err(LoomError::field(
            "insertion.kind",
            format!(
                "the loom's carrier is a {}: give kind = \"rapier\" with [insertion.rapier.bringer] and \
                 [insertion.rapier.taker] (docs/insertion.md)",
                other.name()
            ),
        )),
    }
}

/// The rapier of a loom on its shed: the heads' figures and their clearance over the repeat.
#[derive(Debug, Clone, Serialize)]
pub struct RapierCheck {
    /// The heads and the transfer.
    #[serde(flatten)]
    pub rapier: RapierReport,
    /// The clearance over every pick.
    #[serde(flatten)]
    pub clearance: Clearance,
    /// Picks in the repeat.
    pub picks: usize,
}

/// The rapier of `loom` at `speed` weaving `pattern`: [`Rapier::report`] and [`clearance`].
pub fn rapier_check(loom: &Loom, pattern: &Pattern, speed: ShaftSpeed) -> Result<RapierCheck> {
    let r = rapier_of(loom)?;
    let rapier = r.report(speed).map_err(insertion_error)?;
    let clearance = clearance(loom, pattern, r)?;
    Ok(RapierCheck { rapier, clearance, picks: pattern.picks() })
}

/// Points per turn of the rapier's plot.
const PLOT_POINTS: usize = 720;

/// The rapier's plot: both tips across the reed (from the bringer's selvedge), the heads' speeds,
/// and the clearance of the worst pick while a head is in the shed, its least value marked.
pub fn rapier_figure(loom: &Loom, pattern: &Pattern, c: &RapierCheck, speed: ShaftSpeed) -> Result<Figure> {
    let r = rapier_of(loom)?;
    let motion = Motion::new(loom, pattern)?;
    let shed = CarrierShed::new(loom, &motion, pattern)?;
    let w = speed.rad_per_s();
    let width_mm = r.reed_width_m * 1e3;
    let angles: Vec<f64> = (0..=PLOT_POINTS).map(|k| 360.0 * k as f64 / PLOT_POINTS as f64).collect();
    let tip = |k: usize, deg: f64| r.tip(k, deg.to_radians());
    let bringer: Vec<(f64, f64)> = angles.iter().map(|&a| (a, tip(0, a).u_m * 1e3)).collect();
    let taker: Vec<(f64, f64)> = angles.iter().map(|&a| (a, width_mm - tip(1, a).u_m * 1e3)).collect();
    let vb: Vec<(f64, f64)> = angles.iter().map(|&a| (a, tip(0, a).du * w)).collect();
    let vt: Vec<(f64, f64)> = angles.iter().map(|&a| (a, -tip(1, a).du * w)).collect();
    let cl = &c.clearance;
    let [from, to] = cl.in_shed_deg;
    let rep = &c.rapier;
    let transfer_at = rep.transfer_deg;
    let transfer_y = tip(0, transfer_at).u_m * 1e3;
    let panels = vec![
        with_selvedges(
            Panel::new(
                "tip across the reed [mm]",
                vec![Series::line("bringer", bringer), Series::line("taker", taker)],
            ),
            width_mm,
            "bringer's selvedge",
            "taker's selvedge",
        )
        .with_notes([Note::new(
            transfer_at,
            transfer_y,
            format!("overlap {} mm at {}°", sig4(rep.transfer_overlap_mm), sig4(transfer_at)),
        )]),
        Panel::new("velocity across the reed [m/s]", vec![Series::line("bringer", vb), Series::line("taker", vt)]),
        clearance_panel(&shed, cl, vec![XBand::new(from, to, "a head in the shed", XBand::WINDOW)]),
    ];
    let title = format!(
        "rapier at {} rpm: overlap {} mm, peak head speed {} m/s, least clearance {} mm (pick {})",
        sig4(speed.rpm()),
        sig4(rep.transfer_overlap_mm),
        sig4(rep.peak_head_speed_m_s),
        sig4(cl.min_clearance_mm),
        cl.worst_pick
    );
    Ok(Figure::new(title, "main-shaft angle [deg]", panels))
}
