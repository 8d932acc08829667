//! The bridge's sections of a problem file: `[material]`, `[hinge]`, `[actuator]` and the
//! optional `[dynamics]` and `[part]`, read and validated into a [`Bridge`].

use serde::Deserialize;
use serde_json::json;

use super::dynamics::DynamicsSettings;
use super::part::PartSettings;
use super::{Bridge, BridgeSettings};
use crate::model::actuator::{Actuator, RawActuator};
use crate::model::entry::SectionSchema;
use crate::model::hinge::HingeKind;
use crate::model::material::{Material, RawMaterial};
use crate::model::Mechanism;
use crate::vocab::error::Segment;
use crate::vocab::reader::{k, quoted, Res};
use crate::vocab::schema::{Measure, Measured, NonNegativeLength, NonNegativeMass, PositiveLength};
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
    #[schemars(extend("enum" = HingeKind::NAMES))]
    kind: Option<String>,
    width: Measured<PositiveLength>,
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
    #[schemars(extend("enum" = HingeKind::NAMES))]
    kind: String,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawDynamics {
    payload_mass: Measured<NonNegativeMass>,
    /// Default: the input block's, from `[part]`'s sizes, the plate and the density.
    input_link_mass: Option<Measured<NonNegativeMass>>,
    /// Default: the output block's, likewise.
    output_link_mass: Option<Measured<NonNegativeMass>>,
    /// Moved to `[part]`: read only to say so, and no key of the schema.
    #[schemars(skip)]
    link_thickness: Option<Quantity>,
    #[schemars(extend("exclusiveMinimum" = DAMPING_RATIO.0, "maximum" = DAMPING_RATIO.1))]
    damping_ratio: Number,
}

/// `damping_ratio` lies in (this, that]: some damping, for a settling time to exist; above
/// critical damping the +-2 % band is reached without oscillation, which is fine.
const DAMPING_RATIO: (f64, f64) = (0.0, 10.0);

#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawPart {
    link_thickness: Option<Measured<PositiveLength>>,
    fillet_radius: Option<Measured<NonNegativeLength>>,
    input_block_width: Option<Measured<PositiveLength>>,
    input_block_height: Option<Measured<PositiveLength>>,
    output_block_width: Option<Measured<PositiveLength>>,
    output_block_height: Option<Measured<PositiveLength>>,
    min_slot: Option<Measured<NonNegativeLength>>,
    /// Whether the study keeps to the part's rules (default true); false checks the part
    /// only after the study.
    enforce: Option<bool>,
}

