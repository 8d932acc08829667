//! The JSON Schema (draft 2020-12) of problem files that `flexopt schema` prints for editors.
//!
//! It is made from what the reader reads with: the raw types it deserializes (their enums,
//! ranges and exclusive keys stated beside their fields), the unit tables, and, for each
//! model of the registry, the model its `init` template builds (its outputs and their
//! units, its angle limit). What it cannot say is listed, with why, by the test that feeds
//! it every file the reader refuses (`tests/problem_files/rejected.rs`).

use std::path::Path;

use schemars::generate::SchemaSettings;
use schemars::SchemaGenerator;
use serde_json::{json, Map, Value};

use super::init::template;
use super::refine::RawRefine;
use super::schema::{RawConstraint, RawObjective, RawSearch, RawVariable, RawZones};
use super::validate::{positive_only, NAME_PATTERN};
use super::Problem;
use crate::model::material::STRENGTH_FRACTIONS;
use crate::model::registry::{ModelEntry, MODELS};
use crate::vocab::units;
use crate::vocab::Dimension;

/// `[tolerances]`: its two keys of its own, and a variable's tolerance under any other key.
fn tolerances_schema(g: &mut schemars::SchemaGenerator) -> Value {
    json!({"type": "object",
        "properties": {
            "coverage": g.subschema_for::<super::tolerances::RawCoverage>(),
            "yield_of": {"type": "array", "items": {"type": "string"}, "minItems": 1},
        },
        "additionalProperties": g.subschema_for::<super::tolerances::RawTolerance>()})
}

/// The JSON Schema of a problem file: the common keys, every model's sections, and what
/// each model requires and allows.
pub fn json_schema() -> Value {
    let mut g = SchemaSettings::draft2020_12().into_generator();
    let mut properties = Map::new();
    properties.insert(
        "name".into(),
        json!({"type": "string", "pattern": NAME_PATTERN,
               "description": "names the results folder: letters, digits, - _ . (not first)"}),
    );
    properties.insert("description".into(), json!({"type": "string"}));
    properties.insert(
        "model".into(),
        json!({"enum": MODELS.iter().map(|m| m.name).collect::<Vec<_>>()}),
    );
    let all_units: Vec<&str> = units::tables()
        .iter()
        .flat_map(|(d, _)| units::names(*d))
        .collect();
    properties.insert(
        "variables".into(),
        json!({"type": "array", "items": {"allOf": [
            g.subschema_for::<RawVariable>(),
            {"properties": {"unit": {"enum": all_units}}},
            {"$ref": "#/$defs/SizeInItsUnit"},
            {"if": {"properties": {"unit": {"enum": positive_units()}}, "required": ["unit"]},
             "then": {"patternProperties": {VALUE_KEYS: {"exclusiveMinimum": 0}}}},
        ]}}),
    );
    properties.insert(
        "objective".into(),
        g.subschema_for::<RawObjective>().to_value(),
    );
    properties.insert(
        "constraints".into(),
        json!({"type": "array", "items": {"allOf": [
            g.subschema_for::<RawConstraint>(),
            {"$ref": "#/$defs/SizeInItsUnit"},
        ]}}),
    );
    properties.insert("search".into(), g.subschema_for::<RawSearch>().to_value());
    properties.insert("zones".into(), g.subschema_for::<RawZones>().to_value());
    properties.insert("refine".into(), g.subschema_for::<RawRefine>().to_value());
    properties.insert("tolerances".into(), tolerances_schema(&mut g));
    let mut per_model = Vec::new();
    for m in MODELS {
        let sections = (m.schema)(&mut g);
        let required: Vec<&str> = sections
            .iter()
            .filter(|s| s.required)
            .map(|s| s.name)
            .collect();
        let mine: Vec<(&str, Value)> = sections
            .iter()
            .map(|s| (s.name, s.schema.clone().to_value()))
            .collect();
        let rules: Vec<Value> = sections.iter().flat_map(|s| s.rules.clone()).collect();
        per_model.push((m, required, mine, rules));
    }
    let all_sections: Vec<&str> = per_model
        .iter()
        .flat_map(|(_, _, mine, _)| mine.iter().map(|(name, _)| *name))
        .collect();
    // a section two models read (the bridge's `[part]` and a network's) has each model's
    // schema under that model; one model's alone stands at the top
    let shared = |name: &str| all_sections.iter().filter(|&&s| s == name).count() > 1;
    for (_, _, mine, _) in &per_model {
        for (name, schema) in mine {
            let at_top = if shared(name) {
                json!({"type": "object"})
            } else {
                schema.clone()
            };
            properties.insert(name.to_string(), at_top);
        }
    }
    let all_of: Vec<Value> = per_model
        .iter()
        .map(|(m, required, mine, rules)| {
            let names: Vec<&str> = mine.iter().map(|(name, _)| *name).collect();
            // the sections of other models are no keys of this one
            let mut then: Map<String, Value> = all_sections
                .iter()
                .filter(|s| !names.contains(s))
                .map(|s| (s.to_string(), Value::Bool(false)))
                .collect();
            then.extend(
                mine.iter()
                    .filter(|(name, _)| shared(name))
                    .map(|(name, schema)| (name.to_string(), schema.clone())),
            );
            then.extend(model_keys(m));
            let mut then = json!({"required": required, "properties": then});
            if !rules.is_empty() {
                then["allOf"] = json!(rules);
            }
            json!({
                "if": {"properties": {"model": {"const": m.name}}, "required": ["model"]},
                "then": then,
            })
        })
        .collect();
    let mut schema = json!({
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "flexopt problem file",
        "description": "A design problem for flexopt (TOML). Quantities with a dimension are \
                        strings with their unit: \"10 mm\", \"72 GPa\".",
        "type": "object",
        "properties": properties,
        "required": ["name", "model", "variables", "objective"],
        "additionalProperties": false,
        "allOf": all_of,
        "$defs": definitions(g),
    });
    schema["$defs"]["SizeInItsUnit"] = size_in_its_unit();
    without_null(&mut schema);
    schema
}

