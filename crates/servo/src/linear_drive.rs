//! The constants of a linear transmission's torque, worked out once: what evaluates the torque
//! at many points of a long cycle (every frame of a servo-shedding study).

use crate::Axis;

/// The torque of an [`Axis`] with a linear transmission (`θ = k·y`), its constants worked out
/// once: `T = (J_m + J_x)·k·a + (c·v + F_μ·sgn v + k_s·s + F_c)/(k·η)`. The same arithmetic as
/// [`Axis::torque_at`] and [`Axis::torque_rate`], which evaluate through it: the same bits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearDrive {
    /// `k`, motor radians per slave SI unit ([`Axis::motor_rad_per_unit`]).
    pub k: f64,
    /// `k·η`.
    ke: f64,
    /// `(J_m + J_x)·k + m/(k·η)`, N·m per unit slave acceleration ([`Axis::torque_inertia`]).
    inertia: f64,
    /// Viscous friction `c`, Coulomb friction `F_μ`, spring `k_s`, constant force `F_c`.
    viscous: f64,
    friction: f64,
    spring: f64,
    constant: f64,
}

impl LinearDrive {
    /// The constants of `axis`; `None` for a crank and lever (its ratio changes with the position).
    pub fn of(axis: &Axis) -> Option<Self> {
        if axis.load.crank_lever.is_some() {
            return None;
        }
        let k = axis.motor_rad_per_unit();
        let l = &axis.load;
        Some(Self {
            k,
            ke: k * l.efficiency,
            inertia: axis.torque_inertia(),
            viscous: l.viscous_n_s_m,
            friction: l.friction_n,
            spring: l.spring_n_m,
            constant: l.constant_force_n,
        })
    }

    /// The motor torque (N·m) with the slave at position `s`, velocity `v` and acceleration `a`
    /// (SI), the Coulomb friction zero where `v = 0` ([`Axis::torque_at`]).
    #[inline]
    pub fn torque_at(&self, s: f64, v: f64, a: f64) -> f64 {
        let fric = if v == 0.0 { 0.0 } else { self.friction * v.signum() };
        self.inertia * a + (self.viscous * v + fric + self.spring * s + self.constant) / self.ke
    }

    /// The torque's time derivative (N·m/s) from the velocity, acceleration and jerk, away from a
    /// sign change of the velocity ([`Axis::torque_rate`]).
    #[inline]
    pub fn torque_rate(&self, v: f64, a: f64, j: f64) -> f64 {
        self.inertia * j + (self.viscous * a + self.spring * v) / self.ke
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use loomkin_laws::StrokeUnit;

    #[test]
    fn the_torque_is_the_models_written_out_and_its_rate_the_derivative_in_time() {
        let text = include_str!("../../../examples/servo-axis.toml").replace("spring_n_m = 0.0", "spring_n_m = 300.0");
        let axis =
            Axis::from_toml(&text.replace("constant_force_n = 0.0", "constant_force_n = 7.5"), StrokeUnit::Mm).unwrap();
        let d = axis.linear_drive().unwrap();
        let (l, m) = (&axis.load, &axis.motor);
        let k = 2.0 * std::f64::consts::PI / (l.travel_mm_per_rev.unwrap() * 1e-3);
        assert!((d.k - k).abs() <= 1e-15 * k);
        // A motion s(t) = 0.02 sin 9t + 0.003 t: the torque against the model written out, the
        // rate against the central difference of the torque along it.
        let s = |t: f64| 0.02 * (9.0 * t).sin() + 0.003 * t;
        let v = |t: f64| 0.18 * (9.0 * t).cos() + 0.003;
        let a = |t: f64| -1.62 * (9.0 * t).sin();
        let j = |t: f64| -14.58 * (9.0 * t).cos();
        for i in 0..50 {
            let t = 0.013 * i as f64 + 0.001;
            let force = l.moving_mass_kg.unwrap() * a(t)
                + l.viscous_n_s_m * v(t)
                + l.friction_n * v(t).signum()
                + l.spring_n_m * s(t)
                + l.constant_force_n;
            let written = (m.rotor_inertia_kg_m2 + l.extra_inertia_kg_m2) * k * a(t) + force / (k * l.efficiency);
            let torque = d.torque_at(s(t), v(t), a(t));
            assert!((torque - written).abs() <= 1e-12 * written.abs().max(1.0), "{torque} {written}");
            assert_eq!(torque.to_bits(), axis.torque_at(s(t), v(t), a(t)).to_bits());
            let h = 1e-6;
            let diff =
                (d.torque_at(s(t + h), v(t + h), a(t + h)) - d.torque_at(s(t - h), v(t - h), a(t - h))) / (2.0 * h);
            let rate = d.torque_rate(v(t), a(t), j(t));
            assert!((rate - diff).abs() <= 1e-5 * rate.abs().max(1.0), "{rate} {diff}");
            assert_eq!(rate.to_bits(), axis.torque_rate(v(t), a(t), j(t)).to_bits());
        }
        // A crank and lever has none.
        let lever = crate::CrankLever {
            crank_radius_mm: 40.0,
            rod_length_mm: 200.0,
            lever_input_arm_mm: 100.0,
            lever_output_arm_mm: 200.0,
            lever_angle_deg: 0.0,
            rocking_shaft_x_mm: -100.0,
            rocking_shaft_y_mm: 200.0,
            frame_link_mm: Some(400.0),
            lever_inertia_kg_m2: 0.02,
            crank_branch: crate::CrankBranch::Ccw,
            gear_ratio: 1.0,
            mid_stroke_mm: 40.0,
        };
        let load = crate::Load { crank_lever: Some(lever), travel_mm_per_rev: None, ..axis.load.clone() };
        let crank = Axis { load, ..axis.clone() };
        assert!(crank.linear_drive().is_none());
    }
}
