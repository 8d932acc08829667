//! What a new user starts from: the problem file `flexopt init` writes, and the JSON Schema
//! of problem files that `flexopt schema` prints for editors.

use schemars::generate::SchemaSettings;
use serde_json::{json, Map, Value};

use super::refine::RawRefine;
use super::schema::{RawConstraint, RawObjective, RawSearch, RawVariable, RawZones};
use crate::model::registry::{ModelEntry, MODELS};

/// The problem file `flexopt init` writes for the model `model`, named `name`: every key,
/// the optional ones commented with their defaults, ready to run.
pub fn template(model: &ModelEntry, name: &str) -> String {
    let key = |k: String, note: &str| format!("{k:<28} # {note}\n");
    format!(
        "# A flexopt problem file, written by `flexopt init --model {m}`. Run it with\n\
         #   flexopt run {name}.toml\n\
         # Every key is explained beside it; `flexopt schema` prints the JSON Schema of the\n\
         # format, for editors that complete and check keys.\n\n{}{}{}\n{}{}",
        key(
            format!("name = \"{name}\""),
            "names the results folder: letters, digits, - _ ."
        ),
        key("description = \"\"".into(), "free text for the reports"),
        key(
            format!("model = \"{}\"", model.name),
            "the mechanism's model"
        ),
        model.template,
        include_str!("template.toml"),
        m = model.name,
    )
}

/// The name a problem file may have (`name = ...`) made from `stem`: the characters the
/// format allows kept, the rest turned into `_`.
pub fn name_from(stem: &str) -> String {
    let name: String = stem
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "-_.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    if name.is_empty() {
        "my_problem".into()
    } else {
        name
    }
}

/// The JSON Schema (draft 2020-12) of a problem file: the common keys, every model's
/// sections, and which sections each model requires.
pub fn json_schema() -> Value {
    let mut g = SchemaSettings::draft2020_12().into_generator();
    let mut properties = Map::new();
    properties.insert(
        "name".into(),
        json!({"type": "string", "pattern": "^[A-Za-z0-9_.-]+$",
               "description": "names the results folder"}),
    );
    properties.insert("description".into(), json!({"type": "string"}));
    properties.insert(
        "model".into(),
        json!({"enum": MODELS.iter().map(|m| m.name).collect::<Vec<_>>()}),
    );
    let mut sub = |name: &str, schema: schemars::Schema| {
        properties.insert(name.into(), schema.to_value());
    };
    sub(
        "variables",
        schemars::Schema::from(
            json!({"type": "array", "items": g.subschema_for::<RawVariable>().to_value()})
                .as_object()
                .cloned()
                .unwrap_or_default(),
        ),
    );
    sub("objective", g.subschema_for::<RawObjective>());
    sub(
        "constraints",
        schemars::Schema::from(
            json!({"type": "array", "items": g.subschema_for::<RawConstraint>().to_value()})
                .as_object()
                .cloned()
                .unwrap_or_default(),
        ),
    );
    sub("search", g.subschema_for::<RawSearch>());
    sub("zones", g.subschema_for::<RawZones>());
    sub("refine", g.subschema_for::<RawRefine>());
    let mut per_model = Vec::new();
    for m in MODELS {
        let sections = (m.schema)(&mut g);
        let required: Vec<&str> = sections
            .iter()
            .filter(|s| s.required)
            .map(|s| s.name)
            .collect();
        // the sections of other models are no keys of this one
        let mine: Vec<&str> = sections.iter().map(|s| s.name).collect();
        for s in sections {
            properties.insert(s.name.into(), s.schema.to_value());
        }
        per_model.push((m.name, required, mine));
    }
    let all_sections: Vec<String> = per_model
        .iter()
        .flat_map(|(_, _, mine)| mine.iter().map(|s| s.to_string()))
        .collect();
    let all_of: Vec<Value> = per_model
        .iter()
        .map(|(name, required, mine)| {
            let foreign: Map<String, Value> = all_sections
                .iter()
                .filter(|s| !mine.contains(&s.as_str()))
                .map(|s| (s.clone(), Value::Bool(false)))
                .collect();
            json!({
                "if": {"properties": {"model": {"const": name}}, "required": ["model"]},
                "then": {"required": required, "properties": foreign},
            })
        })
        .collect();
    json!({
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "flexopt problem file",
        "description": "A design problem for flexopt (TOML). Quantities with a dimension are \
                        strings with their unit: \"10 mm\", \"72 GPa\".",
        "type": "object",
        "properties": properties,
        "required": ["name", "model", "variables", "objective"],
        "additionalProperties": false,
        "allOf": all_of,
        "$defs": g.take_definitions(true),
    })
}
