//! The finite-element check of a design's part, as `verify` and `run --verify` run it.

use std::path::Path;

use flexopt::fe::verify::{verify_design, VerifySettings};
use flexopt::problem::Problem;
use flexopt::report::summary::Wrote;
use flexopt::report::verify::{write_verify, VerifyReport, VerifyTable};

use crate::failure::{emit, Failure};

/// The settings of a verification: the defaults, the tolerance from `--tolerance`.
pub fn verify_settings(path: &Path, tolerance: Option<f64>) -> Result<VerifySettings, Failure> {
    let mut settings = VerifySettings::default();
    if let Some(t) = tolerance {
        if !(1e-6..=0.1).contains(&t) {
            return Err(Failure::bad_input(format!(
                "{}: key `--tolerance`: must lie between 1e-6 and 0.1, got {t}",
                path.display()
            )));
        }
        settings.tolerance = t;
    }
    Ok(settings)
}

/// Checks the design `x` on its part, writes the files into `dir` and prints the table.
pub fn run_verify(
    problem: &Problem,
    x: &[f64],
    settings: &VerifySettings,
    dir: &Path,
) -> Result<(), Failure> {
    if let Some(Err(e)) = problem.mechanism().part(x) {
        return Err(Failure::cannot_be_made(format!(
            "{}: this design gives no part that can be made: {e}",
            problem.file.display()
        )));
    }
    let v = verify_design(problem.mechanism(), x, settings).map_err(|e| {
        Failure::bad_input(format!(
            "{}: cannot check this design: {e}",
            problem.file.display()
        ))
    })?;
    let report = VerifyReport::new(problem, x, &v);
    let files = write_verify(|name| dir.join(name), &report, &v).map_err(Failure::write_failed)?;
    emit(&VerifyTable(&report));
    emit(&Wrote(&files));
    Ok(())
}
