//! Stress limits written as a fraction of the material's strength.

use crate::model::material::{Material, STRENGTH_FRACTIONS};
use crate::vocab::units::Unit;
use crate::vocab::Dimension;

/// The unit `"yield"` or `"ultimate"` of a stress constraint: a fraction of the
/// material's strength; `None` for any other unit name.
pub fn strength_fraction(
    name: &str,
    dimension: Dimension,
    material: Option<&Material>,
    output: &str,
) -> Result<Option<Unit>, String> {
    let [yield_, ultimate] = STRENGTH_FRACTIONS;
    let strength = match name {
        n if n == yield_ => material.map(|m| m.yield_strength),
        n if n == ultimate => material.map(|m| m.ultimate_strength),
        _ => return Ok(None),
    };
    if dimension != Dimension::Stress {
        return Err(format!(
            "\"{name}\" (a fraction of the {name} strength) only fits stress outputs, not \
             \"{output}\""
        ));
    }
    let strength = match (material, strength.flatten()) {
        (_, Some(s)) => s,
        (Some(m), None) => {
            return Err(format!(
                "material \"{}\" has no {name} strength: set material.{name}_strength",
                m.name
            ))
        }
        (None, _) => return Err(format!("this model has no material, so no {name} strength")),
    };
    Ok(Some(Unit {
        name: name.into(),
        dimension,
        to_si: strength,
    }))
}
