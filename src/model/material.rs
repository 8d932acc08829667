//! Isotropic linear-elastic materials, and the `[material]` section of a problem file.

use serde::{Deserialize, Serialize};

use crate::model::Dimension;
use crate::problem::reader::{k, quoted, Res};
use crate::problem::schema::{Number, Quantity};
use crate::problem::sections::Sections;

/// The `[material]` section as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMaterial {
    pub preset: Option<String>,
    pub name: Option<String>,
    pub youngs_modulus: Option<Quantity>,
    pub poisson_ratio: Option<Number>,
    pub ultimate_strength: Option<Quantity>,
    pub density: Option<Quantity>,
}

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

impl Material {
    /// Reads the `[material]` section: a preset, or the values, or a preset with some
    /// values overridden.
    pub fn from_section(s: &Sections, m: &RawMaterial) -> Res<Material> {
        let path = |key: &str| [k("material"), k(key)];
        let mut mat = match &m.preset {
            Some(p) => Material::preset(p).ok_or_else(|| {
                s.err(
                    &path("preset"),
                    format!(
                        "unknown material \"{p}\"; expected one of {}",
                        quoted(Material::PRESETS)
                    ),
                )
            })?,
            None => {
                if m.youngs_modulus.is_none() || m.poisson_ratio.is_none() {
                    let missing = if m.youngs_modulus.is_none() {
                        "youngs_modulus"
                    } else {
                        "poisson_ratio"
                    };
                    return Err(s.err(
                        &path(missing),
                        format!(
                            "missing: give a `preset` ({}) or the material's values",
                            quoted(Material::PRESETS)
                        ),
                    ));
                }
                Material {
                    name: "custom".into(),
                    youngs_modulus: f64::NAN,
                    poisson_ratio: f64::NAN,
                    ultimate_strength: None,
                    density: f64::NAN,
                }
            }
        };
        if let Some(n) = &m.name {
            mat.name = n.clone();
        }
        if let Some(q) = &m.youngs_modulus {
            mat.youngs_modulus = s.positive(&path("youngs_modulus"), q, Dimension::Stress)?;
        }
        if let Some(n) = m.poisson_ratio {
            let nu = s.finite(&path("poisson_ratio"), n)?;
            if !(nu > -1.0 && nu < 0.5) {
                return Err(s.err(
                    &path("poisson_ratio"),
                    format!("must lie in (-1, 0.5), got {nu}"),
                ));
            }
            mat.poisson_ratio = nu;
        }
        if let Some(q) = &m.ultimate_strength {
            mat.ultimate_strength =
                Some(s.positive(&path("ultimate_strength"), q, Dimension::Stress)?);
        }
        if let Some(q) = &m.density {
            mat.density = density(q).map_err(|msg| s.err(&path("density"), msg))?;
        }
        Ok(mat)
    }
}

/// Density has a unit of its own: `"2810 kg/m3"` or `"2.81 g/cm3"`.
fn density(q: &Quantity) -> Result<f64, String> {
    let Quantity::Text(t) = q else {
        return Err("expected a density with its unit, e.g. \"2810 kg/m3\"".into());
    };
    let t = t.trim();
    let (num, unit) = t.split_at(t.find(char::is_whitespace).unwrap_or(t.len()));
    let factor = match unit.trim() {
        "kg/m3" | "kg/m^3" => 1.0,
        "g/cm3" | "g/cm^3" => 1000.0,
        u => {
            return Err(format!(
                "unknown unit \"{u}\" for a density; expected \"kg/m3\" or \"g/cm3\""
            ))
        }
    };
    match num.parse::<f64>() {
        // from aerogels to osmium, with room
        Ok(v) if v.is_finite() && (1e-3..=1e6).contains(&(v * factor)) => Ok(v * factor),
        _ => Err(format!(
            "\"{t}\" is not a density between 1e-3 and 1e6 kg/m3, e.g. \"2810 kg/m3\""
        )),
    }
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
