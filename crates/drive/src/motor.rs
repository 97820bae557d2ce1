//! The motors that turn the main shaft: an ideal constant torque, an induction motor (linear slip
//! line or Kloss curve) through a gear, and a speed-controlled servo drive (PI loop, torque limit).
//!
//! Every torque and speed here is referred to the main shaft: an induction motor of torque
//! `M_m(ω_m)` behind a gear of ratio `i = ω_m/ω` gives the shaft `i·M_m(i·ω)`.

use crate::ripple::RippleError;
use loomkin_units::{Field, Range, rad_per_s_from_rpm};
use serde::Serialize;

/// The torque–speed curve of an induction motor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MotorCurve {
    /// The straight line through the synchronous speed (no torque) and the rated point: the
    /// motor's curve near its working point, with no breakdown.
    Linear,
    /// Kloss's formula `M = 2·M_b / (s/s_b + s_b/s)`, its breakdown slip `s_b` fixed by the rated
    /// point and the breakdown torque `M_b`.
    Kloss,
}

impl MotorCurve {
    /// The curve named `linear` or `kloss`.
    pub fn parse(field: &str, name: &str) -> Result<Self, RippleError> {
        match name.trim() {
            "linear" => Ok(Self::Linear),
            "kloss" => Ok(Self::Kloss),
            other => Err(RippleError::field(field, format!("'{other}': expected linear or kloss"))),
        }
    }
}

/// An induction motor driving the main shaft through a gear.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Induction {
    /// Synchronous speed of the motor, rad/s.
    pub synchronous_rad_s: f64,
    /// Rated speed of the motor, rad/s.
    pub rated_rad_s: f64,
    /// Rated torque of the motor (rated power over rated speed), N·m.
    pub rated_torque_n_m: f64,
    /// Breakdown torque over rated torque (Kloss curve).
    pub breakdown_ratio: f64,
    /// The curve.
    pub curve: MotorCurve,
    /// Gear ratio, motor speed over main-shaft speed.
    pub gear_ratio: f64,
}

impl Induction {
    /// `synchronous_rpm`: the motor's synchronous speed.
    pub const SYNCHRONOUS_RPM: Field = Field::new(
        "synchronous_rpm",
        Range::open_closed(0.0, 1e5, "rpm"),
        "Synchronous speed of the induction motor (its shaft, before the gear): 3000, 1500, 1000 … rpm \
         at 50 Hz. Above 0 up to 100000 rpm.",
    )
    .with_default(1500.0);
    /// `rated_rpm`: the motor's rated speed, below the synchronous speed.
    pub const RATED_RPM: Field = Field::new(
        "rated_rpm",
        Range::open_closed(0.0, 1e5, "rpm"),
        "Rated speed of the induction motor (its shaft), below the synchronous speed: the rated slip \
         fixes the slope of the curve.",
    )
    .with_default(1450.0);
    /// `rated_power_kw`: the motor's rated power.
    pub const RATED_POWER_KW: Field = Field::new(
        "rated_power_kw",
        Range::open_closed(0.0, 1e5, "kW"),
        "Rated power of the induction motor; with the rated speed it gives the rated torque. Required \
         with motor = induction.",
    );
    /// `breakdown_ratio`: breakdown torque over rated torque.
    pub const BREAKDOWN_RATIO: Field = Field::new(
        "breakdown_ratio",
        Range::open_closed(1.0, 10.0, ""),
        "Breakdown (pull-out) torque over rated torque of the Kloss curve: 2 … 3 for standard motors; \
         above 1 (the rated point lies below breakdown).",
    )
    .with_default(2.5);
    /// `gear_ratio`: motor speed over main-shaft speed.
    pub const GEAR_RATIO: Field = Field::new(
        "gear_ratio",
        Range::open_closed(0.0, 1000.0, ""),
        "Motor speed over main-shaft speed (belt and gears). Left out: the rated speed over the loom's \
         speed_rpm, so the motor runs at its rated point at the loom's speed.",
    );

