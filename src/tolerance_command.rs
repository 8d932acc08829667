//! `flexopt tolerance`: one design under its tolerances, written as a set and shown as a
//! table.

use std::path::Path;

use crate::failure::{emit, Failure};
use flexopt::problem::Problem;
use flexopt::report::tolerance::{write_tolerance_set, ToleranceReport, ToleranceTable};
use flexopt::tolerance::{analyze, monte_carlo::Settings};

/// The most samples a run may ask for: ten million rows of outputs are a few hundred MB.
const SAMPLES: (usize, usize) = (2, 10_000_000);

/// The Monte Carlo settings of the options, the file's `[search]` for those not given.
pub fn settings(
    problem: &Problem,
    samples: usize,
    seed: Option<u64>,
    threads: Option<usize>,
) -> Result<Settings, Failure> {
    if !(SAMPLES.0..=SAMPLES.1).contains(&samples) {
        return Err(Failure::bad_input(format!(
            "{}: key `--samples`: must lie between {} and {}, got {samples}",
            problem.file.display(),
            SAMPLES.0,
            SAMPLES.1
        )));
    }
    if let Some(e) = problem.stand_in_error("a tolerance analysis") {
        return Err(Failure::bad_input(e));
    }
    Ok(Settings {
        samples,
        seed: seed.unwrap_or(problem.search.seed),
        threads: threads.unwrap_or(problem.search.threads),
    })
}

pub fn run(problem: &Problem, x: &[f64], settings: Settings, dir: &Path) -> Result<(), Failure> {
    let analysis = analyze(problem, x, settings).map_err(|e| {
        Failure::bad_input(format!(
            "{}: key `tolerances`: {e}",
            problem.file.display()
        ))
    })?;
    let report = ToleranceReport::new(problem, x, &analysis);
    let files =
        write_tolerance_set(dir, &report, &analysis, problem).map_err(Failure::write_failed)?;
    emit(&ToleranceTable(&report))?;
    emit(&flexopt::report::summary::Wrote(&files))
}
