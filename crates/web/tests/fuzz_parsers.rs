//! Property tests for every file parser of loomkin (cycle, drive, mechanism, cam point table,
//! shedding spec, Monte-Carlo and tolerance studies): arbitrary text and mutated valid files never panic; a refusal is one line
//! without `NaN`; an accepted file holds only finite numbers.
//!
//! They live here because the workbench crate depends on every library crate. Cases per
//! property: `LOOMKIN_FUZZ_CASES` (default 64).

use proptest::prelude::*;

const CYCLE: &str = "unit = \"mm\"\nstroke = 100\nspeed_rpm = 300\n\n[[segment]]\nkind = \"dwell\"\nto_deg = 60\n\n\
[[segment]]\nkind = \"rise\"\nto_deg = 180\nlaw = \"modified-sine\"\n\n[[segment]]\nkind = \"dwell\"\nto_deg = 240\n\n\
[[segment]]\nkind = \"return\"\nto_deg = 360\nlaw = \"modified-trapezoid\"\nparams = { ramp = 0.125 }\n";
const DRIVE: &str =
    "[drive]\nstroke_m = 0.1\nmotion_angle_deg = 180\nmoving_mass_kg = 1\npinion_radius_m = 0.02\nefficiency = 0.9\n";
const MECHANISM: &str = "[mechanism]\nc1_m_per_n = 3.6098e-5\nc23_m_per_n = 2.9072e-6\nc4_m_per_n = 6.3222e-4\n\
theta_kg_m2 = 0.181835\nshuttle_kg = 0.419725\nl_m = 0.74\nk_m = 0.23\nr_m = 0.083\nchecking_n = 49.0332\n\n[design]\n\
velocity_m_s = 17.0\ndistance_m = 0.22\nfirst_stage_m = 0.086\nspeed_rpm = 200.0\n\n[required]\nretardation_pct = 10.0\n\
path_m = 1.53\nfree_shed_deg = 120.0\n";
const MONTECARLO: &str = "draws = 5\nseed = 3\nbins = 4\npercentiles = [5, 50, 95]\n[settings]\n\
speed_rpm = { dist = \"normal\", mean = 200, sd = 4, min = 190, max = 210 }\nplay_mm = { dist = \"uniform\", min = 0, \
max = 10 }\nshuttle_g = 420\n[limits]\nvelocity_m_s = { min = 15, max = 19 }\n";
const TOLERANCE: &str = "draws = 3\nseed = 3\nstep_deg = 10\n[dimensions]\nl6_m = { dist = \"normal\", mean = 0.4, \
sd = 0.001 }\nalpha_deg = { dist = \"uniform\", min = 46, max = 48 }\n[limits]\npressure_angle_deg = { max = 60 }\n";
const SPEC: &str = "motion_deg = 180\npositive = \"0.5:sine-ramp:0:1,0.5:cosine-ramp:1:0\"\n";

fn cam_table() -> String {
    (0..40)
        .map(|i| {
            let p = std::f64::consts::TAU * f64::from(i) / 40.0;
            format!("{:.6},{:.6}\n", 0.366 * p.cos(), 0.577 * p.sin())
        })
        .collect::<String>()
}

const NUMBERS: &[&str] = &[
    "0", "-0", "-1", "1e-320", "5e-324", "1e-300", "1e308", "-1e308", "1e999", "nan", "inf", "-inf", "1e-9", "1e9",
    "360", "-360", "0.25", "1000000", "\"x\"", "[]", "{}", "true",
];

/// One parser: its name and a run that returns the error text or the debug text of the result.
type Parser = fn(&str) -> Result<String, String>;

