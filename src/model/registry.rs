//! The models a problem file can name. Adding a model is one file or folder under
//! `src/model/` that implements [`super::Model`] and gives a [`ModelEntry`], plus its line in
//! [`MODELS`].

use std::sync::Arc;

use super::Model;
use crate::problem::sections::Sections;
use crate::problem::ProblemError;

/// How a problem file selects and configures a model.
#[derive(Clone, Copy)]
pub struct ModelEntry {
    /// The value of the file's `model` key.
    pub name: &'static str,
    /// The top-level sections of the file the model reads (`[material]`, `[hinge]`, ...);
    /// any other section is refused before the model is built.
    pub sections: &'static [&'static str],
    /// Reads and validates the model's sections, and builds the model.
    pub build: fn(&mut Sections) -> Result<Arc<dyn Model>, ProblemError>,
    /// The JSON Schema of each of its sections, and whether the section is required.
    pub schema: fn(&mut schemars::SchemaGenerator) -> Vec<SectionSchema>,
    /// Its part of the file `flexopt init` writes: its sections, commented, then a ready
    /// set of variables, objective and constraints.
    pub template: &'static str,
}

/// One section of a model's part of a problem file, for the JSON Schema.
pub struct SectionSchema {
    pub name: &'static str,
    pub schema: schemars::Schema,
    pub required: bool,
}

/// No sections: a model whose parameters are all variables.
pub fn no_sections(_: &mut schemars::SchemaGenerator) -> Vec<SectionSchema> {
    Vec::new()
}

impl std::fmt::Debug for ModelEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ModelEntry")
            .field("name", &self.name)
            .field("sections", &self.sections)
            .finish()
    }
}

/// Every model a problem file can select.
pub const MODELS: &[ModelEntry] = &[super::bridge::ENTRY, super::prr3::ENTRY, super::pss3::ENTRY];

/// The entry named `name` among `models`.
pub fn find<'m>(models: &'m [ModelEntry], name: &str) -> Option<&'m ModelEntry> {
    models.iter().find(|m| m.name == name)
}
