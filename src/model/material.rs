//! Isotropic linear-elastic materials, and the `[material]` section of a problem file.

use serde::{Deserialize, Serialize};

use crate::vocab::reader::{k, quoted, Res};
use crate::vocab::schema::{quantity_pattern, Measured, PositiveStress, Sign};
use crate::vocab::sections::Sections;
use crate::vocab::values::{Number, Quantity};

/// The `[material]` section as written.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(extend("anyOf" = [
    {"required": ["preset"]},
    {"required": ["youngs_modulus", "poisson_ratio"]},
]))]
pub struct RawMaterial {
    #[schemars(extend("enum" = Material::PRESETS))]
    pub preset: Option<String>,
    pub name: Option<String>,
    pub youngs_modulus: Option<Measured<PositiveStress>>,
    #[schemars(extend(
        "exclusiveMinimum" = POISSON_RATIO.0,
        "exclusiveMaximum" = POISSON_RATIO.1
    ))]
    pub poisson_ratio: Option<Number>,
    pub yield_strength: Option<Measured<PositiveStress>>,
    pub ultimate_strength: Option<Measured<PositiveStress>>,
    #[schemars(schema_with = "density_schema")]
    #[serde(default)]
    pub density: Option<Quantity>,
}

/// Poisson's ratio lies strictly between these.
const POISSON_RATIO: (f64, f64) = (-1.0, 0.5);

/// The units of a density, with their factors to kg/m^3.
const DENSITY_UNITS: [(&str, f64); 4] = [
    ("kg/m3", 1.0),
    ("kg/m^3", 1.0),
    ("g/cm3", 1000.0),
    ("g/cm^3", 1000.0),
];

fn density_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
    let names: Vec<&str> = DENSITY_UNITS.iter().map(|u| u.0).collect();
    schemars::json_schema!({
        "type": "string",
        "pattern": quantity_pattern(Sign::Positive, &names),
        "description": "A density with its unit, e.g. \"2810 kg/m3\" or \"2.81 g/cm3\"",
    })
}

/// An isotropic linear-elastic material, SI units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Material {
    pub name: String,
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio nu (dimensionless).
    pub poisson_ratio: f64,
    /// Yield (0.2 % proof) strength (Pa), when known.
    pub yield_strength: Option<f64>,
    /// Ultimate (tensile) strength sigma_u (Pa), when known.
    pub ultimate_strength: Option<f64>,
    /// Density rho (kg/m^3).
    pub density: f64,
}

/// One preset: name, E (GPa), nu, yield and ultimate strength (MPa), density (kg/m^3).
/// The figures and their sources are in docs/materials.md: specification minimums for the
/// strengths where a specification gives them, handbook values for the rest.
const PRESETS: [(&str, f64, f64, f64, f64, f64); 7] = [
    // paper 004 Sec. 3: E = 72 GPa, nu = 0.33, sigma_u = 505 MPa (the paper's figure, kept
    // so that its study reproduces; the handbook's typical yield is 503 MPa)
    ("al7075-t6", 72.0, 0.33, 503.0, 505.0, 2810.0),
    ("al6061-t6", 68.9, 0.33, 240.0, 290.0, 2700.0),
    ("ti6al4v", 113.8, 0.342, 828.0, 895.0, 4430.0),
    // paper 001: E = 210 GPa, nu = 0.28; strengths: GB/T 1222's minimums for 60Si2Mn
    ("65si2mn", 210.0, 0.28, 1375.0, 1570.0, 7850.0),
    ("17-4ph-h900", 196.0, 0.272, 1170.0, 1310.0, 7780.0),
    ("c17200", 131.0, 0.30, 965.0, 1140.0, 8260.0),
    ("50crva", 206.0, 0.29, 1130.0, 1275.0, 7850.0),
];

impl Material {
    /// Shear modulus G = E / (2 (1 + nu)), as paper 004 Sec. 3 computes it.
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Aluminium alloy 7075-T6 as paper 004 (Sec. 3) gives it: E = 72 GPa, nu = 0.33,
    /// sigma_u = 505 MPa; yield 503 MPa and density 2810 kg/m^3 are handbook values.
    pub fn al7075_t6() -> Self {
        Self::preset("al7075-t6").expect("a preset")
    }