    /// An induction motor from its nameplate (`speed` in rpm of the motor, power in kW).
    pub fn new(
        synchronous_rpm: f64,
        rated_rpm: f64,
        rated_power_kw: f64,
        breakdown_ratio: f64,
        curve: MotorCurve,
        gear_ratio: f64,
    ) -> Result<Self, RippleError> {
        let ns = Self::SYNCHRONOUS_RPM.check(synchronous_rpm)?;
        let nr = Self::RATED_RPM.check_as(Self::RATED_RPM.name, rated_rpm)?;
        Range::open(0.0, ns, "rpm").check(Self::RATED_RPM.name, nr)?;
        let p = Self::RATED_POWER_KW.check(rated_power_kw)?;
        let k = Self::BREAKDOWN_RATIO.check(breakdown_ratio)?;
        let i = Self::GEAR_RATIO.check(gear_ratio)?;
        let rated_rad_s = rad_per_s_from_rpm(nr);
        Ok(Self {
            synchronous_rad_s: rad_per_s_from_rpm(ns),
            rated_rad_s,
            rated_torque_n_m: p * 1e3 / rated_rad_s,
            breakdown_ratio: k,
            curve,
            gear_ratio: i,
        })
    }

    /// Rated slip `s_r = 1 − n_r/n_s`.
    pub fn rated_slip(&self) -> f64 {
        1.0 - self.rated_rad_s / self.synchronous_rad_s
    }

    /// Breakdown slip of the Kloss curve, `s_b = s_r·(k + √(k² − 1))` (the root of
    /// `M_r/M_b = 2/(s_r/s_b + s_b/s_r)` on the stable side, `s_b > s_r`).
    pub fn breakdown_slip(&self) -> f64 {
        let k = self.breakdown_ratio;
        self.rated_slip() * (k + (k * k - 1.0).sqrt())
    }

    /// The motor's own torque at its slip `s`, N·m, and `dM/ds`.
    pub fn motor_torque(&self, s: f64) -> (f64, f64) {
        match self.curve {
            MotorCurve::Linear => {
                let c = self.rated_torque_n_m / self.rated_slip();
                (c * s, c)
            }
            MotorCurve::Kloss => {
                let mb = self.breakdown_ratio * self.rated_torque_n_m;
                let sb = self.breakdown_slip();
                // M = 2·M_b·s·s_b/(s² + s_b²): the same as 2M_b/(s/s_b + s_b/s), finite at s = 0.
                let d = s * s + sb * sb;
                let m = 2.0 * mb * s * sb / d;
                (m, 2.0 * mb * sb * (sb * sb - s * s) / (d * d))
            }
        }
    }

    /// The torque at the main shaft turning at `omega` rad/s, N·m, and its derivative in ω.
    pub fn torque(&self, omega: f64) -> (f64, f64) {
        let i = self.gear_ratio;
        let ws = self.synchronous_rad_s;
        let s = 1.0 - i * omega / ws;
        let (m, dm_ds) = self.motor_torque(s);
        (i * m, -i * i * dm_ds / ws)
    }

    /// The main-shaft speed of the breakdown torque (Kloss) — below it the curve is unstable; the
    /// linear curve has none (0).
    pub fn breakdown_speed_rad_s(&self) -> f64 {
        match self.curve {
            MotorCurve::Linear => 0.0,
            MotorCurve::Kloss => self.synchronous_rad_s * (1.0 - self.breakdown_slip()) / self.gear_ratio,
        }
    }

    /// The largest torque the motor gives the main shaft on its stable side, N·m (breakdown for
    /// Kloss; unbounded for the line).
    pub fn max_torque_n_m(&self) -> f64 {
        match self.curve {
            MotorCurve::Linear => f64::INFINITY,
            MotorCurve::Kloss => self.gear_ratio * self.breakdown_ratio * self.rated_torque_n_m,
        }
    }
}

/// A servo drive holding the main shaft's speed with a PI loop and a torque limit.
///
/// `M = clamp(z + K_p·(ω_ref − ω), ±M_max)`, `dz/dt = (K_p/T_i)·(ω_ref − ω)`; the integrator
/// stops while the torque is limited and the error would drive it further (conditional
/// integration, the usual anti-windup).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Servo {
    /// Speed set-point at the main shaft, rad/s.
    pub speed_rad_s: f64,
    /// Proportional gain at the main shaft, N·m per rad/s.
    pub gain_n_m_s: f64,
    /// Integral time, s.
    pub integral_s: f64,
    /// Torque limit at the main shaft, N·m.
    pub torque_limit_n_m: f64,
}

