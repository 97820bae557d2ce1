//! The elastic picking mechanism (the paper's Fig. 1) and its derived constants B, C, D (eq. 4).

use crate::Result;
use crate::units::{KG_M2_PER_KGF_CM_S2, KG_PER_KGF_S2_PER_CM, M_PER_CM, M_PER_N_PER_CM_PER_KGF, N_PER_KGF};
use loomkin_units::Range;
use serde::{Deserialize, Serialize};

/// Dimensions, compliances and masses of an under-pick picking mechanism, in SI.
///
/// Symbols of the paper: picker-head travel x along the stick's tip, stick length l (pivot to
/// picker), strap-loop height k (pivot to strap), return-spring radius r.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Params {
    /// c₁: compliance of the picking stick at the picker, m/N, for the strap at `k_m`.
    pub c1_m_per_n: f64,
    /// c₂ + c₃: compliance of the strap loop plus the picking shaft, m/N.
    pub c23_m_per_n: f64,
    /// c₄: compliance of the stick's return spring, m/N.
    pub c4_m_per_n: f64,
    /// Θ: moment of inertia of picking stick and shoe about the pivot, kg·m².
    pub theta_kg_m2: f64,
    /// m: shuttle mass, kg.
    pub shuttle_kg: f64,
    /// l: picking-stick length from the pivot to the picker, m.
    pub l_m: f64,
    /// k: height of the strap loop above the pivot, m (0 < k < l).
    pub k_m: f64,
    /// r: radius at which the return spring acts, m.
    pub r_m: f64,
    /// F₀: checking force on the shuttle, N.
    pub checking_n: f64,
}

/// The derived constants of the equation of motion B·ẍ + (C + 1)·x = s − D (eqs. 4, 5).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Constants {
    /// B = m·c₁ + (c₂+c₃)·(m·l² + Θ)/k², in s².
    pub b_s2: f64,
    /// C = r²·(c₂+c₃)/(k²·c₄), dimensionless.
    pub c: f64,
    /// D = F₀·(c₁ + l²·(c₂+c₃)/k²), in m: the static deflection under the checking force.
    pub d_m: f64,
}

impl Constants {
    /// Natural circular frequency of the loaded mechanism ψ = √((C+1)/B), in 1/s.
    pub fn natural_1_s(&self) -> f64 {
        ((self.c + 1.0) / self.b_s2).sqrt()
    }
}

impl Params {
    /// The mechanism measured by Jederán (1959, §1.2), converted once from kgf, cm, s to SI:
    /// c₁ = 3.54·10⁻² cm/kgf, c₂+c₃ = 0.2851·10⁻² cm/kgf, c₄ = 0.62 cm/kgf, Θ = 1.8542 kgf·cm·s²,
    /// l = 74 cm, k = 23 cm, r = 8.3 cm, m = 0.428·10⁻³ kgf·s²/cm (0.4197 kg, a 420 g shuttle),
    /// F₀ = 5 kgf.
    pub fn paper() -> Self {
        Self {
            c1_m_per_n: 3.54e-2 * M_PER_N_PER_CM_PER_KGF,
            c23_m_per_n: 0.2851e-2 * M_PER_N_PER_CM_PER_KGF,
            c4_m_per_n: 0.62 * M_PER_N_PER_CM_PER_KGF,
            theta_kg_m2: 1.8542 * KG_M2_PER_KGF_CM_S2,
            shuttle_kg: 0.428e-3 * KG_PER_KGF_S2_PER_CM,
            l_m: 74.0 * M_PER_CM,
            k_m: 23.0 * M_PER_CM,
            r_m: 8.3 * M_PER_CM,
            checking_n: 5.0 * N_PER_KGF,
        }
    }

