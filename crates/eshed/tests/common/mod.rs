//! Fixtures shared by the tests and the benches of loomkin-eshed (each test crate uses a part).
#![allow(dead_code)]

use loomkin_eshed::{FrameServo, Transmission, Winding};
use loomkin_servo::{CrankBranch, CrankLever, Motor};

/// A 10/30 N·m, 3000/4500 rpm servo motor (the example loom's).
pub fn motor() -> Motor {
    Motor {
        rated_torque_nm: 10.0,
        peak_torque_nm: 30.0,
        rated_speed_rpm: 3000.0,
        max_speed_rpm: 4500.0,
        rotor_inertia_kg_m2: 1.2e-3,
        torque_at_max_speed_nm: None,
    }
}

/// [`motor`] through 100 mm a turn at 95 %, no friction, a 1.5 Ω winding of 1.7 N·m/A.
pub fn servo() -> FrameServo {
    FrameServo {
        motor: motor(),
        transmission: Transmission {
            travel_mm_per_rev: 100.0,
            efficiency: 0.95,
            friction_n: 0.0,
            viscous_n_s_m: 0.0,
            extra_inertia_kg_m2: 0.0,
            crank_lever: None,
        },
        winding: Winding { resistance_ohm: 1.5, torque_constant_n_m_a: 1.7 },
        motion_deg: None,
        moves: Default::default(),
    }
}

/// A crank and lever for frames of up to 110 mm stroke: a 45 mm crank behind a 6:1 gearbox, a
/// 200 mm rod, a straight lever of 100 mm to the rod and 200 mm to a 400 mm frame link.
pub fn crank_lever() -> CrankLever {
    CrankLever {
        crank_radius_mm: 45.0,
        rod_length_mm: 200.0,
        lever_input_arm_mm: 100.0,
        lever_output_arm_mm: 200.0,
        lever_angle_deg: 0.0,
        rocking_shaft_x_mm: -100.0,
        rocking_shaft_y_mm: 200.0,
        frame_link_mm: Some(400.0),
        lever_inertia_kg_m2: 0.015,
        crank_branch: CrankBranch::Ccw,
        gear_ratio: 6.0,
        mid_stroke_mm: 0.0,
    }
}