/// The JSON Schema of each of the bridge's sections.
pub fn schema(g: &mut schemars::SchemaGenerator) -> Vec<SectionSchema> {
    let one = SectionSchema::new;
    // each hinge's kind once: from [hinge.b] or [hinges.b], or else from hinge.kind
    let hinge_rules = ["b", "d"]
        .iter()
        .flat_map(|which| {
            let in_table = |table: &str| {
                json!({"properties": {table: {"required": [which]}}, "required": [table]})
            };
            [
                json!({"not": {"allOf": [in_table("hinge"), in_table("hinges")]}}),
                json!({
                    "if": {"properties": {"hinge": {"not": {"required": ["kind"]}}},
                           "required": ["hinge"]},
                    "then": {"anyOf": [in_table("hinge"), in_table("hinges")]},
                }),
            ]
        })
        .collect();
    vec![
        SectionSchema {
            rules: crate::model::material::strength_rules("material"),
            ..one("material", g.subschema_for::<RawMaterial>(), true)
        },
        SectionSchema {
            rules: hinge_rules,
            ..one("hinge", g.subschema_for::<RawHinge>(), true)
        },
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
    let size = |key: &str, q: &Option<Measured<PositiveLength>>| -> Res<Option<f64>> {
        q.as_ref()
            .map(|q| s.measured(&[k("actuator"), k(key)], q))
            .transpose()
    };
    let actuator_size = [size("length", &a.length)?, size("height", &a.height)?];
    let part = part_settings(s, &p, actuator_size)?;
    let width = s.measured(&[k("hinge"), k("width")], &h.width)?;
    let blocks = part.block_masses(width, material.density);
    let actuator = Actuator::read(s, &a)?;
    let stack_mass = actuator.mass.unwrap_or(0.0);
    let settings = BridgeSettings {
        hinge_b,
        hinge_d,
        width,
        material,
        actuator,
        dynamics: d
            .as_ref()
            .map(|d| dynamics(s, d, part.link_thickness, blocks))
            .transpose()?
            .map(|d| d.with_stack_mass(stack_mass)),
        part,
    };
    let bridge = Bridge::new(settings);
    Ok(Mechanism::complete(bridge.clone()).with_modulus_scaling(std::sync::Arc::new(bridge)))
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

/// `[part]`, each key with its default ([`PartSettings::default`]).
fn part_settings(
    s: &Sections,
    p: &RawPart,
    [actuator_length, actuator_height]: [Option<f64>; 2],
) -> Res<PartSettings> {
    let d = PartSettings::default();
    fn length<M: Measure>(s: &Sections, key: &str, q: &Option<Measured<M>>, or: f64) -> Res<f64> {
        s.measured_or(&[k("part"), k(key)], q, or)
    }
    Ok(PartSettings {
        link_thickness: length(s, "link_thickness", &p.link_thickness, d.link_thickness)?,
        fillet_radius: length(s, "fillet_radius", &p.fillet_radius, d.fillet_radius)?,
        input_block_width: length(
            s,
            "input_block_width",
            &p.input_block_width,
            d.input_block_width,
        )?,
        input_block_height: length(
            s,
            "input_block_height",
            &p.input_block_height,
            d.input_block_height,
        )?,
        output_block_width: length(
            s,
            "output_block_width",
            &p.output_block_width,
            d.output_block_width,
        )?,
        output_block_height: length(
            s,
            "output_block_height",
            &p.output_block_height,
            d.output_block_height,
        )?,
        min_slot: length(s, "min_slot", &p.min_slot, d.min_slot)?,
        actuator_length,
        actuator_height,
        enforce: p.enforce.unwrap_or(d.enforce),
    })
}

/// `[dynamics]`; `blocks` the input and output blocks' masses of the part, which a link's
/// mass left out takes (NaN without a density, then refused).
fn dynamics(
    s: &Sections,
    d: &RawDynamics,
    link_thickness: f64,
    blocks: [f64; 2],
) -> Res<DynamicsSettings> {
    let path = |key: &str| [k("dynamics"), k(key)];
    if d.link_thickness.is_some() {
        return Err(s.err(
            &path("link_thickness"),
            "the middle links' thickness is a size of the part: give it as \
             `[part] link_thickness` (one key for the dynamics and the part)"
                .to_string(),
        ));
    }
    let mass = |key: &str, q: &Measured<NonNegativeMass>| s.measured(&path(key), q);
    let block = |key: &str, q: &Option<Measured<NonNegativeMass>>, or: f64| match q {
        Some(q) => mass(key, q),
        None if or.is_finite() => Ok(or),
        None => Err(s.err(
            &path(key),
            "missing: the part's block gives it from the material's density, which \
             [material] does not give; give the density or this mass"
                .to_string(),
        )),
    };
    let zeta = s.finite(&path("damping_ratio"), d.damping_ratio)?;
    let (above, most) = DAMPING_RATIO;
    if !(zeta > above && zeta <= most) {
        return Err(s.err(
            &path("damping_ratio"),
            format!("must lie in ({above}, {most}], got {zeta}"),
        ));
    }
    Ok(DynamicsSettings::new(
        mass("payload_mass", &d.payload_mass)?,
        block("input_link_mass", &d.input_link_mass, blocks[0])?,
        block("output_link_mass", &d.output_link_mass, blocks[1])?,
        link_thickness,
        zeta,
    ))
}
