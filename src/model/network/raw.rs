//! The network's sections as a problem file writes them (`[network]` and its tables, the
//! schema of every section the network reads), which [`super::file`] reads and checks into
//! a [`super::description::Description`].

use indexmap::IndexMap;
use serde::Deserialize;

use super::checks::Two;
use super::part::RawNetworkPart;
use super::supports::RawNetworkSupport;
use crate::model::actuator::RawActuator;
use crate::model::entry::SectionSchema;
use crate::model::hinge::HingeKind;
use crate::model::material::RawMaterial;
use crate::vocab::schema::{Measured, NonNegativeMass, PositiveLength};

/// The sections the network reads.
pub const SECTIONS: &[&str] = &["material", "network", "actuator", "part", "analysis"];

/// How the network is solved: `deflection = "small"` (the default) the linear model alone;
/// `"large"` also the outputs at the working stroke (`nl_...`), each flexure a chain of
/// `elements` corotational beams, the path from the unloaded part in `steps` load steps,
/// the critical load factor (`nl_critical`) looked for up to `critical_up_to` times the
/// working stroke.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(super) struct RawAnalysis {
    pub(super) deflection: Option<Deflection>,
    #[schemars(range(min = 1, max = 64))]
    pub(super) elements: Option<usize>,
    #[schemars(range(min = 1, max = 200))]
    pub(super) steps: Option<usize>,
    /// The multiple of the working stroke up to which `nl_critical` looks for a critical
    /// point: above 1, at most 100 (default 4).
    #[schemars(range(min = 1, max = 100))]
    pub(super) critical_up_to: Option<f64>,
}

/// Small (linear) or large deflection.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub(super) enum Deflection {
    Small,
    Large,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(super) struct RawNetwork {
    pub(super) width: Measured<PositiveLength>,
    pub(super) unit: Option<String>,
    /// Each parameter as `[name, dimension]`: a list, as a table's keys come in no order.
    #[schemars(with = "Vec<[String; 2]>")]
    pub(super) parameters: Vec<Two>,
    pub(super) mirror: Option<Vec<String>>,
    #[serde(default)]
    pub(super) bodies: Vec<RawNetworkBody>,
    #[serde(default)]
    pub(super) hinges: Vec<RawNetworkHinge>,
    #[serde(default)]
    pub(super) beams: Vec<RawNetworkBeam>,
    pub(super) input: RawNetworkPort,
    pub(super) outputs: Vec<RawNetworkPort>,
    #[serde(default)]
    pub(super) measures: Vec<RawNetworkMeasure>,
    #[serde(default)]
    pub(super) supports: Vec<RawNetworkSupport>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(super) struct RawNetworkBody {
    pub(super) name: String,
    #[schemars(with = "Option<Vec<[String; 2]>>")]
    pub(super) outline: Option<Vec<Two>>,
    pub(super) link: Option<RawNetworkLink>,
    pub(super) on_axis: Option<Vec<String>>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(super) struct RawNetworkLink {
    #[schemars(with = "[String; 2]")]
    pub(super) from: Two,
    #[schemars(with = "[String; 2]")]
    pub(super) to: Two,
    pub(super) width: String,
}

/// A hinge: its named keys, and the kind's dimensions among the rest (not denied: they are
/// checked against the kind, with a message that lists the kind's own).
#[derive(Debug, Deserialize, schemars::JsonSchema)]
pub(super) struct RawNetworkHinge {
    pub(super) name: String,
    #[schemars(extend("enum" = HingeKind::NAMES))]
    pub(super) kind: String,
    pub(super) from: String,
    pub(super) to: String,
    #[schemars(with = "[String; 2]")]
    pub(super) start: Two,
    pub(super) angle: String,
    #[serde(flatten)]
    #[schemars(with = "std::collections::BTreeMap<String, String>")]
    pub(super) dimensions: IndexMap<String, String>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(super) struct RawNetworkBeam {
    pub(super) name: String,
    pub(super) from: String,
    pub(super) to: String,
    #[schemars(with = "[String; 2]")]
    pub(super) start: Two,
    #[schemars(with = "[String; 2]")]
    pub(super) end: Two,
    pub(super) thickness: String,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(super) struct RawNetworkPort {
    /// The output's name (outputs only).
    pub(super) name: Option<String>,
    pub(super) body: String,
    #[schemars(with = "[String; 2]")]
    pub(super) at: Two,
    #[schemars(with = "[String; 2]")]
    pub(super) direction: Two,
    pub(super) across: Option<String>,
    /// The mass the output carries (outputs only), for the natural frequencies.
    pub(super) payload: Option<Measured<NonNegativeMass>>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(super) struct RawNetworkMeasure {
    pub(super) name: String,
    pub(super) dimension: String,
    pub(super) value: String,
}

/// The JSON Schema of each of the network's sections.
pub fn schema(g: &mut schemars::SchemaGenerator) -> Vec<SectionSchema> {
    let one = SectionSchema::new;
    vec![
        SectionSchema {
            rules: crate::model::material::strength_rules("material"),
            ..one("material", g.subschema_for::<RawMaterial>(), true)
        },
        one("network", g.subschema_for::<RawNetwork>(), true),
        one("actuator", g.subschema_for::<RawActuator>(), true),
        one("part", g.subschema_for::<RawNetworkPart>(), false),
        one("analysis", g.subschema_for::<RawAnalysis>(), false),
    ]
}
