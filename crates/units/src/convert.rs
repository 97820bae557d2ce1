//! Unit conversions, named once. loomkin computes in SI (m, rad, s); files and front ends may speak
//! mm and degrees, and convert at their edge with these.

/// Standard gravity g₀, m/s² (the conventional value, CGPM 1901): the weight of a mass on a loom.
pub const STANDARD_GRAVITY_M_S2: f64 = 9.806_65;

/// Millimetres per metre (a scale for descriptors given in mm, `Range::in_unit`).
pub const MM_PER_M: f64 = 1000.0;

/// Milliseconds per second.
const MS_PER_S: f64 = 1000.0;

/// Milliseconds from seconds.
#[inline]
pub fn ms_from_s(s: f64) -> f64 {
    s * MS_PER_S
}

/// Metres from millimetres.
#[inline]
pub fn m_from_mm(mm: f64) -> f64 {
    mm / MM_PER_M
}

/// Millimetres from metres.
#[inline]
pub fn mm_from_m(m: f64) -> f64 {
    m * MM_PER_M
}

/// Radians from degrees (exact for multiples of 90° as far as `f64` allows).
#[inline]
pub fn rad_from_deg(deg: f64) -> f64 {
    deg.to_radians()
}

/// Degrees from radians.
#[inline]
pub fn deg_from_rad(rad: f64) -> f64 {
    rad.to_degrees()
}

/// Seconds per minute.
const S_PER_MIN: f64 = 60.0;

/// Angular speed in rad/s from a speed in rpm, `rpm·2π/60` (the product first, then the division:
/// the rounding every study of loomkin has used, so their figures keep their last bits;
/// [`crate::ShaftSpeed::rad_per_s`] is a checked main-shaft speed's).
#[inline]
pub fn rad_per_s_from_rpm(rpm: f64) -> f64 {
    rpm * std::f64::consts::TAU / S_PER_MIN
}

/// Speed in rpm from an angular speed in rad/s, `ω·60/2π` (a motor's speed from its shaft's).
#[inline]
pub fn rpm_from_rad_per_s(rad_per_s: f64) -> f64 {
    rad_per_s * S_PER_MIN / std::f64::consts::TAU
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speeds_are_the_formulas_they_replace_bit_for_bit() {
        use std::f64::consts::PI;
        for rpm in [0.0, 1e-3, 1.0, 200.0, 333.3, 600.0, 750.0, 1e5, 12345.678] {
            assert_eq!(rad_per_s_from_rpm(rpm).to_bits(), (rpm * 2.0 * PI / 60.0).to_bits());
            let w = rad_per_s_from_rpm(rpm);
            assert_eq!(rpm_from_rad_per_s(w).to_bits(), (w * 60.0 / (2.0 * PI)).to_bits());
            assert!((rpm_from_rad_per_s(w) - rpm).abs() <= 4.0 * f64::EPSILON * rpm);
        }
        // 60 rpm is one revolution per second (to the rounding of the product 60·2π).
        let tau = std::f64::consts::TAU;
        assert!((rad_per_s_from_rpm(60.0) - tau).abs() <= f64::EPSILON * tau);
    }

    #[test]
    fn round_trips() {
        for v in [0.0, 1e-9, 0.36, 180.0, -47.0, 1e6] {
            assert!((m_from_mm(mm_from_m(v)) - v).abs() <= 1e-15 * v.abs());
            assert!((deg_from_rad(rad_from_deg(v)) - v).abs() <= 1e-14 * v.abs());
        }
        assert_eq!(rad_from_deg(180.0), std::f64::consts::PI);
        assert_eq!(mm_from_m(0.015_5), 15.5);
    }
}
