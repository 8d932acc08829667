//! The models a problem file can name. Adding a model is one file or folder under
//! `src/model/` that implements [`super::Model`] (and the capabilities it has) and gives an
//! [`super::entry::ModelEntry`], plus its line in [`MODELS`]; the command line's choices of
//! model come from this list.

pub use super::entry::{ModelEntry, SectionSchema};

/// Every model a problem file can select.
pub const MODELS: &[ModelEntry] = &[
    super::bridge::ENTRY,
    super::prr3::ENTRY,
    super::pss3::ENTRY,
    super::network::ENTRY,
];

/// The entry named `name` among `models`.
pub fn find<'m>(models: &'m [ModelEntry], name: &str) -> Option<&'m ModelEntry> {
    models.iter().find(|m| m.name == name)
}
