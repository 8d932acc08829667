//! The bridge's sections of a problem file: `[material]`, `[hinge]`, `[actuator]` and the
//! optional `[dynamics]` and `[part]`, read and validated into a [`Bridge`].

use serde::Deserialize;

use super::dynamics::DynamicsSettings;
use super::part::PartSettings;
use super::{Actuator, Bridge, BridgeSettings};
use crate::model::entry::SectionSchema;
use crate::model::hinge::HingeKind;
use crate::model::material::{Material, RawMaterial};
use crate::model::{Dimension, Mechanism};
use crate::vocab::error::Segment;
use crate::vocab::reader::{k, quoted, Res};
use crate::vocab::sections::Sections;
use crate::vocab::values::{Number, Quantity};

/// The sections the bridge reads.
pub const SECTIONS: &[&str] = &[
    "material", "hinge", "hinges", "actuator", "dynamics", "part",
];

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawHinge {
    /// The kind of both hinges, unless `[hinge.b]` or `[hinge.d]` names another.
    kind: Option<String>,
    width: Quantity,
    b: Option<RawOneHinge>,
    d: Option<RawOneHinge>,
}

/// `[hinges.b]` and `[hinges.d]`: the same as `[hinge.b]` and `[hinge.d]`, for files that
/// keep the per-hinge tables apart from `[hinge]`.
#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawHinges {
    b: Option<RawOneHinge>,
    d: Option<RawOneHinge>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawOneHinge {
    kind: String,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawActuator {
    nominal_stroke: Quantity,
    preload: Quantity,
    stiffness: Option<Quantity>,
    length: Option<Quantity>,
    height: Option<Quantity>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawDynamics {
    payload_mass: Quantity,
    input_link_mass: Quantity,
    output_link_mass: Quantity,
    /// Moved to `[part]`: read only to say so.
    link_thickness: Option<Quantity>,
    damping_ratio: Number,
}

#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawPart {
    link_thickness: Option<Quantity>,
    fillet_radius: Option<Quantity>,
    input_block_width: Option<Quantity>,
    input_block_height: Option<Quantity>,
    output_block_width: Option<Quantity>,
    output_block_height: Option<Quantity>,
    min_slot: Option<Quantity>,
}

/// The JSON Schema of each of the bridge's sections.
pub fn schema(g: &mut schemars::SchemaGenerator) -> Vec<SectionSchema> {
    let one = |name, schema, required| SectionSchema {
        name,
        schema,
        required,
    };
    vec![
        one("material", g.subschema_for::<RawMaterial>(), true),
        one("hinge", g.subschema_for::<RawHinge>(), true),
        one("hinges", g.subschema_for::<RawHinges>(), false),
        one("actuator", g.subschema_for::<RawActuator>(), true),
        one("dynamics", g.subschema_for::<RawDynamics>(), false),
        one("part", g.subschema_for::<RawPart>(), false),
    ]
}

/// Reads the bridge's sections and builds the model.
pub fn build(s: &mut Sections) -> Res<Mechanism> {
    let m: RawMaterial = s.required("material")?;
    let h: RawHinge = s.required("hinge")?;
    let hs: RawHinges = s.optional("hinges")?.unwrap_or_default();
    let a: RawActuator = s.required("actuator")?;
    let d: Option<RawDynamics> = s.optional("dynamics")?;
    let p: RawPart = s.optional("part")?.unwrap_or_default();
    let material = Material::from_section(s, &m)?;
    let kind = |which: &str,
                one: &Option<RawOneHinge>,
                other: &Option<RawOneHinge>|
     -> Res<HingeKind> {
        match (one, other) {
            (Some(_), Some(_)) => {
                return Err(s.err(
                    &[k("hinges"), k(which)],
                    format!(
                        "hinge {which} is given twice: keep [hinge.{which}] or [hinges.{which}]"
                    ),
                ))
            }
            (None, Some(o)) => return hinge_kind(s, &[k("hinges"), k(which), k("kind")], &o.kind),
            _ => {}
        }
        match (one, &h.kind) {
            (Some(o), _) => hinge_kind(s, &[k("hinge"), k(which), k("kind")], &o.kind),
            (None, Some(both)) => hinge_kind(s, &[k("hinge"), k("kind")], both),
            (None, None) => Err(s.err(
                &[k("hinge"), k("kind")],
                format!(
                    "missing: give the kind of both hinges here, or hinge {which}'s in \
                     [hinge.{which}] (one of {})",
                    quoted(HingeKind::NAMES)
                ),
            )),
        }
    };
    let (hinge_b, hinge_d) = (kind("b", &h.b, &hs.b)?, kind("d", &h.d, &hs.d)?);
    let size = |key: &str, q: &Option<Quantity>| -> Res<Option<f64>> {
        q.as_ref()
            .map(|q| s.positive(&[k("actuator"), k(key)], q, Dimension::Length))
            .transpose()
    };
    let actuator_size = [size("length", &a.length)?, size("height", &a.height)?];
    let part = part_settings(s, &p, actuator_size)?;
    let settings = BridgeSettings {
        hinge_b,
        hinge_d,
        width: s.positive(&[k("hinge"), k("width")], &h.width, Dimension::Length)?,
        material,
        actuator: actuator(s, &a)?,
        dynamics: d
            .as_ref()
            .map(|d| dynamics(s, d, part.link_thickness))
            .transpose()?,
        part,
    };
    Ok(Mechanism::complete(Bridge::new(settings)))
}

fn hinge_kind(s: &Sections, path: &[Segment], kind: &str) -> Res<HingeKind> {
    HingeKind::from_name(kind).ok_or_else(|| {
        s.err(
            path,
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

/// `[part]`, each key with its default ([`PartSettings::default`]).
fn part_settings(
    s: &Sections,
    p: &RawPart,
    [actuator_length, actuator_height]: [Option<f64>; 2],
) -> Res<PartSettings> {
    let d = PartSettings::default();
    let length = |key: &str, q: &Option<Quantity>, default: f64, zero: bool| -> Res<f64> {
        let path = [k("part"), k(key)];
        match q {
            None => Ok(default),
            Some(q) if zero => s.non_negative(&path, q, Dimension::Length),
            Some(q) => s.positive(&path, q, Dimension::Length),
        }
    };
    Ok(PartSettings {
        link_thickness: length("link_thickness", &p.link_thickness, d.link_thickness, false)?,
        fillet_radius: length("fillet_radius", &p.fillet_radius, d.fillet_radius, true)?,
        input_block_width: length(
            "input_block_width",
            &p.input_block_width,
            d.input_block_width,
            false,
        )?,
        input_block_height: length(
            "input_block_height",
            &p.input_block_height,
            d.input_block_height,
            false,
        )?,
        output_block_width: length(
            "output_block_width",
            &p.output_block_width,
            d.output_block_width,
            false,
        )?,
        output_block_height: length(
            "output_block_height",
            &p.output_block_height,
            d.output_block_height,
            false,
        )?,
        min_slot: length("min_slot", &p.min_slot, d.min_slot, true)?,
        actuator_length,
        actuator_height,
    })
}

fn dynamics(s: &Sections, d: &RawDynamics, link_thickness: f64) -> Res<DynamicsSettings> {
    let path = |key: &str| [k("dynamics"), k(key)];
    if d.link_thickness.is_some() {
        return Err(s.err(
            &path("link_thickness"),
            "the middle links' thickness is a size of the part: give it as \
             `[part] link_thickness` (one key for the dynamics and the part)"
                .to_string(),
        ));
    }
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
        link_thickness,
        zeta,
    ))
}
