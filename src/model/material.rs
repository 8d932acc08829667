//! Isotropic linear-elastic materials.

use serde::Serialize;

/// An isotropic linear-elastic material, SI units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Material {
    pub name: String,
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio nu (dimensionless).
    pub poisson_ratio: f64,
    /// Ultimate (tensile) strength sigma_u (Pa), when known.
    pub ultimate_strength: Option<f64>,
    /// Density rho (kg/m^3).
    pub density: f64,
}

impl Material {
    /// Shear modulus G = E / (2 (1 + nu)), as paper 004 Sec. 3 computes it.
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Aluminium alloy 7075-T6 as paper 004 (Sec. 3) gives it: E = 72 GPa, nu = 0.33,
    /// sigma_u = 505 MPa; the density 2810 kg/m^3 is the handbook value.
    pub fn al7075_t6() -> Self {
        Material {
            name: "al7075-t6".into(),
            youngs_modulus: 72e9,
            poisson_ratio: 0.33,
            ultimate_strength: Some(505e6),
            density: 2810.0,
        }
    }

    /// 65Si2Mn spring steel as paper 001 gives it: E = 210 GPa, nu = 0.28, 7850 kg/m^3.
    /// Paper 001 prints no strength and the grade's strength depends on its heat
    /// treatment, so none is assumed: a problem that limits stress as a fraction of
    /// the ultimate strength must state it.
    pub fn spring_steel_65si2mn() -> Self {
        Material {
            name: "65si2mn".into(),
            youngs_modulus: 210e9,
            poisson_ratio: 0.28,
            ultimate_strength: None,
            density: 7850.0,
        }
    }

    /// The presets by the names a problem file uses.
    pub fn preset(name: &str) -> Option<Self> {
        match name {
            "al7075-t6" => Some(Self::al7075_t6()),
            "65si2mn" => Some(Self::spring_steel_65si2mn()),
            _ => None,
        }
    }

    /// Names accepted by [`Material::preset`].
    pub const PRESETS: &'static [&'static str] = &["al7075-t6", "65si2mn"];
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shear_modulus_of_al7075() {
        let g = Material::al7075_t6().shear_modulus();
        assert!((g - 72e9 / 2.66).abs() < 1e-3);
    }

    #[test]
    fn every_preset_name_resolves() {
        for name in Material::PRESETS {
            assert_eq!(Material::preset(name).unwrap().name, *name);
        }
        assert!(Material::preset("unobtainium").is_none());
    }
}
