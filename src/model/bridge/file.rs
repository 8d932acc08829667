//! The bridge's sections of a problem file: `[material]`, `[hinge]`, `[actuator]` and the
//! optional `[dynamics]`, read and validated into a [`Bridge`].

use std::sync::Arc;

use serde::Deserialize;

use super::dynamics::DynamicsSettings;
use super::{Actuator, Bridge, BridgeSettings};
use crate::model::hinge::HingeKind;
use crate::model::material::{Material, RawMaterial};
use crate::model::{Dimension, Model};
use crate::problem::reader::{k, quoted, Res};
use crate::problem::schema::{Number, Quantity};
use crate::problem::sections::Sections;

/// The sections the bridge reads.
pub const SECTIONS: &[&str] = &["material", "hinge", "actuator", "dynamics"];

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawHinge {
    kind: String,
    width: Quantity,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawActuator {
    nominal_stroke: Quantity,
    preload: Quantity,
    stiffness: Option<Quantity>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDynamics {
    payload_mass: Quantity,
    input_link_mass: Quantity,
    output_link_mass: Quantity,
    link_thickness: Quantity,
    damping_ratio: Number,
}

/// Reads the bridge's sections and builds the model.
pub fn build(s: &mut Sections) -> Res<Arc<dyn Model>> {
    let m: RawMaterial = s.required("material")?;
    let h: RawHinge = s.required("hinge")?;
    let a: RawActuator = s.required("actuator")?;
    let d: Option<RawDynamics> = s.optional("dynamics")?;
    let material = Material::from_section(s, &m)?;
    let kind = hinge_kind(s, &h.kind)?;
    let settings = BridgeSettings {
        hinge_b: kind,
        hinge_d: kind,
        width: s.positive(&[k("hinge"), k("width")], &h.width, Dimension::Length)?,
        material,
        actuator: actuator(s, &a)?,
        dynamics: d.as_ref().map(|d| dynamics(s, d)).transpose()?,
    };
    Ok(Arc::new(Bridge::new(settings)))
}

fn hinge_kind(s: &Sections, kind: &str) -> Res<HingeKind> {
    HingeKind::from_name(kind).ok_or_else(|| {
        s.err(
            &[k("hinge"), k("kind")],
            format!(
                "unknown hinge kind \"{kind}\"; expected one of {}",
                quoted(HingeKind::NAMES)
            ),
        )
    })
}

fn actuator(s: &Sections, a: &RawActuator) -> Res<Actuator> {
    let path = |key: &str| [k("actuator"), k(key)];
    Ok(Actuator {
        nominal_stroke: s.positive(
            &path("nominal_stroke"),
            &a.nominal_stroke,
            Dimension::Length,
        )?,
        preload: s.non_negative(&path("preload"), &a.preload, Dimension::Force)?,
        stiffness: match &a.stiffness {
            Some(q) => Some(s.positive(&path("stiffness"), q, Dimension::Stiffness)?),
            None => None,
        },
    })
}

fn dynamics(s: &Sections, d: &RawDynamics) -> Res<DynamicsSettings> {
    let path = |key: &str| [k("dynamics"), k(key)];
    let mass = |key: &str, q: &Quantity| s.non_negative(&path(key), q, Dimension::Mass);
    let zeta = s.finite(&path("damping_ratio"), d.damping_ratio)?;
    // the settling time is that of an oscillator: it needs some damping, and above
    // critical damping the +-2 % band is reached without oscillation, which is fine
    if !(zeta > 0.0 && zeta <= 10.0) {
        return Err(s.err(
            &path("damping_ratio"),
            format!("must lie in (0, 10], got {zeta}"),
        ));
    }
    Ok(DynamicsSettings::new(
        mass("payload_mass", &d.payload_mass)?,
        mass("input_link_mass", &d.input_link_mass)?,
        mass("output_link_mass", &d.output_link_mass)?,
        s.non_negative(
            &path("link_thickness"),
            &d.link_thickness,
            Dimension::Length,
        )?,
        zeta,
    ))
}
