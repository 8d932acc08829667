//! What a new user starts from: the problem file `flexopt init` writes (the JSON Schema
//! `flexopt schema` prints is [`super::json_schema`]).

use crate::model::hinge::HingeKind;
use crate::model::material::Material;
use crate::model::registry::{ModelEntry, MODELS};

/// What `flexopt init` may choose beyond the model: the kind of every hinge and the
/// material preset; `None` keeps the model's template.
#[derive(Debug, Clone, Copy, Default)]
pub struct Choices<'a> {
    pub hinge: Option<HingeKind>,
    pub material: Option<&'a str>,
}

/// The problem file `flexopt init` writes for the model `model`, named `name`: every key,
/// the optional ones commented with their defaults, ready to run.
pub fn template(model: &ModelEntry, name: &str) -> String {
    header(model, name, "") + model.template + include_str!("template.toml")
}

/// [`template`] with the hinges of `choices.hinge` (their dimensions as the variables, each
/// within the kind's starting bounds, [`HingeKind::start_bounds`]) and the material preset
/// `choices.material`; an error names the option and what is wrong (a model without hinges
/// or without a material, an unknown preset).
pub fn template_with(model: &ModelEntry, name: &str, choices: Choices) -> Result<String, String> {
    let mut body = model.template.to_string();
    let mut flags = String::new();
    if let Some(preset) = choices.material {
        body = with_material(model, &body, preset)?;
        flags += &format!(" --material {preset}");
    }
    if let Some(kind) = choices.hinge {
        body = with_hinge(model, &body, kind)?;
        flags += &format!(" --hinge {}", kind.name());
    }
    Ok(header(model, name, &flags) + &body + include_str!("template.toml"))
}