impl Servo {
    /// `servo_gain_n_m_s`: the proportional gain of the speed loop.
    pub const GAIN_N_M_S: Field = Field::new(
        "servo_gain_n_m_s",
        Range::open_closed(0.0, 1e7, "N·m·s"),
        "Proportional gain of the servo's speed loop at the main shaft, N·m per rad/s. Required with \
         motor = servo.",
    );
    /// `servo_integral_s`: the integral time of the speed loop.
    pub const INTEGRAL_S: Field = Field::new(
        "servo_integral_s",
        Range::open_closed(1e-6, 1e3, "s"),
        "Integral time of the servo's speed loop (K_i = K_p/T_i); the integrator makes the mean speed \
         the set-point exactly.",
    )
    .with_default(0.05);
    /// `servo_torque_limit_n_m`: the servo's torque limit at the main shaft.
    pub const TORQUE_LIMIT_N_M: Field = Field::new(
        "servo_torque_limit_n_m",
        Range::open_closed(0.0, 1e7, "N·m"),
        "Torque limit of the servo drive at the main shaft. Required with motor = servo.",
    );

    /// A servo holding `speed_rpm` at the main shaft.
    pub fn new(speed_rpm: f64, gain_n_m_s: f64, integral_s: f64, torque_limit_n_m: f64) -> Result<Self, RippleError> {
        Ok(Self {
            speed_rad_s: rad_per_s_from_rpm(loomkin_units::ShaftSpeed::from_rpm(speed_rpm)?.rpm()),
            gain_n_m_s: Self::GAIN_N_M_S.check(gain_n_m_s)?,
            integral_s: Self::INTEGRAL_S.check(integral_s)?,
            torque_limit_n_m: Self::TORQUE_LIMIT_N_M.check(torque_limit_n_m)?,
        })
    }

    /// The torque at speed `omega` with integrator state `z`, and whether it is limited.
    pub fn torque(&self, omega: f64, z: f64) -> (f64, bool) {
        let m = z + self.gain_n_m_s * (self.speed_rad_s - omega);
        let l = self.torque_limit_n_m;
        if m > l {
            (l, true)
        } else if m < -l {
            (-l, true)
        } else {
            (m, false)
        }
    }

    /// `dz/dφ` (per radian of the main shaft) at speed `omega` and state `z`.
    pub fn dz_dphi(&self, omega: f64, z: f64) -> f64 {
        let e = self.speed_rad_s - omega;
        let (m, limited) = self.torque(omega, z);
        if limited && (m > 0.0) == (e > 0.0) {
            return 0.0;
        }
        self.gain_n_m_s / self.integral_s * e / omega
    }
}

/// The motor of a speed-ripple study.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "motor", rename_all = "kebab-case")]
pub enum Motor {
    /// An ideal drive of constant torque, the one that balances the load over the repeat, turning
    /// the shaft at a mean speed of `speed_rad_s`.
    Constant {
        /// Mean speed (repeat angle over repeat time), rad/s.
        speed_rad_s: f64,
    },
    /// An induction motor through a gear.
    Induction(Induction),
    /// A speed-controlled servo drive.
    Servo(Servo),
}

impl Motor {
    /// The name of the model (`constant`, `induction`, `servo`).
    pub fn name(&self) -> &'static str {
        match self {
            Self::Constant { .. } => "constant",
            Self::Induction(_) => "induction",
            Self::Servo(_) => "servo",
        }
    }
}

/// Which motor model turns the shaft.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MotorKind {
    /// An ideal constant torque.
    #[default]
    Constant,
    /// An induction motor.
    Induction,
    /// A servo drive.
    Servo,
}

impl MotorKind {
    /// The model named `constant`, `induction` or `servo`.
    pub fn parse(field: &str, name: &str) -> Result<Self, RippleError> {
        match name.trim() {
            "constant" => Ok(Self::Constant),
            "induction" => Ok(Self::Induction),
            "servo" => Ok(Self::Servo),
            other => Err(RippleError::field(field, format!("'{other}': expected constant, induction or servo"))),
        }
    }
}

/// A motor as a loom file's `[drive]` table or a command line gives it: every parameter optional,
/// the rules for the ones left out here ([`MotorSpec::build`]).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct MotorSpec {
    /// The model (constant when left out).
    pub motor: Option<MotorKind>,
    /// The induction motor's curve (linear when left out).
    pub motor_curve: Option<MotorCurve>,
    /// [`Induction::SYNCHRONOUS_RPM`].
    pub synchronous_rpm: Option<f64>,
    /// [`Induction::RATED_RPM`].
    pub rated_rpm: Option<f64>,
    /// [`Induction::RATED_POWER_KW`].
    pub rated_power_kw: Option<f64>,
    /// [`Induction::BREAKDOWN_RATIO`].
    pub breakdown_ratio: Option<f64>,
    /// [`Induction::GEAR_RATIO`].
    pub gear_ratio: Option<f64>,
    /// [`Servo::GAIN_N_M_S`].
    pub servo_gain_n_m_s: Option<f64>,
    /// [`Servo::INTEGRAL_S`].
    pub servo_integral_s: Option<f64>,
    /// [`Servo::TORQUE_LIMIT_N_M`].
    pub servo_torque_limit_n_m: Option<f64>,
}

