//! Unit conversions, named once. loomkin computes in SI (m, rad, s); files and front ends may speak
//! mm and degrees, and convert at their edge with these.

/// Millimetres per metre.
const MM_PER_M: f64 = 1000.0;

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

#[cfg(test)]
mod tests {
    use super::*;

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
