//! Which library descriptor (`loomkin_units::Field`) each CLI flag takes, named rather than
//! guessed from the flag's key: docs/reference/fields.md shows these ranges and the range-end
//! sweep (crates/cli/src/range_ends.rs) runs each flag at its descriptor's ends.
//!
//! Matching by key alone gave 14 flags another quantity's range (`shed law --motion-deg` showed a
//! rapier drive's (0, 180] where the command checks 1 … 360°) and left flags whose key several
//! descriptors share (`--step-deg`, `--points`, `--speed-rpm`) to a guess by their default. Here
//! a flag names its descriptor once: [`EVERY`] for a flag that means one quantity in every command
//! that has it, [`ONE`] per command (it wins over [`EVERY`]). A flag whose key is a descriptor's and
//! which takes none of them says why ([`Takes::Nothing`]). The tests below keep the tables and the
//! command tree together: every flag whose key is some descriptor's is named here, and every entry
//! names a flag that exists.

use loomkin_units::Field;

/// What a flag takes.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Takes {
    /// The descriptor the command checks the value through.
    Field(&'static Field),
    /// No one descriptor: the reason (a path, a span whose numbers each have the range, a range that
    /// depends on another argument).
    Nothing(&'static str),
}

/// Flags that take one descriptor in every command that has them.
pub(crate) const EVERY: &[(&str, Takes)] = &[
    ("--alpha-deg", Takes::Field(&loomkin_mech::ModulatorGeometry::ALPHA_DEG)),
    ("--breakdown-ratio", Takes::Field(&loomkin_drive::Induction::BREAKDOWN_RATIO)),
    ("--carrier-length-m", Takes::Field(&loomkin_shed::LoomRequirement::CARRIER_LENGTH_M)),
    ("--carrier-speed-m-s", Takes::Field(&loomkin_shed::LoomRequirement::CARRIER_SPEED_M_S)),
    ("--checking-kgf", Takes::Field(&loomkin_picking::Settings::CHECKING_KGF)),
    ("--cloth-width-m", Takes::Field(&loomkin_shed::LoomRequirement::CLOTH_WIDTH_M)),
    ("--crossing-range-deg", Takes::Field(&loomkin_shed::LoomRequirement::CROSSING_RANGE_DEG)),
    ("--damping-ratio", Takes::Field(&loomkin_dynamics::Follower::DAMPING_RATIO)),
    ("--design-speed-rpm", Takes::Field(&loomkin_picking::DesignSpec::SPEED_RPM)),
    ("--distance-m", Takes::Field(&loomkin_picking::DesignSpec::DISTANCE_M)),
    ("--dpi", Takes::Field(&loomkin_plot::Page::DPI)),
    ("--dwell-centre-deg", Takes::Field(&loomkin_mech::OutputLawSpec::DWELL_CENTRE_DEG)),
    ("--dwell-deg", Takes::Field(&loomkin_mech::OutputLawSpec::DWELL_DEG)),
    ("--dwell-tolerance-mm", Takes::Field(&loomkin_drive::SleyAnalysis::DWELL_TOLERANCE_MM)),
    ("--first-stage-m", Takes::Field(&loomkin_picking::DesignSpec::FIRST_STAGE_M)),
    ("--flywheel-kg-m2", Takes::Field(&loomkin_drive::ripple::FLYWHEEL_KG_M2)),
    ("--force-n", Takes::Field(&loomkin_dynamics::Follower::FORCE_N)),
    ("--free-shed-deg", Takes::Field(&loomkin_picking::RequiredVelocity::FREE_SHED_DEG)),
    ("--gear-ratio", Takes::Field(&loomkin_drive::Induction::GEAR_RATIO)),
    ("--height", Takes::Field(&loomkin_plot::Page::HEIGHT)),
    ("--l2-m", Takes::Field(&loomkin_mech::ModulatorGeometry::L2_M)),
    ("--l3-m", Takes::Field(&loomkin_mech::ModulatorGeometry::L3_M)),
    ("--l3p-m", Takes::Field(&loomkin_mech::ModulatorGeometry::L3P_M)),
    ("--l6-m", Takes::Field(&loomkin_mech::ModulatorGeometry::L6_M)),
    ("--mass-kg", Takes::Field(&loomkin_dynamics::Follower::MASS_KG)),
    ("--natural-hz", Takes::Field(&loomkin_dynamics::Follower::NATURAL_HZ)),
    ("--path-m", Takes::Field(&loomkin_picking::RequiredVelocity::PATH_M)),
    ("--play-mm", Takes::Field(&loomkin_picking::Settings::PLAY_MM)),
    ("--preload-n", Takes::Field(&loomkin_dynamics::Follower::PRELOAD_N)),
    ("--pressure-limit-deg", Takes::Field(&loomkin_mech::DobbyInputs::PRESSURE_LIMIT_DEG)),
    ("--rated-power-kw", Takes::Field(&loomkin_drive::Induction::RATED_POWER_KW)),
    ("--rated-rpm", Takes::Field(&loomkin_drive::Induction::RATED_RPM)),
    ("--reed-width-m", Takes::Field(&loomkin_shed::LoomRequirement::REED_WIDTH_M)),
    ("--retardation-pct", Takes::Field(&loomkin_picking::RequiredVelocity::RETARDATION_PCT)),
    ("--return-spring-n-m", Takes::Field(&loomkin_dynamics::Follower::RETURN_SPRING_N_M)),
    ("--roller-m", Takes::Field(&loomkin_mech::DobbyInputs::ROLLER_M)),
    ("--roller-mm", Takes::Field(&loomkin_mech::DobbyInputs::ROLLER_MM)),
    ("--servo-gain-n-m-s", Takes::Field(&loomkin_drive::Servo::GAIN_N_M_S)),
    ("--servo-integral-s", Takes::Field(&loomkin_drive::Servo::INTEGRAL_S)),
    ("--servo-torque-limit-n-m", Takes::Field(&loomkin_drive::Servo::TORQUE_LIMIT_N_M)),
    ("--shed-excess", Takes::Field(&loomkin_shed::LoomRequirement::SHED_EXCESS)),
    ("--shuttle-g", Takes::Field(&loomkin_picking::Settings::SHUTTLE_G)),
    ("--strap-cm", Takes::Field(&loomkin_picking::Settings::STRAP_CM)),
    ("--synchronous-rpm", Takes::Field(&loomkin_drive::Induction::SYNCHRONOUS_RPM)),
    ("--theta-deg", Takes::Field(&loomkin_mech::ModulatorGeometry::THETA_DEG)),
    ("--threshold", Takes::Field(&loomkin_shed::Conditions::THRESHOLD_FIELD)),
    ("--tolerance", Takes::Field(&loomkin_cams::table::Spacing::TOLERANCE)),
    ("--velocity-m-s", Takes::Field(&loomkin_picking::DesignSpec::VELOCITY_M_S)),
    ("--width", Takes::Field(&loomkin_plot::Page::WIDTH)),
];

/// Flags whose descriptor depends on the command (a `--step-deg` of a cam table is not a dobby's).
pub(crate) const ONE: &[(&str, &str, Takes)] = &[
    ("law sample", "--points", Takes::Field(&loomkin_laws::Law::SAMPLE_POINTS)),
    ("law plot", "--points", Takes::Field(&loomkin_laws::Law::PLOT_POINTS)),
    ("cycle", "--points", Takes::Field(&loomkin_laws::Cycle::POINTS)),
    ("pick simulate", "--points", Takes::Field(&loomkin_picking::History::POINTS)),
    ("pick sweep", "--points", Takes::Field(&loomkin_picking::Sweep::POINTS)),
    ("pick plot", "--points", Takes::Field(&loomkin_picking::History::PLOT_POINTS)),
    ("servo law", "--points", Takes::Field(&loomkin_laws::Law::SAMPLE_POINTS)),
    ("shed plot", "--points", Takes::Field(&loomkin_shed::PLOT_POINTS)),
    ("dyn response", "--points", Takes::Field(&loomkin_dynamics::Response::POINTS)),
    ("dyn compensate", "--points", Takes::Field(&loomkin_dynamics::Compensation::POINTS)),
    ("sley analyze", "--points", Takes::Field(&loomkin_drive::SleyAnalysis::POINTS)),
    ("cycle", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("pick simulate", "--speed-rpm", Takes::Field(&loomkin_picking::Settings::SPEED_RPM)),
    ("pick sweep", "--speed-rpm", Takes::Field(&loomkin_picking::Settings::SPEED_RPM)),
    ("pick plot", "--speed-rpm", Takes::Field(&loomkin_picking::Settings::SPEED_RPM)),
    ("servo torque", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("servo optimize", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("servo plot", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("servo check", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("shed law", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("shed table", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("shed pareto", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("shed best", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("shed window", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("shed plot", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("dobby analyze", "--speed-rpm", Takes::Field(&loomkin_mech::DobbyInputs::SPEED_RPM)),
    ("dobby synthesize", "--speed-rpm", Takes::Field(&loomkin_mech::DobbyInputs::SPEED_RPM)),
    ("dobby plot", "--speed-rpm", Takes::Field(&loomkin_mech::DobbyInputs::SPEED_RPM)),
    ("dobby sweep", "--speed-rpm", Takes::Field(&loomkin_mech::DobbyInputs::SPEED_RPM)),
    ("dyn response", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("dyn sweep", "--speed-rpm", Takes::Nothing("a FROM:TO:STEP span, each of its speeds in the shaft's range")),
    ("dyn compensate", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("dyn optimize", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("dyn two-mass", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("sley analyze", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("insert budget", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("insert rapier", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("insert projectile", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    ("insert airjet", "--speed-rpm", Takes::Field(&loomkin_units::ShaftSpeed::SPEED)),
    (
        "pick sweep",
        "--from",
        Takes::Nothing(
            "the swept setting's own range (speed, play, shuttle, strap or checking force): no one descriptor",
        ),
    ),
    ("shed pareto", "--from", Takes::Nothing("a path to a table made before, not a number")),
    ("dobby sweep", "--from", Takes::Field(&loomkin_mech::AlphaSweep::FROM)),
    (
        "pick sweep",
        "--to",
        Takes::Nothing(
            "the swept setting's own range (speed, play, shuttle, strap or checking force): no one descriptor",
        ),
    ),
    ("dobby sweep", "--to", Takes::Field(&loomkin_mech::AlphaSweep::TO)),
    ("servo optimize", "--starts", Takes::Field(&loomkin_servo::ServoInputs::STARTS)),
    ("servo export", "--step-deg", Takes::Field(&loomkin_servo::ServoInputs::EXPORT_STEP_DEG)),
    ("dobby analyze", "--step-deg", Takes::Field(&loomkin_mech::DobbyInputs::STEP_DEG)),
    ("dobby synthesize", "--step-deg", Takes::Field(&loomkin_mech::DobbyInputs::STEP_DEG)),
    ("dobby plot", "--step-deg", Takes::Field(&loomkin_mech::DobbyInputs::PLOT_STEP_DEG)),
    ("dobby sweep", "--step-deg", Takes::Field(&loomkin_mech::DobbyInputs::STEP_DEG)),
    ("cam table", "--step-deg", Takes::Field(&loomkin_cams::table::Spacing::STEP_DEG)),
    ("cam profile", "--step-deg", Takes::Field(&loomkin_cams::profile::CamProfile::STEP_DEG)),
    ("loom torque", "--step-deg", Takes::Field(&loomkin_loom::Drive::STEP_DEG)),
    ("loom servo", "--step-deg", Takes::Field(&loomkin_cams::table::Spacing::STEP_DEG)),
    ("drive inertia", "--step-deg", Takes::Field(&loomkin_loom::Drive::STEP_DEG)),
    ("drive ripple", "--step-deg", Takes::Field(&loomkin_drive::ripple::STEP_DEG)),
    ("drive correct", "--step-deg", Takes::Field(&loomkin_drive::ripple::STEP_DEG)),
    ("servo check", "--stroke-deg", Takes::Field(&loomkin_laws::CycleSpec::STROKE_DEG)),
    ("servo check", "--stroke-mm", Takes::Field(&loomkin_laws::CycleSpec::STROKE_MM)),
    ("shed law", "--stroke-mm", Takes::Field(&loomkin_shed::Conditions::STROKE_MM)),
    ("shed table", "--stroke-mm", Takes::Field(&loomkin_shed::Conditions::STROKE_MM)),
    ("shed pareto", "--stroke-mm", Takes::Field(&loomkin_shed::Conditions::STROKE_MM)),
    ("shed best", "--stroke-mm", Takes::Field(&loomkin_shed::Conditions::STROKE_MM)),
    ("shed plot", "--stroke-mm", Takes::Field(&loomkin_shed::Conditions::STROKE_MM)),
    ("cam table", "--stroke-deg", Takes::Field(&loomkin_cams::table::Motion::STROKE_DEG)),
    ("cam table", "--stroke-mm", Takes::Field(&loomkin_cams::table::Motion::STROKE_MM)),
    ("cam profile", "--stroke-deg", Takes::Field(&loomkin_laws::CycleSpec::STROKE_DEG)),
    ("cam profile", "--stroke-mm", Takes::Field(&loomkin_laws::CycleSpec::STROKE_MM)),
    ("servo check", "--motion-deg", Takes::Field(&loomkin_laws::CycleSpec::MOTION_DEG)),
    ("shed law", "--motion-deg", Takes::Field(&loomkin_shed::MOTION_DEG_FIELD)),
    ("shed table", "--motion-deg", Takes::Field(&loomkin_shed::MOTION_DEG_FIELD)),
    ("shed pareto", "--motion-deg", Takes::Field(&loomkin_shed::MOTION_DEG_FIELD)),
    ("shed best", "--motion-deg", Takes::Field(&loomkin_shed::MOTION_DEG_FIELD)),
    ("cam table", "--motion-deg", Takes::Field(&loomkin_cams::table::Motion::MOTION_DEG)),
    ("cam profile", "--motion-deg", Takes::Field(&loomkin_laws::CycleSpec::MOTION_DEG)),
    ("shed best", "--window-deg", Takes::Field(&loomkin_shed::WINDOW_DEG)),
    ("insert budget", "--window-deg", Takes::Field(&loomkin_insertion::PickBudget::WINDOW_DEG)),
    ("dobby synthesize", "--cycles", Takes::Field(&loomkin_mech::OutputLawSpec::CYCLES)),
    ("dobby plot", "--cycles", Takes::Field(&loomkin_mech::OutputLawSpec::CYCLES)),
    ("dobby sweep", "--cycles", Takes::Field(&loomkin_mech::OutputLawSpec::CYCLES)),
    ("dyn response", "--cycles", Takes::Field(&loomkin_dynamics::Response::CYCLES)),
    ("dobby synthesize", "--chord-tol-mm", Takes::Field(&loomkin_mech::Synthesis::CHORD_TOL_MM)),
    ("cam profile", "--chord-tol-mm", Takes::Field(&loomkin_cams::profile::CamProfile::CHORD_TOL_MM)),
    ("dobby synthesize", "--bore-mm", Takes::Field(&loomkin_mech::Synthesis::BORE_MM)),
    ("cam profile", "--bore-mm", Takes::Field(&loomkin_cams::profile::CamProfile::BORE_MM)),
    ("dobby plot", "--at-deg", Takes::Field(&loomkin_mech::DobbyInputs::AT_DEG)),
    ("dobby sweep", "--by", Takes::Field(&loomkin_mech::AlphaSweep::BY)),
    ("cam profile", "--prime-radius-mm", Takes::Field(&loomkin_cams::profile::CamDesign::PRIME_RADIUS_MM)),
    ("cam profile", "--max-pressure-deg", Takes::Field(&loomkin_cams::profile::CamDesign::MAX_PRESSURE_DEG)),
    ("cam profile", "--roller-radius-mm", Takes::Field(&loomkin_cams::profile::CamDesign::ROLLER_RADIUS_MM)),
    ("cam profile", "--offset-mm", Takes::Field(&loomkin_cams::profile::CamDesign::OFFSET_MM)),
    ("cam profile", "--arm-mm", Takes::Field(&loomkin_cams::profile::CamDesign::ARM_MM)),
    ("cam profile", "--pivot-mm", Takes::Field(&loomkin_cams::profile::CamDesign::PIVOT_MM)),
    ("dyn sweep", "--residual-limit-pct", Takes::Field(&loomkin_dynamics::SweepPoint::RESIDUAL_LIMIT_PCT)),
    ("dyn spectrum", "--ratio", Takes::Nothing("a FROM:TO:STEP span, each of its numbers in the ratio's range")),
    ("dyn optimize", "--band-pct", Takes::Field(&loomkin_dynamics::Optimized::BAND_PCT)),
    ("loom stagger", "--min-clearance-mm", Takes::Field(&loomkin_loom::StaggerOptions::MIN_CLEARANCE_MM)),
    ("loom servo", "--min-clearance-mm", Takes::Field(&loomkin_loom::StaggerOptions::MIN_CLEARANCE_MM)),
    ("sley synthesize", "--reed-stroke-mm", Takes::Field(&loomkin_drive::SleyTarget::STROKE_MM)),
    ("sley synthesize", "--back-dwell-deg", Takes::Field(&loomkin_drive::SleyTarget::BACK_DWELL_DEG)),
    ("sley synthesize", "--reed-height-mm", Takes::Field(&loomkin_drive::SleyTarget::REED_HEIGHT_MM)),
    ("sley synthesize", "--sword-mm", Takes::Field(&loomkin_drive::SleyTarget::SWORD_MM)),
    ("drive ripple", "--target-ripple-pct", Takes::Field(&loomkin_drive::ripple::TARGET_RIPPLE_PCT)),
    ("insert budget", "--reed-width-mm", Takes::Field(&loomkin_insertion::PickBudget::REED_WIDTH_MM)),
    ("insert budget", "--carrier-length-mm", Takes::Field(&loomkin_insertion::PickBudget::CARRIER_LENGTH_MM)),
    ("insert budget", "--speed-m-s", Takes::Field(&loomkin_insertion::PickBudget::SPEED_M_S)),
    ("insert budget", "--carrier-mass-g", Takes::Field(&loomkin_insertion::PickBudget::CARRIER_MASS_G)),
];

/// The descriptor `flag` of `command` takes, or why it takes none; `None` when it is not named here.
pub(crate) fn takes(command: &str, flag: &str) -> Option<Takes> {
    ONE.iter()
        .find(|(c, f, _)| *c == command && *f == flag)
        .map(|(_, _, t)| *t)
        .or_else(|| EVERY.iter().find(|(f, _)| *f == flag).map(|(_, t)| *t))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fields_doc::{cli_inputs, descriptors_by_key};

    /// Every flag whose key is a descriptor's names what it takes, and a flag named in [`EVERY`]
    /// means one quantity wherever it is.
    #[test]
    fn every_flag_with_a_descriptor_key_names_its_descriptor() {
        let by_key = descriptors_by_key();
        let missing: Vec<String> = cli_inputs()
            .into_iter()
            .filter(|c| c.flag.starts_with("--") && by_key.contains_key(c.key.as_str()))
            .filter(|c| takes(&c.command, &c.flag).is_none())
            .map(|c| format!("{} {}", c.command, c.flag))
            .collect();
        assert!(missing.is_empty(), "flags to name in crates/cli/src/flag_fields.rs: {missing:?}");
    }

    /// Every entry names a flag of the command tree (a renamed or removed flag leaves none behind).
    #[test]
    fn every_entry_names_a_flag_that_exists() {
        let inputs = cli_inputs();
        for (command, flag, _) in ONE {
            assert!(
                inputs.iter().any(|c| c.command == *command && c.flag == *flag),
                "{command} {flag} is not a flag of the CLI"
            );
        }
        for (flag, _) in EVERY {
            assert!(inputs.iter().any(|c| c.flag == *flag), "{flag} is a flag of no command");
        }
    }

    /// A named descriptor is listed in its crate's `FIELDS` (the reference and Python read those).
    #[test]
    fn every_named_descriptor_is_listed() {
        let listed: Vec<&Field> = descriptors_by_key().into_values().flatten().collect();
        let named = ONE.iter().map(|(_, _, t)| t).chain(EVERY.iter().map(|(_, t)| t));
        for t in named {
            if let Takes::Field(f) = t {
                assert!(listed.contains(f), "{} is in no crate's FIELDS", f.name);
            }
        }
    }
}