impl MotorSpec {
    /// These parameters with the ones `over` gives put in their place (a command line over a file).
    pub fn overridden(&self, over: &MotorSpec) -> MotorSpec {
        MotorSpec {
            motor: over.motor.or(self.motor),
            motor_curve: over.motor_curve.or(self.motor_curve),
            synchronous_rpm: over.synchronous_rpm.or(self.synchronous_rpm),
            rated_rpm: over.rated_rpm.or(self.rated_rpm),
            rated_power_kw: over.rated_power_kw.or(self.rated_power_kw),
            breakdown_ratio: over.breakdown_ratio.or(self.breakdown_ratio),
            gear_ratio: over.gear_ratio.or(self.gear_ratio),
            servo_gain_n_m_s: over.servo_gain_n_m_s.or(self.servo_gain_n_m_s),
            servo_integral_s: over.servo_integral_s.or(self.servo_integral_s),
            servo_torque_limit_n_m: over.servo_torque_limit_n_m.or(self.servo_torque_limit_n_m),
        }
    }

    /// Refuses a parameter of `over` (a command line over a file) that the motor of `self` (the
    /// parameters in force, [`MotorSpec::overridden`]) does not read: a servo gain with an
    /// induction motor, a breakdown ratio on a linear curve, which would otherwise be ignored
    /// unchecked. `name` turns a key into the front end's name for it (`--servo-gain-n-m-s`).
    pub fn check_read(&self, over: &MotorSpec, name: impl Fn(&str) -> String) -> Result<(), RippleError> {
        let kind = self.motor.unwrap_or_default();
        let kind_name = |k: MotorKind| match k {
            MotorKind::Constant => "constant",
            MotorKind::Induction => "induction",
            MotorKind::Servo => "servo",
        };
        let induction = [
            ("motor_curve", over.motor_curve.is_some()),
            (Induction::SYNCHRONOUS_RPM.name, over.synchronous_rpm.is_some()),
            (Induction::RATED_RPM.name, over.rated_rpm.is_some()),
            (Induction::RATED_POWER_KW.name, over.rated_power_kw.is_some()),
            (Induction::GEAR_RATIO.name, over.gear_ratio.is_some()),
            (Induction::BREAKDOWN_RATIO.name, over.breakdown_ratio.is_some()),
        ];
        let servo = [
            (Servo::GAIN_N_M_S.name, over.servo_gain_n_m_s.is_some()),
            (Servo::INTEGRAL_S.name, over.servo_integral_s.is_some()),
            (Servo::TORQUE_LIMIT_N_M.name, over.servo_torque_limit_n_m.is_some()),
        ];
        for (needs, keys) in [(MotorKind::Induction, &induction[..]), (MotorKind::Servo, &servo[..])] {
            if let Some((key, _)) = keys.iter().find(|(_, given)| *given)
                && kind != needs
            {
                return Err(RippleError::field(
                    name(key),
                    format!(
                        "read only by {} {} motor: give {} {} (the motor here is {})",
                        if needs == MotorKind::Induction { "an" } else { "a" },
                        kind_name(needs),
                        name("motor"),
                        kind_name(needs),
                        kind_name(kind)
                    ),
                ));
            }
        }
        if over.breakdown_ratio.is_some() && self.motor_curve.unwrap_or(MotorCurve::Linear) != MotorCurve::Kloss {
            return Err(RippleError::field(
                name(Induction::BREAKDOWN_RATIO.name),
                format!("read only by Kloss's curve: give {} kloss (the curve here is linear)", name("motor_curve")),
            ));
        }
        Ok(())
    }

