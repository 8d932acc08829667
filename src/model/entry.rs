//! How a problem file selects and configures a model: the entry each model gives the
//! registry ([`super::registry::MODELS`]).

use super::hinge::HingeKind;
use super::{Mechanism, ParameterInfo};
use crate::vocab::sections::Sections;
use crate::vocab::ProblemError;

/// How a problem file selects and configures a model.
#[derive(Clone, Copy)]
pub struct ModelEntry {
    /// The value of the file's `model` key.
    pub name: &'static str,
    /// The top-level sections of the file the model reads (`[material]`, `[hinge]`, ...);
    /// any other section is refused before the model is built.
    pub sections: &'static [&'static str],
    /// Reads and validates the model's sections, and builds the model.
    pub build: fn(&mut Sections) -> Result<Mechanism, ProblemError>,
    /// The JSON Schema of each of its sections, and whether the section is required.
    pub schema: fn(&mut schemars::SchemaGenerator) -> Vec<SectionSchema>,
    /// Its part of the file `flexopt init` writes: its sections, commented, then a ready
    /// set of variables, objective and constraints.
    pub template: &'static str,
    /// A model whose `[hinge]` section sets the kind of its hinges: its parameters when
    /// every hinge is of the given kind, each with the index of the kind's dimension it is
    /// (none for the other parameters), for `flexopt init --hinge`.
    pub hinge_layout: Option<HingeLayout>,
    /// A section that, added to the template, makes the model list the outputs it lists
    /// only when asked (a network's at the working stroke): the JSON Schema accepts those
    /// names as well as the template's own.
    pub optional_outputs: Option<&'static str>,
}

/// A model's parameters when every hinge is of the given kind, each with the index of the
/// kind's dimension it is (none for the other parameters).
pub type HingeLayout = fn(HingeKind) -> Vec<(ParameterInfo, Option<usize>)>;

/// One section of a model's part of a problem file, for the JSON Schema.
pub struct SectionSchema {
    pub name: &'static str,
    pub schema: schemars::Schema,
    pub required: bool,
    /// Rules between this section and the rest of the file (a table another section may
    /// give instead, a value a constraint needs from it), each a JSON Schema of the whole
    /// file that applies when the model is chosen.
    pub rules: Vec<serde_json::Value>,
}

impl SectionSchema {
    /// A section with no rules between it and the rest of the file.
    pub fn new(name: &'static str, schema: schemars::Schema, required: bool) -> Self {
        SectionSchema {
            name,
            schema,
            required,
            rules: Vec::new(),
        }
    }
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
