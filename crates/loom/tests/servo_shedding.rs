//! The loom file's `[shedding] drive = "servo"`: the plans against the dobby's motion, the table's
//! errors, and the study on the example.

use loomkin_loom::{Loom, Motion, Pattern, servo_laws, servo_setups, servo_study};

const SERVO: &str = include_str!("../../../examples/servo-shedding-loom.toml");
const RAPIER: &str = include_str!("../../../examples/rapier-loom.toml");
const POINT: &str = include_str!("../../../examples/point-24.wif");

#[test]
fn without_pass_through_every_frames_plan_is_the_dobby_motion() {
    let loom = Loom::from_toml(SERVO).unwrap();
    let pattern = Pattern::from_wif(POINT).unwrap();
    let motion = Motion::new(&loom, &pattern).unwrap();
    let setups = servo_setups(&loom, &pattern, None, None).unwrap();
    let laws = servo_laws(&loom);
    for (i, s) in setups.iter().enumerate() {
        assert_eq!(s.plan.cycle_spec(&laws), motion.cycle_spec(i), "frame {}", i + 1);
        assert_eq!(s.plan.start_level_m(), motion.frame(i, s.plan.start_deg - 1e-6).y_m);
    }
}

#[test]
fn the_dobby_loom_reads_as_before_and_has_no_servo() {
    let loom = Loom::from_toml(RAPIER).unwrap();
    assert!(loom.shedding.servo.is_none());
    let pattern = Pattern::from_wif(POINT).unwrap();
    let e = servo_study(&loom, &pattern).unwrap_err().to_string();
    assert!(e.starts_with("shedding.drive:"), "{e}");
}

#[test]
fn the_servo_table_is_checked_field_by_field() {
    let cases = [
        (
            SERVO.replace("drive = \"servo\"", "drive = \"cam\""),
            "shedding.drive: \"cam\": allowed \"dobby\" or \"servo\"",
        ),
        (SERVO.replace("drive = \"servo\"", ""), "shedding.servo: only with drive = \"servo\""),
        (
            SERVO.replace("peak_torque_nm = 30", "peak_torque_nm = 3"),
            "shedding.servo.motor.peak_torque_nm = 3 is out of range",
        ),
        (
            SERVO.replace("travel_mm_per_rev = 100", "travel_mm_per_rev = 0"),
            "shedding.servo.transmission.travel_mm_per_rev = 0 is out of range",
        ),
        (SERVO.replace("voltage_v = 560", "voltage_v = 0"), "shedding.servo.bus.voltage_v = 0 is out of range"),
        (
            SERVO.replace("regeneration_efficiency = 0.9", "regeneration_efficiency = 1.5"),
            "shedding.servo.bus.regeneration_efficiency = 1.5 is out of range",
        ),
        (
            SERVO.replace("[shedding.servo.bus]", "[[shedding.servo.frame]]\nframes = [25]\n[shedding.servo.bus]"),
            "shedding.servo.frame[0].frames: frame 25: frames are numbered 1 to 24 from the front",
        ),
    ];
    for (text, want) in cases {
        let e = Loom::from_toml(&text).unwrap_err().to_string();
        assert!(e.starts_with(want), "{e}\nwanted: {want}");
    }
    // A frame's own motor and motion angle.
    let text = SERVO.replace(
        "[shedding.servo.bus]",
        "[[shedding.servo.frame]]\nframes = [1, 2]\nmotion_deg = 250\nmotor = { rated_torque_nm = 8, peak_torque_nm = 24, rated_speed_rpm = 3000, max_speed_rpm = 4500, rotor_inertia_kg_m2 = 8e-4 }\n[shedding.servo.bus]",
    );
    let loom = Loom::from_toml(&text).unwrap();
    let s = loom.shedding.servo.as_ref().unwrap();
    assert_eq!(s.frames[0].motor.rated_torque_nm, 8.0);
    assert_eq!(s.frames[1].motion_deg, Some(250.0));
    assert_eq!(s.frames[2].motor.rated_torque_nm, 10.0);
    let pattern = Pattern::from_wif(POINT).unwrap();
    let setups = servo_setups(&loom, &pattern, None, None).unwrap();
    assert_eq!(setups[0].plan.moves[0].length_deg, 250.0);
    assert_eq!(setups[2].plan.moves[0].length_deg, 280.0);
}

#[test]
fn the_example_study_balances_and_every_motor_passes() {
    let loom = Loom::from_toml(SERVO).unwrap();
    let pattern = Pattern::from_wif(POINT).unwrap();
    let r = servo_study(&loom, &pattern).unwrap();
    assert_eq!(r.frames.len(), 24);
    assert!(r.motors_ok);
    assert!(r.frames.iter().all(|f| f.rest_continuity >= 2));
    // What the supply gives and the resistor takes differ by what the frames draw, less what the
    // regeneration efficiency loses of the energy the frames return.
    let drawn: f64 = r.frames.iter().map(|f| f.energy_j).sum();
    let lost_in_regeneration = r.regenerated_energy_j / 0.9 * (1.0 - 0.9);
    let balance = r.supplied_energy_j - r.braking_energy_j - drawn - lost_in_regeneration;
    assert!(balance.abs() < 1e-9 * r.supplied_energy_j, "{balance}");
    assert!(r.peak_bus_power_w > 0.0 && r.peak_bus_power_w < r.frames.iter().map(|f| f.peak_power_w).sum::<f64>());
}