    /// 65Si2Mn spring steel as paper 001 gives it: E = 210 GPa, nu = 0.28, 7850 kg/m^3;
    /// the paper prints no strength: the preset takes GB/T 1222's minimums for the
    /// nearest standard grade, 60Si2Mn, quenched and tempered (docs/materials.md).
    pub fn spring_steel_65si2mn() -> Self {
        Self::preset("65si2mn").expect("a preset")
    }

    /// The presets by the names a problem file uses.
    pub fn preset(name: &str) -> Option<Self> {
        PRESETS
            .iter()
            .find(|p| p.0 == name)
            .map(|&(name, e, nu, fy, fu, rho)| Material {
                name: name.into(),
                youngs_modulus: e * 1e9,
                poisson_ratio: nu,
                yield_strength: Some(fy * 1e6),
                ultimate_strength: Some(fu * 1e6),
                density: rho,
            })
    }

    /// Names accepted by [`Material::preset`].
    pub const PRESETS: &'static [&'static str] = &[
        "al7075-t6",
        "al6061-t6",
        "ti6al4v",
        "65si2mn",
        "17-4ph-h900",
        "c17200",
        "50crva",
    ];
}

/// The strengths a stress limit may be written as a fraction of (`unit = "ultimate"`): a
/// constraint's unit names one, and the material must give it.
pub const STRENGTH_FRACTIONS: [&str; 2] = ["yield", "ultimate"];

/// The rules of the JSON Schema that come with a material read from the section `section`:
/// a constraint whose unit is a strength fraction needs that strength, from a preset (every
/// preset gives both) or the section's own `<fraction>_strength`.
pub fn strength_rules(section: &str) -> Vec<serde_json::Value> {
    STRENGTH_FRACTIONS
        .iter()
        .map(|fraction| {
            serde_json::json!({
                "if": {
                    "properties": {"constraints": {"contains": {
                        "properties": {"unit": {"const": fraction}},
                        "required": ["unit"],
                    }}},
                    "required": ["constraints"],
                },
                "then": {"properties": {section: {"anyOf": [
                    {"required": ["preset"]},
                    {"required": [format!("{fraction}_strength")]},
                ]}}},
            })
        })
        .collect()
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
                    yield_strength: None,
                    ultimate_strength: None,
                    density: f64::NAN,
                }
            }
        };
        if let Some(n) = &m.name {
            mat.name = n.clone();
        }
        if let Some(q) = &m.youngs_modulus {
            mat.youngs_modulus = s.measured(&path("youngs_modulus"), q)?;
        }
        if let Some(n) = m.poisson_ratio {
            let nu = s.finite(&path("poisson_ratio"), n)?;
            let (lo, hi) = POISSON_RATIO;
            if !(nu > lo && nu < hi) {
                return Err(s.err(
                    &path("poisson_ratio"),
                    format!("must lie in ({lo}, {hi}), got {nu}"),
                ));
            }
            mat.poisson_ratio = nu;
        }
        if let Some(q) = &m.yield_strength {
            mat.yield_strength = Some(s.measured(&path("yield_strength"), q)?);
        }
        if let Some(q) = &m.ultimate_strength {
            mat.ultimate_strength = Some(s.measured(&path("ultimate_strength"), q)?);
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
    let unit = unit.trim();
    let Some(&(_, factor)) = DENSITY_UNITS.iter().find(|(name, _)| *name == unit) else {
        return Err(format!(
            "unknown unit \"{unit}\" for a density; expected \"kg/m3\" or \"g/cm3\""
        ));
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
        assert_eq!(Material::PRESETS.len(), PRESETS.len());
        for name in Material::PRESETS {
            let m = Material::preset(name).unwrap();
            assert_eq!(m.name, *name);
            // yield below ultimate, every figure physical
            assert!(m.yield_strength.unwrap() <= m.ultimate_strength.unwrap());
            assert!(m.poisson_ratio > 0.2 && m.poisson_ratio < 0.4);
        }
        assert!(Material::preset("unobtainium").is_none());
    }
}
