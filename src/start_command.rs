//! The commands that help a user start: `init`, `schema`, `completions`, `outputs`, and the
//! reading of a problem file from standard input (`-`).

use std::io::Read;
use std::path::Path;

use clap::CommandFactory;

use crate::args::Cli;
use crate::failure::{emit, Failure};
use flexopt::model::hinge::HingeKind;
use flexopt::model::registry::{find, MODELS};
use flexopt::problem::init::{name_from, template, template_with, Choices};
use flexopt::problem::json_schema::json_schema;
use flexopt::problem::units::Unit;
use flexopt::problem::Problem;

/// The problem file at `path`, or from standard input when `path` is `-`.
pub(crate) fn load_problem(path: &Path) -> Result<Problem, Failure> {
    if path != Path::new("-") {
        return Problem::load(path).map_err(Failure::bad_input);
    }
    let mut text = String::new();
    std::io::stdin()
        .take(flexopt::problem::MAX_FILE_BYTES + 1)
        .read_to_string(&mut text)
        .map_err(|e| Failure::bad_input(format!("<stdin>: cannot read the problem file: {e}")))?;
    if text.len() as u64 > flexopt::problem::MAX_FILE_BYTES {
        return Err(Failure::bad_input(format!(
            "<stdin>: a problem file may have at most {} bytes",
            flexopt::problem::MAX_FILE_BYTES
        )));
    }
    Problem::parse(Path::new("<stdin>"), &text).map_err(Failure::bad_input)
}

/// `flexopt init`: the template of `model`, with the hinge kind and material preset chosen,
/// into `file`, or onto standard output.
pub(crate) fn init(
    model: &str,
    hinge: Option<&str>,
    material: Option<&str>,
    file: Option<&Path>,
    force: bool,
) -> Result<(), Failure> {
    let entry = find(MODELS, model)
        .ok_or_else(|| Failure::bad_input(format!("unknown model \"{model}\"")))?;
    let hinge = match hinge {
        Some(name) => Some(HingeKind::from_name(name).ok_or_else(|| {
            Failure::bad_input(format!(
                "--hinge: unknown kind \"{name}\"; the kinds: {}",
                HingeKind::NAMES.join(", ")
            ))
        })?),
        None => None,
    };
    let name = file
        .and_then(|f| f.file_stem())
        .map(|s| name_from(&s.to_string_lossy()))
        .unwrap_or_else(|| format!("my_{model}"));
    let text =
        template_with(entry, &name, Choices { hinge, material }).map_err(Failure::bad_input)?;
    let Some(file) = file else {
        emit(&text)?;
        return Ok(());
    };
    if file.exists() && !force {
        return Err(Failure::bad_input(format!(
            "{}: the file exists; give --force to overwrite it",
            file.display()
        )));
    }
    flexopt::report::write_atomic(file, text.as_bytes()).map_err(|e| {
        Failure::bad_input(format!(
            "{}: cannot be written: {}",
            file.display(),
            e.message
        ))
    })?;
    eprintln!(
        "wrote {}: a {model} problem ready to run; edit it, then: flexopt run {}",
        file.display(),
        file.display()
    );
    Ok(())
}

/// `flexopt schema`.
pub(crate) fn schema() -> Result<(), Failure> {
    crate::failure::print_json(&json_schema())
}

/// `flexopt completions SHELL`. clap_complete panics when its writer fails, so the script
/// is made in memory and written as every other output is.
pub(crate) fn completions(shell: clap_complete::Shell) -> Result<(), Failure> {
    let mut script = Vec::new();
    clap_complete::generate(shell, &mut Cli::command(), "flexopt", &mut script);
    crate::failure::write_stdout(&script)
}

/// `flexopt outputs --model M`: the model's parameters and outputs, as its template
/// configures it.
pub(crate) fn outputs(model: &str, file: Option<&Path>) -> Result<(), Failure> {
    let problem = match file {
        // the file's own model, its sections read: a circular hinge's parameters are r and
        // t, a strip's l and t
        Some(path) => Problem::load(path).map_err(Failure::bad_input)?,
        None => {
            let entry = find(MODELS, model)
                .ok_or_else(|| Failure::bad_input(format!("unknown model \"{model}\"")))?;
            Problem::parse(Path::new("template.toml"), &template(entry, "template")).map_err(
                |e| Failure::bad_input(format!("the {model} template does not read: {e}")),
            )?
        }
    };
    let m = problem.model();
    let model = m.name();
    let mut text = format!("{model}: parameters (each a [[variables]] entry)\n");
    for p in m.parameters() {
        text += &format!(
            "  {:<18} {:<9} {}\n",
            p.name,
            Unit::display(p.dimension).name,
            p.description
        );
    }
    text += &format!(
        "{model}: outputs (objective and constraints name them; shown in this unit unless a \
         constraint gives another, SI in JSON)\n"
    );
    for (i, o) in m.outputs().iter().enumerate() {
        let note = match (m.unavailable(i), o.stand_in) {
            (Some(_), _) => " (needs [dynamics])".to_string(),
            (None, Some(what)) => format!(" (the model's value: {what})"),
            (None, None) => String::new(),
        };
        text += &format!(
            "  {:<18} {:<9} {}{note}\n",
            o.name,
            o.display
                .map_or_else(|| Unit::display(o.dimension).name, str::to_string),
            o.description
        );
    }
    emit(&text)
}