fn definitions(mut g: SchemaGenerator) -> Map<String, Value> {
    g.take_definitions(true)
}

/// The keys of a variable or constraint that hold a value in its `unit`.
const VALUE_KEYS: &str = "^(lower|upper|value)$";

/// The units of the dimensions whose variables must be above zero.
fn positive_units() -> Vec<&'static str> {
    units::tables()
        .iter()
        .filter(|(d, _)| positive_only(*d))
        .flat_map(|(d, _)| units::names(*d))
        .collect()
}

/// For each unit of each dimension, the values a variable or constraint written in it may
/// hold: zero, or a size [`units::physical`] allows, either sign.
fn size_in_its_unit() -> Value {
    let mut rules = Vec::new();
    for &(dimension, table) in units::tables() {
        let (lo, hi) = units::physical_range(dimension);
        for &(name, factor) in table {
            let (lo, hi) = (least_reaching(lo, factor), most_within(hi, factor));
            rules.push(json!({
                "if": {"properties": {"unit": {"const": name}}, "required": ["unit"]},
                "then": {"patternProperties": {VALUE_KEYS: {"anyOf": [
                    {"const": 0},
                    {"minimum": lo, "maximum": hi},
                    {"minimum": -hi, "maximum": -lo},
                ]}}},
            }));
        }
    }
    json!({"allOf": rules})
}

