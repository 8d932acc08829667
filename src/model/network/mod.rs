//! Planar compliant mechanisms described as networks of rigid bodies and flexures (issue
//! 25): the structural analysis ([`structure`]) of bodies joined through the hinge
//! library's compliances, and the natural modes of their masses on it ([`modes`]), over
//! [`crate::model::scalar::Scalar`] for exact gradients; the problem file's description
//! ([`file`]) and the model of its outputs ([`model`]); its part and the finite-element
//! check through its ports ([`part`]), for a file with a `[part]` section.

mod assemble;
mod checks;
mod depiction;
pub mod description;
pub mod file;
mod inertia;
pub mod model;
pub mod modes;
mod on_axis;
pub mod part;
pub mod ports;
mod raw;
mod scaling;
pub mod structure;
mod supports;

use super::entry::ModelEntry;

/// How a problem file selects a network (`model = "network"`).
pub const ENTRY: ModelEntry = ModelEntry {
    name: "network",
    sections: file::SECTIONS,
    build: assemble::build,
    schema: file::schema,
    template: include_str!("../templates/network.toml"),
    hinge_layout: None,
    optional_outputs: Some("\n[analysis]\ndeflection = \"large\"\n"),
};