/// The models that take `section` ([`ModelEntry::sections`]), for messages.
fn models_with(section: &str) -> String {
    MODELS
        .iter()
        .filter(|m| m.sections.contains(&section))
        .map(|m| m.name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// `body` with its `[material]` section's preset set to `preset`.
fn with_material(model: &ModelEntry, body: &str, preset: &str) -> Result<String, String> {
    if Material::preset(preset).is_none() {
        return Err(format!(
            "--material: unknown preset \"{preset}\"; the presets: {}",
            Material::PRESETS.join(", ")
        ));
    }
    let others: Vec<&str> = Material::PRESETS
        .iter()
        .copied()
        .filter(|&p| p != preset)
        .collect();
    let line = key(
        format!("preset = \"{preset}\""),
        &format!("or {};", others.join(", ")),
    );
    let mut body = replace_line(body, "[material]", "preset = ", &line).ok_or_else(|| {
        format!(
            "--material: the model \"{}\" has no [material] section; models with one: {}",
            model.name,
            models_with("material")
        )
    })?;
    // the values a designer would override, shown as the preset has them
    let m = Material::preset(preset).expect("a preset");
    let stress =
        |v: Option<f64>| v.map_or_else(String::new, |v| format!("{} MPa", short(v * 1e-6)));
    for (k, value) in [
        (
            "youngs_modulus",
            format!("{} GPa", short(m.youngs_modulus * 1e-9)),
        ),
        ("poisson_ratio", short(m.poisson_ratio)),
        ("yield_strength", stress(m.yield_strength)),
        ("ultimate_strength", stress(m.ultimate_strength)),
        ("density", format!("{} kg/m3", short(m.density))),
    ] {
        let prefix = format!("# {k} = ");
        let quoted = if k == "poisson_ratio" {
            value
        } else {
            format!("\"{value}\"")
        };
        if let Some(b) = replace_line(&body, "[material]", &prefix, &format!("{prefix}{quoted}\n"))
        {
            body = b;
        }
    }
    Ok(body)
}

/// `v` as a problem file writes it: at most 6 significant digits, no trailing zeros.
fn short(v: f64) -> String {
    format!("{}", format!("{v:.6e}").parse::<f64>().unwrap_or(v))
}

/// `body` with every hinge of kind `kind`: the `[hinge]` section's kind, and the hinges'
/// variables those of the kind's dimensions.
fn with_hinge(model: &ModelEntry, body: &str, kind: HingeKind) -> Result<String, String> {
    let no_hinges = || {
        format!(
            "--hinge: the model \"{}\" has no hinges of a kind to choose; models with them: {}",
            model.name,
            models_with("hinge")
        )
    };
    let layout = model.hinge_layout.ok_or_else(no_hinges)?;
    let others: Vec<String> = HingeKind::NAMES
        .iter()
        .filter(|&&k| k != kind.name())
        .map(|k| format!("\"{k}\""))
        .collect();
    let line = key(
        format!("kind = \"{}\"", kind.name()),
        &format!("every hinge; or {}", others.join(", ")),
    );
    let body = replace_line(body, "[hinge]", "kind = ", &line).ok_or_else(no_hinges)?;
    let (head, blocks, tail) = variable_blocks(&body);
    let start = kind.start_bounds();
    let mut variables = Vec::new();
    for (p, dimension) in layout(kind) {
        variables.push(match dimension {
            Some(k) => {
                let (lower, upper) = start[k];
                format!(
                    "[[variables]]\n{}unit = \"mm\"\nlower = {lower}\nupper = {upper}\n",
                    key(format!("name = \"{}\"", p.name), &p.description)
                )
            }
            // the template's own entry for the angles and the middle link
            None => blocks
                .iter()
                .find(|(n, _)| *n == p.name)
                .map(|(_, block)| block.to_string())
                .ok_or_else(|| {
                    format!(
                        "--hinge: the {} template has no variable {}",
                        model.name, p.name
                    )
                })?,
        });
    }
    Ok(format!("{head}{}\n{tail}", variables.join("\n")))
}

/// `body` split at its `[[variables]]` entries: the text before the first, each entry's
/// name and text (up to its blank line), and the text after the last.
fn variable_blocks(body: &str) -> (&str, Vec<(&str, &str)>, &str) {
    const ENTRY: &str = "[[variables]]\n";
    let Some(first) = body.find(ENTRY) else {
        return (body, Vec::new(), "");
    };
    let mut blocks = Vec::new();
    let mut at = first;
    while body[at..].starts_with(ENTRY) {
        let end = body[at..].find("\n\n").map_or(body.len(), |e| at + e + 1);
        let block = &body[at..end];
        let name = block
            .lines()
            .find_map(|l| l.strip_prefix("name = \""))
            .and_then(|l| l.split('"').next())
            .unwrap_or("");
        blocks.push((name, block));
        at = (end + 1).min(body.len());
    }
    (&body[..first], blocks, &body[at..])
}

/// `body` with the first line of section `section` that starts with `prefix` replaced by
/// `line` (which ends with its newline); `None` if there is none.
fn replace_line(body: &str, section: &str, prefix: &str, line: &str) -> Option<String> {
    let start = body.find(&format!("\n{section}\n"))? + section.len() + 2;
    let mut at = start;
    for l in body[start..].split_inclusive('\n') {
        if l.starts_with('[') {
            return None;
        }
        if l.starts_with(prefix) {
            return Some(format!("{}{line}{}", &body[..at], &body[at + l.len()..]));
        }
        at += l.len();
    }
    None
}

/// A key and its note, the note aligned as the templates align them.
fn key(k: String, note: &str) -> String {
    format!("{k:<28} # {note}\n")
}

/// The lines above the model's part: how the file was written and the keys every model has.
fn header(model: &ModelEntry, name: &str, flags: &str) -> String {
    format!(
        "# A flexopt problem file, written by\n\
         #   flexopt init --model {m}{flags}\n\
         # Run it with\n\
         #   flexopt run {name}.toml\n\
         # Every key is explained beside it; `flexopt schema` prints the JSON Schema of the\n\
         # format, for editors that complete and check keys.\n\n{}{}{}\n",
        key(
            format!("name = \"{name}\""),
            "names the results folder: letters, digits, - _ ."
        ),
        key("description = \"\"".into(), "free text for the reports"),
        key(
            format!("model = \"{}\"", model.name),
            "the mechanism's model"
        ),
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The quoted value of the first line of `template` that starts with `prefix`.
    fn value_of<'a>(template: &'a str, prefix: &str) -> &'a str {
        let line = template.lines().find(|l| l.starts_with(prefix)).unwrap();
        line.split('"').nth(1).unwrap()
    }

    #[test]
    fn the_templates_own_choices_give_the_template() {
        let models = MODELS.iter().filter(|m| m.hinge_layout.is_some());
        let mut checked = 0;
        for model in models {
            let kind = value_of(model.template, "kind = ");
            let preset = value_of(model.template, "preset = ");
            let chosen = Choices {
                hinge: HingeKind::from_name(kind),
                material: Some(preset),
            };
            let with = template_with(model, "p", chosen).unwrap();
            let m = model.name;
            let flags =
                format!("#   flexopt init --model {m} --material {preset} --hinge {kind}\n");
            let plain = format!("#   flexopt init --model {m}\n");
            assert_eq!(with.replacen(&flags, &plain, 1), template(model, "p"));
            checked += 1;
        }
        assert!(checked > 0);
    }
}