/// What a model's choice says of the common keys: the outputs the objective and the
/// constraints may name, each constraint's units and at most one constraint per output,
/// and the size of its angles, read from the model its template builds.
fn model_keys(entry: &ModelEntry) -> Map<String, Value> {
    let mut keys = Map::new();
    let file = template(entry, "template");
    let Ok(problem) = Problem::parse(Path::new("template.toml"), &file) else {
        return keys;
    };
    let model = problem.model();
    let mut outputs = model.outputs().to_vec();
    // the outputs the model lists only when asked, each once
    if let Some(section) = entry.optional_outputs {
        let asked = Problem::parse(Path::new("template.toml"), &(file + section));
        if let Ok(asked) = asked {
            for o in asked.model().outputs() {
                if !outputs.iter().any(|p| p.name == o.name) {
                    outputs.push(o.clone());
                }
            }
        }
    }
    let names: Vec<&str> = outputs.iter().map(|o| o.name.as_ref()).collect();
    keys.insert(
        "objective".into(),
        json!({"properties": {"maximize": {"enum": names}, "minimize": {"enum": names}}}),
    );
    let units_of = |dimension: Dimension| {
        let mut u = units::names(dimension);
        if dimension == Dimension::Stress && model.material().is_some() {
            u.extend(STRENGTH_FRACTIONS);
        }
        u
    };
    // the outputs of each dimension take its units
    let unit_by_output: Vec<Value> = units::tables()
        .iter()
        .filter_map(|&(dimension, _)| {
            let of_it: Vec<&str> = outputs
                .iter()
                .filter(|o| o.dimension == dimension)
                .map(|o| o.name.as_ref())
                .collect();
            (!of_it.is_empty()).then(|| {
                json!({
                    "if": {"properties": {"output": {"enum": of_it}}, "required": ["output"]},
                    "then": {"properties": {"unit": {"enum": units_of(dimension)}}},
                })
            })
        })
        .collect();
    let once_each: Vec<Value> = names
        .iter()
        .map(|name| {
            json!({"not": {"contains": {"properties": {"output": {"const": name}},
                                        "required": ["output"]},
                           "minContains": 2}})
        })
        .collect();
    keys.insert(
        "constraints".into(),
        json!({
            "items": {"properties": {"output": {"enum": names}}, "allOf": unit_by_output},
            "allOf": once_each,
        }),
    );
    if let Some(limit) = model.angle_limit() {
        let by_unit: Vec<Value> = units::tables()
            .iter()
            .filter(|(d, _)| *d == Dimension::Angle)
            .flat_map(|(_, table)| table.iter())
            .map(|&(name, factor)| {
                let limit = least_reaching(limit, factor);
                json!({
                    "if": {"properties": {"unit": {"const": name}}, "required": ["unit"]},
                    "then": {"patternProperties": {VALUE_KEYS: {
                        "exclusiveMinimum": -limit, "exclusiveMaximum": limit,
                    }}},
                })
            })
            .collect();
        keys.insert("variables".into(), json!({"items": {"allOf": by_unit}}));
    }
    keys
}

/// The least value written in a unit of `factor` whose SI value (`x * factor`, as the reader
/// computes it) reaches `si`: `si / factor` may lie an ulp to either side.
fn least_reaching(si: f64, factor: f64) -> f64 {
    let mut x = si / factor;
    while x * factor < si {
        x = x.next_up();
    }
    while x.next_down() * factor >= si {
        x = x.next_down();
    }
    x
}

/// The greatest value written in a unit of `factor` whose SI value stays within `si`.
fn most_within(si: f64, factor: f64) -> f64 {
    let mut x = si / factor;
    while x * factor > si {
        x = x.next_down();
    }
    while x.next_up() * factor <= si {
        x = x.next_up();
    }
    x
}

/// The schema without `null`: TOML has none, so an optional key is one left out, never one
/// given as null (schemars lets an `Option` be null).
fn without_null(v: &mut Value) {
    match v {
        Value::Object(map) => {
            if let Some(Value::Array(types)) = map.get_mut("type") {
                types.retain(|t| t != "null");
                if let [only] = types.as_slice() {
                    let only = only.clone();
                    map.insert("type".into(), only);
                }
            }
            for key in ["anyOf", "oneOf"] {
                if let Some(Value::Array(options)) = map.get_mut(key) {
                    options.retain(|o| o.get("type") != Some(&json!("null")));
                }
            }
            map.values_mut().for_each(without_null);
        }
        Value::Array(items) => items.iter_mut().for_each(without_null),
        _ => {}
    }
}
