//! What a new user starts from: the problem file `flexopt init` writes (the JSON Schema
//! `flexopt schema` prints is [`super::json_schema`]).

use crate::model::registry::ModelEntry;

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
