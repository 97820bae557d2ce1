//! One frame's servo drive: the servo axis model of loomkin-servo moving the frame's planned cycle,
//! and its electrical power.
//!
//! The frame (mass `m`, return spring `k_s` with preload `F₀` at the bottom of its stroke, weight
//! `m·g`) is the load of a [`loomkin_servo::Axis`] with a translating slave: the motor gives
//!
//! $$ T = (J_m + J_x)\,k\,\ddot y + \frac{m\ddot y + c\dot y + F_\mu\,\mathrm{sgn}\,\dot y + k_s y + F_c}{k\,\eta}, \qquad k = \frac{2\pi}{\ell}, $$
//!
//! `ℓ` the travel per motor revolution, `y` the frame's position from its place at the cycle's
//! start and `F_c = m·g + F₀ + k_s·(y_0 + H/2)` the constant force there. The motor turns at
//! `ω_m = k·ẏ` and draws from the bus
//!
//! $$ P = T\,\omega_m + R\,(T/k_t)^2 $$
//!
//! (mechanical power plus the copper loss; iron, friction and inverter losses of the motor are not
//! modelled). The warp's pull on the frame is not part of this load (`loom torque` has it).

use crate::Transmission;
use loomkin_cams::profile::Jet;
use loomkin_laws::{CycleSegment, Segment};
use loomkin_servo::{Axis, CrankLever, Limits, LinearDrive, Load, Motor};

/// A heald frame as a servo's load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameLoad {
    /// Moving mass, kg.
    pub mass_kg: f64,
    /// Return-spring stiffness, N/m.
    pub spring_n_m: f64,
    /// Spring force with the frame at the bottom of its stroke, N.
    pub preload_n: f64,
    /// Full stroke, m.
    pub stroke_m: f64,
    /// Height over mid-stroke where the frame's cycle starts, m (`±H/2`).
    pub start_level_m: f64,
}

impl FrameLoad {
    /// A 1 kg frame without spring (to check a motor and transmission before the frames are known).
    pub const UNIT: Self = Self { mass_kg: 1.0, spring_n_m: 0.0, preload_n: 0.0, stroke_m: 0.0, start_level_m: 0.0 };

    /// The constant force at the cycle's start position: weight, preload and spring, N.
    pub fn force_at_start_n(&self) -> f64 {
        self.mass_kg * loomkin_units::STANDARD_GRAVITY_M_S2
            + self.preload_n
            + self.spring_n_m * (self.start_level_m + self.stroke_m / 2.0)
    }

    /// The frame's energy at cycle position `s` (m from the start) moving at `v` (m/s) with the
    /// motor's rotor and extra inertia: `½(m + (J_m + J_x)k²)v² + F_c·s + ½k_s s²`, J (zero at the
    /// start at rest); with a crank and lever `½(m v² + (J_m + J_x)ω_m² + J_L φ̇²) + F_c·s + ½k_s s²`.
    pub fn energy_j(&self, axis: &Axis, s: f64, v: f64) -> f64 {
        let j = axis.motor.rotor_inertia_kg_m2 + axis.load.extra_inertia_kg_m2;
        if let Some(link) = axis.linkage() {
            // With a crank and lever: the motor at i·α̇, the lever at φ̇ (its inertia J_L).
            let Some(m) = link.motor(Jet([s, v, 0.0, 0.0, 0.0, 0.0])) else { return f64::NAN };
            let (w, p) = (link.gear * m.alpha.d(1), m.lever.d(1));
            return 0.5 * (self.mass_kg * v * v + j * w * w + link.lever_inertia * p * p)
                + self.force_at_start_n() * s
                + 0.5 * self.spring_n_m * s * s;
        }
        let k = axis.motor_rad_per_unit();
        0.5 * (self.mass_kg + j * k * k) * v * v + self.force_at_start_n() * s + 0.5 * self.spring_n_m * s * s
    }
}

