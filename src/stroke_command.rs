//! `flexopt stroke`: one network design solved with its flexures' large deflection over its
//! working stroke (`Mechanism::large`), written as a set beside the linear model and shown
//! as a table.

use flexopt::model::large::report::StrokeOptions;
use flexopt::problem::Problem;
use flexopt::report::check_writable;
use flexopt::report::stroke::{write_stroke_set, StrokeRun, StrokeTable};
use flexopt::report::summary::Wrote;

use crate::args::StrokeArgs;
use crate::failure::{emit, Failure};

/// The elements a flexure a solve may take: each solve is dense, and the estimate solves
/// with twice as many.
const ELEMENTS: (usize, usize) = (1, 64);
/// The load steps of the path: its points.
const STEPS: (usize, usize) = (1, 1000);

/// Solves the chosen design `x` of `problem` over its stroke, writes the set and prints the
/// table.
pub fn run(problem: &Problem, x: &[f64], args: &StrokeArgs) -> Result<(), Failure> {
    let Some(large) = problem.mechanism().large.clone() else {
        return Err(Failure::bad_input(format!(
            "{}: key `model`: the large-deflection solve is for networks: model `{}` has \
             none (`model = \"network\"` has)",
            problem.file.display(),
            problem.model().name()
        )));
    };
    let options = options(problem, args)?;
    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| problem.default_output_dir().join("stroke"));
    check_writable(&dir).map_err(|e| Failure::bad_input(format!("key `--out`: {e}")))?;
    let report = large.at_stroke(x, &options).map_err(|e| {
        Failure::bad_input(format!(
            "{}: cannot solve this design over its stroke: {e}",
            problem.file.display()
        ))
    })?;
    let run = StrokeRun::new(problem, x, &options, report);
    let files = write_stroke_set(&dir, &run).map_err(Failure::write_failed)?;
    emit(&StrokeTable(&run))?;
    emit(&Wrote(&files))
}

/// The solve's options from the command line's, each checked against its range.
fn options(problem: &Problem, args: &StrokeArgs) -> Result<StrokeOptions, Failure> {
    let file = problem.file.display();
    let within = |key: &str, v: usize, (lo, hi): (usize, usize)| {
        if (lo..=hi).contains(&v) {
            Ok(v)
        } else {
            Err(Failure::bad_input(format!(
                "{file}: key `{key}`: must lie between {lo} and {hi}, got {v}"
            )))
        }
    };
    let elements = within("--elements", args.elements, ELEMENTS)?;
    let steps = within("--steps", args.steps, STEPS)?;
    if let Some(f) = args.force.filter(|f| !f.is_finite() || *f == 0.0) {
        return Err(Failure::bad_input(format!(
            "{file}: key `--force`: must be a finite force other than 0 N, got {f}"
        )));
    }
    Ok(StrokeOptions {
        elements,
        steps,
        force: args.force,
        ..StrokeOptions::default()
    })
}