    /// Checks every field: compliances, Θ, m, l, r positive; 0 < k < l; F₀ ≥ 0.
    pub fn validate(&self) -> Result<()> {
        Range::open_closed(0.0, 1.0, "m/N").check("c1_m_per_n", self.c1_m_per_n)?;
        Range::open_closed(0.0, 1.0, "m/N").check("c23_m_per_n", self.c23_m_per_n)?;
        Range::open_closed(0.0, 1.0, "m/N").check("c4_m_per_n", self.c4_m_per_n)?;
        Range::open_closed(0.0, 1e3, "kg·m²").check("theta_kg_m2", self.theta_kg_m2)?;
        Range::open_closed(0.0, 100.0, "kg").check("shuttle_kg", self.shuttle_kg)?;
        Range::open_closed(0.0, 10.0, "m").check("l_m", self.l_m)?;
        Range::open(0.0, self.l_m, "m").check("k_m", self.k_m)?;
        Range::open_closed(0.0, 10.0, "m").check("r_m", self.r_m)?;
        Range::closed(0.0, 1e5, "N").check("checking_n", self.checking_n)?;
        Ok(())
    }

    /// Stick compliance with the strap loop at height `k_m` (eq. 20a): c₁ = (l − k)²·l / (3·J·E).
    ///
    /// The paper gives no J·E; it is calibrated so that `c1_m_per_n` holds at the designed `k_m`,
    /// i.e. c₁(k) = c₁·(l − k)² / (l − k_design)².
    pub fn c1_at_strap(&self, k_m: f64) -> f64 {
        let r = (self.l_m - k_m) / (self.l_m - self.k_m);
        self.c1_m_per_n * r * r
    }

    /// B, C, D (eq. 4) with the strap at `k_m` (c₁ from eq. 20a), shuttle mass `shuttle_kg` and
    /// checking force `checking_n`. The caller validates the three values.
    pub fn constants_at(&self, k_m: f64, shuttle_kg: f64, checking_n: f64) -> Constants {
        let c1 = self.c1_at_strap(k_m);
        let k2 = k_m * k_m;
        let l = self.l_m;
        Constants {
            b_s2: shuttle_kg * c1 + self.c23_m_per_n * (shuttle_kg * l * l + self.theta_kg_m2) / k2,
            c: self.r_m * self.r_m * self.c23_m_per_n / (k2 * self.c4_m_per_n),
            d_m: checking_n * (c1 + l * l * self.c23_m_per_n / k2),
        }
    }

    /// B, C, D at the designed strap position, shuttle and checking force.
    pub fn constants(&self) -> Constants {
        self.constants_at(self.k_m, self.shuttle_kg, self.checking_n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Eq. 4 evaluated by hand in the paper's own units (kgf, cm, s), then converted: B is in s²
    /// in both systems, C is dimensionless, D goes cm → m.
    #[test]
    fn constants_match_the_paper_units() {
        let (c1, c23, c4, th, m, l, k, r, f0) = (3.54e-2, 0.2851e-2, 0.62, 1.8542, 0.428e-3, 74.0, 23.0, 8.3, 5.0);
        let b = m * c1 + l / (k * k) * c23 * (m * l + th / l);
        let c = r * r / (k * k * c4) * c23;
        let d_cm = f0 * (c1 + l * l / (k * k) * c23);
        let si = Params::paper().constants();
        assert!((si.b_s2 / b - 1.0).abs() < 1e-12, "{} vs {b}", si.b_s2);
        assert!((si.c / c - 1.0).abs() < 1e-12);
        assert!((si.d_m / (d_cm * 0.01) - 1.0).abs() < 1e-12);
        // Orders of magnitude worth remembering: B ≈ 3.78e-5 s², C ≈ 6.0e-4, D ≈ 3.25 mm.
        assert!((si.b_s2 - 3.7776e-5).abs() < 1e-8);
        assert!((si.d_m - 3.2456e-3).abs() < 1e-6);
    }

    #[test]
    fn c1_follows_eq_20a() {
        let p = Params::paper();
        assert_eq!(p.c1_at_strap(p.k_m), p.c1_m_per_n);
        let ratio = p.c1_at_strap(0.13) / p.c1_m_per_n;
        assert!((ratio - (61.0f64 / 51.0).powi(2)).abs() < 1e-12);
    }

    #[test]
    fn validation_names_the_field() {
        let mut p = Params::paper();
        p.k_m = 0.80;
        let e = p.validate().unwrap_err().to_string();
        assert!(e.contains("k_m") && e.contains("0.74"), "{e}");
        p = Params::paper();
        p.shuttle_kg = -1.0;
        assert!(p.validate().unwrap_err().to_string().contains("shuttle_kg"));
    }
}