/// The servo axis of one frame: `motor` moving `load` through `transmission`.
pub fn axis(motor: &Motor, transmission: &Transmission, load: &FrameLoad) -> Axis {
    Axis {
        motor: motor.clone(),
        load: Load {
            moving_mass_kg: Some(load.mass_kg),
            load_inertia_kg_m2: None,
            travel_mm_per_rev: transmission.crank_lever.is_none().then_some(transmission.travel_mm_per_rev),
            gear_ratio: None,
            efficiency: transmission.efficiency,
            friction_n: transmission.friction_n,
            viscous_n_s_m: transmission.viscous_n_s_m,
            spring_n_m: load.spring_n_m,
            constant_force_n: load.force_at_start_n(),
            extra_inertia_kg_m2: transmission.extra_inertia_kg_m2,
            // The cycle's position 0 is the frame's place at its start, `start_level_m` over
            // mid-stroke: mid-stroke is at `−start_level_m`.
            crank_lever: transmission.crank_lever.map(|c| CrankLever { mid_stroke_mm: -load.start_level_m * 1e3, ..c }),
        },
        limits: Limits::default(),
    }
}

/// Torque, motor speed and electrical power of one frame's drive, and their time derivatives.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DrivePoint {
    /// Motor torque, N·m.
    pub torque_n_m: f64,
    /// dT/dt, N·m/s.
    pub torque_rate: f64,
    /// Motor speed, rad/s.
    pub motor_rad_s: f64,
    /// Electrical power drawn from the bus (negative: returned), W.
    pub power_w: f64,
    /// dP/dt, W/s.
    pub power_rate: f64,
    /// Frame velocity, m/s.
    pub v_m_s: f64,
}

/// A frame's drive evaluated on its cycle.
#[derive(Debug, Clone)]
pub struct FrameDrive {
    /// The axis.
    pub axis: Axis,
    /// The frame.
    pub load: FrameLoad,
    /// `R/k_t²`, W/(N·m)².
    pub loss: f64,
    /// Main-shaft speed, rad/s.
    pub omega: f64,
    /// The crank and lever's linkage ([`Axis::linkage`]), built once.
    linkage: Option<loomkin_servo::Linkage>,
    /// A linear transmission's torque constants ([`Axis::linear_drive`]), worked out once.
    linear: Option<LinearDrive>,
}

impl FrameDrive {
    /// `axis` moving `load` at `omega` (main shaft, rad/s), its winding losing `loss` W/(N·m)².
    pub fn new(axis: Axis, load: FrameLoad, loss: f64, omega: f64) -> Self {
        let (linkage, linear) = (axis.linkage(), axis.linear_drive());
        Self { axis, load, loss, omega, linkage, linear }
    }

    /// The drive at local coordinate `t` of law segment `lseg` of cycle segment `seg`.
    pub fn at_law(&self, seg: &CycleSegment, lseg: &Segment, t: f64) -> DrivePoint {
        let [s, v, a, j] = self.state_at_law(seg, lseg, t);
        self.point(s, v, a, j)
    }

    /// The frame's position, velocity, acceleration and jerk (SI) at local coordinate `t` of law
    /// segment `lseg` of cycle segment `seg`: what [`FrameDrive::at_law`] evaluates the drive at.
    pub fn state_at_law(&self, seg: &CycleSegment, lseg: &Segment, t: f64) -> [f64; 4] {
        let d = lseg.derivs_local(t);
        let r = self.omega / seg.length_rad;
        let h = seg.stroke_si;
        [seg.base_si + h * d[0], h * d[1] * r, h * d[2] * r * r, h * d[3] * r * r * r]
    }

    /// The drive at rest at cycle position `s`.
    pub fn at_rest(&self, s: f64) -> DrivePoint {
        self.point(s, 0.0, 0.0, 0.0)
    }

    /// The drive with the frame at cycle position `s`, velocity `v`, acceleration `a` and jerk `j`
    /// (SI, from the frame's cycle).
    pub fn point(&self, s: f64, v: f64, a: f64, j: f64) -> DrivePoint {
        let (t, dt, w, dw) = match &self.linear {
            Some(d) => (d.torque_at(s, v, a), d.torque_rate(v, a, j), d.k * v, d.k * a),
            None => {
                // The crank and lever: torque and motor angle as series in time.
                let nan = Jet::cst(f64::NAN);
                let series = Jet([s, v, 0.5 * a, j / 6.0, 0.0, 0.0]);
                let (t, alpha) = self.axis.motor_series_via(self.linkage.as_ref(), series).unwrap_or((nan, nan));
                (t.v(), t.d(1), alpha.d(1), alpha.d(2))
            }
        };
        DrivePoint {
            torque_n_m: t,
            torque_rate: dt,
            motor_rad_s: w,
            power_w: t * w + self.loss * t * t,
            power_rate: dt * w + t * dw + 2.0 * self.loss * t * dt,
            v_m_s: v,
        }
    }
}