fn parsers() -> Vec<(&'static str, String, Parser)> {
    vec![
        ("cycle", CYCLE.to_string(), |t| {
            loomkin_laws::Cycle::from_toml(t).map(|c| format!("{c:?}")).map_err(|e| e.to_string())
        }),
        ("drive", DRIVE.to_string(), |t| {
            loomkin_servo::Drive::from_text(t).map(|d| format!("{d:?}")).map_err(|e| e.to_string())
        }),
        ("mechanism", MECHANISM.to_string(), |t| {
            loomkin_picking::Mechanism::from_toml(t).map(|m| format!("{m:?}")).map_err(|e| e.to_string())
        }),
        ("cam table", cam_table(), |t| {
            loomkin_mech::parse_point_table(t).map(|p| format!("{p:?}")).map_err(|e| e.to_string())
        }),
        ("shedding spec", SPEC.to_string(), |t| {
            loomkin_shed::ShedLaw::from_toml(t).map(|l| format!("{l:?}")).map_err(|e| e.to_string())
        }),
        ("pick montecarlo study", MONTECARLO.to_string(), |t| {
            loomkin_picking::MonteCarlo::from_toml(t).map(|m| format!("{m:?}")).map_err(|e| e.to_string())
        }),
        ("dobby tolerance study", TOLERANCE.to_string(), |t| {
            loomkin_mech::Tolerance::from_toml(t).map(|m| format!("{:?}", m.nominal)).map_err(|e| e.to_string())
        }),
    ]
}

fn non_finite_word(text: &str) -> Option<&str> {
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .find(|w| matches!(w.to_ascii_lowercase().as_str(), "nan" | "inf" | "infinity"))
}

/// What is wrong with a parser's answer to `text`, if anything.
fn judge(name: &str, text: &str, answer: Result<String, String>) -> Result<(), TestCaseError> {
    match answer {
        Ok(debug) => {
            prop_assert!(
                non_finite_word(&debug).is_none(),
                "{name}: accepted a non-finite value from {text:?}: {debug}"
            );
        }
        Err(e) => {
            prop_assert!(!e.is_empty() && !e.contains('\n'), "{name}: not one line: {e:?}");
            // The message may quote the input ('nan') or name a TOML keyword (`inf`); it must not
            // invent a non-finite number.
            if let Some(w) = non_finite_word(&e).filter(|w| !e.contains(&format!("`{w}`"))) {
                prop_assert!(text.to_ascii_lowercase().contains(&w.to_ascii_lowercase()), "{name}: '{w}' in {e}");
            }
        }
    }
    Ok(())
}

/// A valid file with 1–3 edits: a number made hostile, a span deleted, a line repeated.
fn mutated(valid: &str, edits: &[(u8, usize, usize)]) -> String {
    let mut t = valid.to_string();
    for &(kind, a, b) in edits {
        let len = t.len().max(1);
        let (i, j) = ((a % len).min(b % len), (a % len).max(b % len));
        let (i, j) = (floor_char(&t, i), floor_char(&t, j));
        match kind % 3 {
            0 => {
                // Replace the number starting at or after i.
                if let Some(s) = t[i..].find(|c: char| c.is_ascii_digit()).map(|k| i + k) {
                    let e = t[s..]
                        .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-'))
                        .map_or(t.len(), |k| s + k);
                    t.replace_range(s..e, NUMBERS[b % NUMBERS.len()]);
                }
            }
            1 => t.replace_range(i..j, ""),
            _ => {
                let line = t[i..].lines().next().unwrap_or("").to_string();
                t.insert_str(i, &format!("{line}\n"));
            }
        }
    }
    t
}

fn floor_char(t: &str, mut i: usize) -> usize {
    while i > 0 && !t.is_char_boundary(i) {
        i -= 1;
    }
    i.min(t.len())
}

fn cases() -> u32 {
    std::env::var("LOOMKIN_FUZZ_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(64)
}

#[test]
fn the_valid_files_parse() {
    for (name, valid, parse) in parsers() {
        assert!(parse(&valid).is_ok(), "{name}: {:?}", parse(&valid));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn arbitrary_text_never_panics(text in "(?s).{0,400}") {
        for (name, _, parse) in parsers() {
            judge(name, &text, parse(&text))?;
        }
    }

    #[test]
    fn mutated_files_never_panic(edits in prop::collection::vec((any::<u8>(), any::<usize>(), any::<usize>()), 1..4)) {
        for (name, valid, parse) in parsers() {
            let text = mutated(&valid, &edits);
            judge(name, &text, parse(&text))?;
        }
    }
}
