//! The shape of `optimum.json` as the report reads it: each key it shows, of the type flexopt
//! writes, so that an edited file is refused by its key rather than shown as a value it is
//! not (a string `objective` read as no objective, and so as "no start ended feasible").

use std::collections::BTreeMap;

use serde::de::IgnoredAny;
use serde::Deserialize;

#[derive(Deserialize)]
#[allow(dead_code)] // read for their types only
struct Optimum {
    problem: String,
    model: String,
    problem_fnv1a64: String,
    design: BTreeMap<String, f64>,
    design_units: BTreeMap<String, String>,
    design_si: BTreeMap<String, f64>,
    outputs: BTreeMap<String, Option<f64>>,
    output_units: BTreeMap<String, String>,
    display_units: BTreeMap<String, String>,
    objective: Option<f64>,
    objective_output: String,
    sense: String,
    absolute: bool,
    constraints: Vec<Constraint>,
    feasible: bool,
    configuration: String,
    solver: String,
    seed: u64,
    starts: u64,
    start: u64,
    zone: Option<u64>,
    status: BTreeMap<String, IgnoredAny>,
    kkt_residual: Option<f64>,
    iterations: u64,
    converged: bool,
    ends: BTreeMap<String, u64>,
}

#[derive(Deserialize)]
#[allow(dead_code)] // read for their types only
struct Constraint {
    output: String,
    value: Option<f64>,
    lower: Option<f64>,
    upper: Option<f64>,
    unit: String,
    margin: Option<f64>,
    relative_margin: Option<f64>,
    satisfied: bool,
    active: bool,
    margin_in_sigma: Option<f64>,
}

/// Where `text` (`optimum.json`) is not of the shape flexopt writes: the key and what is wrong.
pub fn check_optimum(text: &str) -> Result<(), String> {
    let mut de = serde_json::Deserializer::from_str(text);
    serde_path_to_error::deserialize::<_, Optimum>(&mut de)
        .map(drop)
        .map_err(|e| match e.path().to_string().as_str() {
            "." => e.inner().to_string(),
            key => format!("key `{key}`: {}", e.inner()),
        })
}