    /// The motor for a loom running at `speed_rpm`; errors name the fields as `{prefix}{name}`
    /// (`drive.rated_power_kw`). Constant torque and the servo hold `speed_rpm` as their mean speed
    /// and set-point; an induction motor's gear ratio left out is its rated speed over `speed_rpm`.
    pub fn build(&self, speed_rpm: f64, prefix: &str) -> Result<Motor, RippleError> {
        let named = |f: &Field| format!("{prefix}{}", f.name);
        let need = |v: Option<f64>, f: &Field, kind: &str| {
            v.ok_or_else(|| RippleError::field(named(f), format!("required with motor = {kind}")))
        };
        let check = |f: &Field, v: f64| f.check_as(&named(f), v).map_err(RippleError::from);
        let or_default = |f: &Field, v: Option<f64>| check(f, v.unwrap_or_else(|| f.default_value()));
        let speed = loomkin_units::ShaftSpeed::from_rpm(speed_rpm)?;
        match self.motor.unwrap_or_default() {
            MotorKind::Constant => Ok(Motor::Constant { speed_rad_s: speed.rad_per_s() }),
            MotorKind::Induction => {
                let ns = or_default(&Induction::SYNCHRONOUS_RPM, self.synchronous_rpm)?;
                let nr = or_default(&Induction::RATED_RPM, self.rated_rpm)?;
                if nr >= ns {
                    return Err(RippleError::field(
                        named(&Induction::RATED_RPM),
                        format!(
                            "{} rpm: allowed below the synchronous speed {} rpm",
                            loomkin_units::compact(nr),
                            loomkin_units::compact(ns)
                        ),
                    ));
                }
                let p = check(
                    &Induction::RATED_POWER_KW,
                    need(self.rated_power_kw, &Induction::RATED_POWER_KW, "induction")?,
                )?;
                let k = or_default(&Induction::BREAKDOWN_RATIO, self.breakdown_ratio)?;
                let i = check(&Induction::GEAR_RATIO, self.gear_ratio.unwrap_or(nr / speed.rpm()))?;
                Ok(Motor::Induction(Induction::new(ns, nr, p, k, self.motor_curve.unwrap_or(MotorCurve::Linear), i)?))
            }
            MotorKind::Servo => {
                let kp = check(&Servo::GAIN_N_M_S, need(self.servo_gain_n_m_s, &Servo::GAIN_N_M_S, "servo")?)?;
                let ti = or_default(&Servo::INTEGRAL_S, self.servo_integral_s)?;
                let lim = check(
                    &Servo::TORQUE_LIMIT_N_M,
                    need(self.servo_torque_limit_n_m, &Servo::TORQUE_LIMIT_N_M, "servo")?,
                )?;
                Ok(Motor::Servo(Servo::new(speed.rpm(), kp, ti, lim)?))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_parameter_the_motor_does_not_read_is_refused_by_name() {
        let flag = |k: &str| format!("--{}", k.replace('_', "-"));
        let file = MotorSpec { motor: Some(MotorKind::Induction), rated_power_kw: Some(5.5), ..MotorSpec::default() };
        // A servo gain over an induction motor of the file.
        let over = MotorSpec { servo_gain_n_m_s: Some(100.0), ..MotorSpec::default() };
        let e = file.overridden(&over).check_read(&over, flag).unwrap_err().to_string();
        assert_eq!(
            e,
            "--servo-gain-n-m-s: read only by a servo motor: give --motor servo (the motor here is induction)"
        );
        // The same with --motor servo is read.
        let over = MotorSpec { motor: Some(MotorKind::Servo), ..over };
        assert!(file.overridden(&over).check_read(&over, flag).is_ok());
        // Induction parameters over the default constant motor.
        let over = MotorSpec { gear_ratio: Some(3.0), ..MotorSpec::default() };
        let e = MotorSpec::default().overridden(&over).check_read(&over, flag).unwrap_err().to_string();
        assert!(e.starts_with("--gear-ratio: read only by an induction motor: give --motor induction"), "{e}");
        // Over an induction motor they are read; the breakdown ratio only on Kloss's curve.
        assert!(file.overridden(&over).check_read(&over, flag).is_ok());
        let over = MotorSpec { breakdown_ratio: Some(2.5), ..MotorSpec::default() };
        let e = file.overridden(&over).check_read(&over, flag).unwrap_err().to_string();
        assert!(e.starts_with("--breakdown-ratio: read only by Kloss's curve: give --motor-curve kloss"), "{e}");
        let over = MotorSpec { motor_curve: Some(MotorCurve::Kloss), ..over };
        assert!(file.overridden(&over).check_read(&over, flag).is_ok());
        // The file's own parameters of another motor are not the command line's: not refused.
        let both = MotorSpec { servo_gain_n_m_s: Some(100.0), ..file };
        assert!(both.check_read(&MotorSpec::default(), flag).is_ok());
    }

    fn motor(curve: MotorCurve) -> Induction {
        Induction::new(1500.0, 1450.0, 5.5, 2.5, curve, 2.9).unwrap()
    }

    #[test]
    fn both_curves_pass_the_rated_point_and_vanish_at_synchronous_speed() {
        for c in [MotorCurve::Linear, MotorCurve::Kloss] {
            let m = motor(c);
            let rated = m.rated_rad_s / m.gear_ratio;
            let (t, _) = m.torque(rated);
            assert!((t - m.gear_ratio * m.rated_torque_n_m).abs() <= 1e-12 * t, "{c:?} {t}");
            assert_eq!(m.torque(m.synchronous_rad_s / m.gear_ratio).0, 0.0);
        }
        // Rated torque from the nameplate: 5.5 kW at 1450 rpm.
        let m = motor(MotorCurve::Kloss);
        assert!((m.rated_torque_n_m - 5500.0 / (1450.0 * std::f64::consts::PI / 30.0)).abs() < 1e-12);
    }

    #[test]
    fn kloss_peaks_at_the_breakdown_torque_and_slip() {
        let m = motor(MotorCurve::Kloss);
        let sb = m.breakdown_slip();
        let (t, d) = m.motor_torque(sb);
        assert!((t - 2.5 * m.rated_torque_n_m).abs() <= 1e-12 * t);
        assert!(d.abs() <= 1e-9 * t);
        // No slip on a grid gives more.
        let best = (1..20_000).map(|k| m.motor_torque(k as f64 * 5e-5).0).fold(0.0, f64::max);
        assert!(best <= t * (1.0 + 1e-15));
    }

    #[test]
    fn the_derivative_matches_finite_differences() {
        for c in [MotorCurve::Linear, MotorCurve::Kloss] {
            let m = motor(c);
            for w in [40.0, 50.0, 52.0, 54.0] {
                let h = 1e-5;
                let fd = (m.torque(w + h).0 - m.torque(w - h).0) / (2.0 * h);
                let d = m.torque(w).1;
                assert!((fd - d).abs() <= 1e-7 * d.abs().max(1.0), "{c:?} {w}: {fd} vs {d}");
            }
        }
    }

    #[test]
    fn the_servo_integrator_stops_when_limited_and_pushed_further() {
        let s = Servo::new(500.0, 50.0, 0.05, 100.0).unwrap();
        // Far below the set-point: torque limited at +100, error positive: no integration.
        assert_eq!(s.torque(0.5 * s.speed_rad_s, 0.0), (100.0, true));
        assert_eq!(s.dz_dphi(0.5 * s.speed_rad_s, 0.0), 0.0);
        // Limited but the error pulls back: integrates.
        assert!(s.dz_dphi(1.01 * s.speed_rad_s, 200.0) < 0.0);
        let e = Induction::new(1500.0, 1600.0, 5.5, 2.5, MotorCurve::Linear, 2.9).unwrap_err();
        assert!(e.to_string().contains("rated_rpm"), "{e}");
    }

    #[test]
    fn a_spec_builds_its_motor_with_the_rules_for_what_is_left_out() {
        let spec = MotorSpec { motor: Some(MotorKind::Induction), rated_power_kw: Some(5.5), ..MotorSpec::default() };
        let Motor::Induction(m) = spec.build(500.0, "drive.").unwrap() else { panic!() };
        // Gear ratio: rated 1450 rpm over the loom's 500 rpm.
        assert!((m.gear_ratio - 2.9).abs() < 1e-15);
        assert_eq!(m.curve, MotorCurve::Linear);
        let e =
            MotorSpec { motor: Some(MotorKind::Induction), ..MotorSpec::default() }.build(500.0, "drive.").unwrap_err();
        assert_eq!(e.to_string(), "drive.rated_power_kw: required with motor = induction");
        let over = spec.overridden(&MotorSpec { rated_rpm: Some(1600.0), ..MotorSpec::default() });
        let e = over.build(500.0, "drive.").unwrap_err();
        assert!(e.to_string().starts_with("drive.rated_rpm: 1600 rpm"), "{e}");
        assert_eq!(
            MotorSpec::default().build(500.0, "").unwrap(),
            Motor::Constant { speed_rad_s: 500.0 * std::f64::consts::PI / 30.0 }
        );
    }
}
