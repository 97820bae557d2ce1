//! Electronic shedding on a loom: every frame's servo plan from the pattern, the frames as the
//! servos' loads, the study on the shared bus (loomkin-eshed does the work).

use crate::{Loom, LoomError, Motion, Pattern, Result};
use loomkin_eshed::{FrameInput, FrameLoad, FramePlan, FrameSetup, MoveLaws, ServoReport};

/// The laws of the frames' moves: the shedding law's rise and fall.
pub fn servo_laws(loom: &Loom) -> MoveLaws {
    let law = &loom.shedding.law;
    MoveLaws {
        rise: (law.spec(true).clone(), law.law(true).clone()),
        fall: (law.spec(false).clone(), law.law(false).clone()),
    }
}

/// Every frame's plan, load and servo (front first) for `loom` weaving `pattern`, the loom's
/// `[shedding.servo]` giving the drives; `motion_deg` overrides every frame's motion angle and
/// `centre_deg` every frame's move centre (crossing offset plus stagger) when given (the optimiser's
/// variables). Fails when the loom's shedding drive is the dobby.
pub fn servo_setups(
    loom: &Loom,
    pattern: &Pattern,
    motion_deg: Option<&[f64]>,
    centre_deg: Option<&[f64]>,
) -> Result<Vec<FrameSetup>> {
    let servo = loom.shedding.servo.as_ref().ok_or_else(|| {
        LoomError::field(
            "shedding.drive",
            "the loom's shedding drive is the dobby: give drive = \"servo\" and [shedding.servo]",
        )
    })?;
    let motion = Motion::new(loom, pattern)?;
    let picks = motion.picks();
    (0..loom.frame_count())
        .map(|i| {
            let up: Vec<bool> = (0..picks).map(|p| motion.is_up(i, p as i64)).collect();
            let s = &servo.frames[i];
            let phi = match (motion_deg, s.motion_deg) {
                (Some(m), _) => m[i],
                (None, Some(m)) => m,
                (None, None) => motion.motion_deg(),
            };
            let phi =
                loomkin_shed::MOTION_DEG.check(&format!("shedding.servo.frame: frame {} motion_deg", i + 1), phi)?;
            let input = FrameInput {
                up: &up,
                stroke_m: motion.stroke_m(i),
                centre_deg: centre_deg.map_or(motion.centre0_deg(i), |c| c[i]),
                motion_deg: phi,
            };
            let plan = FramePlan::new(&input, servo.pass_through)?;
            let f = &loom.frames[i];
            let load = FrameLoad {
                mass_kg: f.mass_kg,
                spring_n_m: f.spring_n_m,
                preload_n: f.preload_n,
                stroke_m: motion.stroke_m(i),
                start_level_m: plan.start_level_m(),
            };
            Ok(FrameSetup { plan, load, servo: s.clone() })
        })
        .collect()
}

/// The servo-shedding study of `loom` weaving `pattern` (`loomkin loom servo`).
pub fn servo_study(loom: &Loom, pattern: &Pattern) -> Result<ServoReport> {
    let setups = servo_setups(loom, pattern, None, None)?;
    let servo = loom.shedding.servo.as_ref().ok_or_else(|| LoomError::field("shedding.drive", "dobby"))?;
    Ok(loomkin_eshed::analyse(&setups, &servo_laws(loom), &servo.bus, loom.speed.rpm(), servo.pass_through)?)
}

/// Every frame's cam table over the repeat in `formats` (the default set when empty), points
/// placed by `spacing`, and the manifest (`loomkin loom servo --emit-tables`).
pub fn servo_tables(
    loom: &Loom,
    pattern: &Pattern,
    spacing: loomkin_cams::table::Spacing,
    formats: &[loomkin_cams::table::Format],
) -> Result<loomkin_eshed::Tables> {
    let setups = servo_setups(loom, pattern, None, None)?;
    Ok(loomkin_eshed::frame_tables(&setups, &servo_laws(loom), spacing, formats, loom.speed.rpm())?)
}

/// Curves of the servo-shedding study: `points` samples over the repeat.
pub fn servo_curves(loom: &Loom, pattern: &Pattern, points: usize) -> Result<loomkin_eshed::Curves> {
    let setups = servo_setups(loom, pattern, None, None)?;
    let servo = loom.shedding.servo.as_ref().ok_or_else(|| LoomError::field("shedding.drive", "dobby"))?;
    Ok(loomkin_eshed::curves(&setups, &servo_laws(loom), &servo.bus, loom.speed.rpm(), points)?)
}

/// Points of [`servo_figure`]'s curves: one a degree of the repeat, at most this many.
pub const SERVO_PLOT_POINTS: usize = 20_001;

/// The plot of `loomkin loom servo -o`: every frame's motor torque, and the bus power with its
/// peak, over the repeat.
pub fn servo_figure(loom: &Loom, pattern: &Pattern, report: &ServoReport) -> Result<loomkin_plot::Figure> {
    use loomkin_plot::{Figure, Legend, Note, Panel, Rule, Series, sig4};
    let points = ((report.repeat_deg as usize) + 1).clamp(2, SERVO_PLOT_POINTS);
    let c = servo_curves(loom, pattern, points)?;
    let line = |ys: &[f64]| c.angle_deg.iter().copied().zip(ys.iter().copied()).collect::<Vec<_>>();
    let torques: Vec<Series> =
        c.torque_n_m.iter().enumerate().map(|(i, t)| Series::line(format!("frame {}", i + 1), line(t))).collect();
    let legend = if torques.len() <= 8 { Legend::Auto } else { Legend::Hidden };
    let peak = report.peak_bus_power_w;
    let mut bus = Panel::new("bus power [W]", vec![Series::line("bus", line(&c.bus_power_w)).with_color([0, 0, 0])])
        .with_notes([Note::new(
            report.peak_bus_power_at_deg,
            peak,
            format!("peak {} W at {}°", sig4(peak), sig4(report.peak_bus_power_at_deg)),
        )]);
    if let Some(m) = report.braking_resistor_max_w {
        bus = bus.with_rule(Rule::y(-m, format!("braking resistor limit −{} W", sig4(m))));
    }
    let title = format!(
        "servo shedding, {} picks at {} rpm: peak bus power {} W, mean {} W, braking {} J per repeat",
        report.picks,
        report.speed_rpm,
        sig4(peak),
        sig4(report.mean_bus_power_w),
        sig4(report.braking_energy_j)
    );
    let panels = vec![Panel::new("motor torque [N·m]", torques).with_legend(legend), bus];
    let mut fig = Figure::new(title, "main-shaft angle [deg] (0 = beat-up of the first pick)", panels);
    fig.size = Some((1100, 800));
    Ok(fig)
}
