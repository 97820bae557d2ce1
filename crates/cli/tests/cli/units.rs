//! Units on every number of a `--json` output (the project's standard: the unit in the key,
//! `_mm`, `_deg`, `_n_m`, `_rpm` …). A key without one is either listed below as dimensionless,
//! a count or an index, or sits in an object that states its unit (a `unit` key beside it, or a
//! parent key that ends in a unit). Checked on every `--json` command of README.md and docs/*.md
//! (docs.rs).

use serde_json::Value;

/// A unit at the end of a key (`peak_torque_n_m`, `omega6_rad_s`, `slave_v_mm_per_deg`, …).
fn has_unit(key: &str) -> bool {
    const UNITS: [&str; 42] = [
        "_mm",
        "_m",
        "_cm",
        "_deg",
        "_rad",
        "_s",
        "_ms",
        "_rpm",
        "_hz",
        "_n",
        "_nm",
        "_n_m",
        "_w",
        "_kg",
        "_g",
        "_kgf",
        "_pct",
        "_s2",
        "_1_s",
        "_m_s",
        "_m_s2",
        "_m_s3",
        "_rad_s",
        "_rad_s2",
        "_deg_s",
        "_kg_m2",
        "_n_s_m",
        "_w_kg",
        "_per_mm",
        "_per_deg",
        "_per_deg2",
        "_per_deg3",
        "_pct_of_stroke",
        "_m2",
        "_n_m_s",
        "_j",
        "_mm_s",
        "_percent",
        "_per_s",
        "_bytes",
        "_a",
        "_per_min",
    ];
    // A quantity before and after a change (`max_timing_error_deg_before`, issue 29's keys).
    let key = key.strip_suffix("_before").or_else(|| key.strip_suffix("_after")).unwrap_or(key);
    UNITS.iter().any(|u| key.ends_with(u))
}

/// Keys that carry a dimensionless number, a count or an index (judged one by one in
/// docs/design/validation.md).
const DIMENSIONLESS: &[&str] = &[
    // metrics of a normalised law and where they are (fractions of the motion angle)
    "cv",
    "ca",
    "ca_pos",
    "ca_neg",
    "cj",
    "cm",
    "ca_rms",
    "ca_turn",
    "a_jump",
    "x_cv",
    "x_ca_pos",
    "x_ca_neg",
    "x_cj",
    "x_cm",
    "x",
    "ds",
    "dv",
    "da",
    "dj",
    "d",
    "d_unit",
    "scale",
    "ramp",
    "continuity_class",
    "rest_continuity",
    "continuous_up_to",
    "class",
    "segments",
    "intervals",
    // ratios and fractions
    "c",
    "threshold",
    "positive_fraction",
    "shed_excess",
    "max_strain",
    "rigidity_ratio",
    "inertia_ratio",
    "envelope_ratio",
    "efficiency",
    "gear_ratio",
    "fail_share",
    "damping_ratio",
    "lengths",
    // counts and indices
    "points",
    "picks",
    "evaluations",
    "distinct_windows",
    "laws_searched",
    "draws",
    "seed",
    "segment",
    "cycle",
    "cycles",
    "row",
    "frame",
    "moves",
    // rounds of the time-true cams' correction (drive correct)
    "rounds",
    "ends",
    "count",
    "counts",
    "failing",
    "not_assembled",
    "not_simulated",
    "ode_draws",
    "separation_draws",
    "self_intersections_b",
    "self_intersections_c",
    "wall_self_intersections_b",
    "wall_self_intersections_c",
    "clearance_checks",
    "max_strain_frame",
    "p",
    "worst_pick",
    "distinct_states",
    // the air jet's relay groups: a group's number in the plan, how many along the reed
    "group",
    "groups",
    // statistics of a quantity named by the object's `name` (`speed_rpm`, …)
    "mean",
    "sd",
    "min",
    "max",
    "value",
    "edges",
    // the dobby curve parameter: rad for an ellipse, m for a point table (its doc says which)
    "cam_param",
    // servo definition points (x: fraction of the motion angle, y: relative acceleration) and the
    // spline coefficients of the normalised law
    "def_points",
    "spline_b",
    // a cam table's re-interpolation tolerance, in the report's top-level `unit` (mm or deg)
    "tolerance",
];

/// Objects whose numbers are not quantities of their own: digit counts of a cam table.
const SKIPPED_OBJECTS: &[&str] = &["decimals"];

/// The keys in `v` whose number (or array of numbers) names no unit and is not listed.
pub fn keys_without_unit(v: &Value) -> Vec<String> {
    let mut out = Vec::new();
    walk(v, &mut out);
    out.sort();
    out.dedup();
    out
}

fn numeric(v: &Value) -> bool {
    match v {
        Value::Number(_) => true,
        Value::Array(a) => !a.is_empty() && a.iter().all(numeric),
        _ => false,
    }
}

fn walk(v: &Value, out: &mut Vec<String>) {
    match v {
        Value::Object(m) => {
            // A `unit` beside the numbers states theirs.
            let unit_beside = m.get("unit").is_some_and(Value::is_string);
            for (k, x) in m {
                if SKIPPED_OBJECTS.contains(&k.as_str()) || has_unit(k) && !numeric(x) {
                    // A parent named with a unit (`layout_deg`) gives its children theirs.
                    continue;
                }
                if numeric(x) && !unit_beside && !has_unit(k) && !DIMENSIONLESS.contains(&k.as_str()) {
                    out.push(k.clone());
                }
                walk(x, out);
            }
        }
        Value::Array(a) => a.iter().for_each(|x| walk(x, out)),
        _ => {}
    }
}

#[test]
fn the_rules_find_a_key_without_a_unit() {
    let v = serde_json::json!({
        "peak_torque_n_m": 1.0, "cv": 2.0, "stroke": 3.0,
        "layout_deg": {"rise": 150.0},
        "checks": [{"value": 1.0, "limit": 2.0, "unit": "N·m"}],
        "decimals": {"y": 5},
        "rows": [{"phi2_deg": 0.0, "speed": [1.0, 2.0]}]
    });
    assert_eq!(keys_without_unit(&v), ["speed", "stroke"]);
}
