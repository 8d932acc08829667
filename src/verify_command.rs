//! The finite-element check of a design's part, as `verify` and `run --verify` run it.

use std::path::Path;

use flexopt::fe::verify::{verify_design, Verification, VerifySettings};
use flexopt::problem::Problem;
use flexopt::report::summary::Wrote;
use flexopt::report::verify::{write_verify_set, VerifyReport, VerifyTable};

use crate::failure::{emit, Failure};

/// The settings of a verification: the defaults, the tolerance from `--tolerance` (and the
/// first mesh's elements through a hinge from it), the budget from `--max-dofs`.
pub fn verify_settings(
    path: &Path,
    tolerance: Option<f64>,
    max_dofs: Option<usize>,
) -> Result<VerifySettings, Failure> {
    let mut settings = VerifySettings::default();
    if let Some(t) = tolerance {
        if !(1e-6..=0.1).contains(&t) {
            return Err(Failure::bad_input(format!(
                "{}: key `--tolerance`: must lie between 1e-6 and 0.1, got {t}",
                path.display()
            )));
        }
        settings.tolerance = t;
        settings.per_thickness = VerifySettings::per_thickness_for(t);
    }
    if let Some(n) = max_dofs {
        if !(1_000..=50_000_000).contains(&n) {
            return Err(Failure::bad_input(format!(
                "{}: key `--max-dofs`: must lie between 1000 and 50000000, got {n}",
                path.display()
            )));
        }
        settings.max_dofs = n;
    }
    Ok(settings)
}

/// Checks the design `x` on its part, writes the files into `dir` as one set and prints the
/// table.
pub fn run_verify(
    problem: &Problem,
    x: &[f64],
    settings: &VerifySettings,
    dir: &Path,
) -> Result<(), Failure> {
    let (report, v) = check_design(problem, x, settings)?;
    let files = write_verify_set(dir, &report, &v).map_err(Failure::write_failed)?;
    emit(&VerifyTable(&report))?;
    emit(&Wrote(&files))
}

/// Checks the design `x` on its part: the report and the verification it was made from.
pub fn check_design(
    problem: &Problem,
    x: &[f64],
    settings: &VerifySettings,
) -> Result<(VerifyReport, Verification), Failure> {
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
    Ok((VerifyReport::new(problem, x, &v), v))
}
