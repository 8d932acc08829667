//! `flexopt tolerance`: one design under its tolerances, written as a set and shown as a
//! table.

use std::path::Path;

use crate::failure::{emit, Failure};
use flexopt::problem::Problem;
use flexopt::refine::spread::{measure_spread, SpreadError, SpreadSettings, MIN_SAMPLES};
use flexopt::refine::study::spread_fidelity;
use flexopt::report::tolerance::FeReport;
use flexopt::report::tolerance::{
    write_robust, write_tolerance_set, RobustTable, ToleranceReport, ToleranceTable,
};
use flexopt::study::checked_threads;
use flexopt::study::{Study, StudyOptions};
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
    let threads = checked_threads(threads.map(|t| t as i128)).map_err(|what| {
        Failure::bad_input(format!(
            "{}: key `--threads`: {what}",
            problem.file.display()
        ))
    })?;
    Ok(Settings {
        samples,
        seed: seed.unwrap_or(problem.search.seed),
        threads: threads.unwrap_or(problem.search.threads),
    })
}

/// The most samples `--fe` checks: each is an FE check of a second or more.
const FE_SAMPLES: (usize, usize) = (MIN_SAMPLES, 200);

/// The settings of `--fe`'s samples: the Monte Carlo's seed and threads.
pub fn fe_samples(
    problem: &Problem,
    samples: usize,
    settings: Settings,
) -> Result<SpreadSettings, Failure> {
    if !(FE_SAMPLES.0..=FE_SAMPLES.1).contains(&samples) {
        return Err(Failure::bad_input(format!(
            "{}: key `--fe-samples`: must lie between {} and {}, got {samples}",
            problem.file.display(),
            FE_SAMPLES.0,
            FE_SAMPLES.1
        )));
    }
    if problem.mechanism.part_maker.is_none() {
        return Err(Failure::bad_input(format!(
            "{}: key `--fe`: the {} model has no part to check by finite elements",
            problem.file.display(),
            problem.model().name()
        )));
    }
    Ok(SpreadSettings {
        samples,
        seed: settings.seed,
        threads: settings.threads,
    })
}

pub fn run(
    problem: &Problem,
    x: &[f64],
    settings: Settings,
    fe: Option<SpreadSettings>,
    dir: &Path,
) -> Result<(), Failure> {
    let analysis = analyze(problem, x, settings).map_err(|e| {
        Failure::bad_input(format!("{}: key `tolerances`: {e}", problem.file.display()))
    })?;
    let mut report = ToleranceReport::new(problem, x, &analysis);
    if let Some(fe_settings) = fe {
        let high = spread_fidelity(problem, x);
        let spread = measure_spread(problem, x, &analysis, &high, fe_settings).map_err(|e| {
            let message = format!(
                "{}: key `--fe`: the FE check of the samples: {e}",
                problem.file.display()
            );
            match e {
                SpreadError::Input(_) => Failure::bad_input(message),
                SpreadError::Measure(_) => Failure::cannot_be_made(message),
            }
        })?;
        report.fe = Some(FeReport::new(problem, &spread));
    }
    let files =
        write_tolerance_set(dir, &report, &analysis, problem).map_err(Failure::write_failed)?;
    emit(&ToleranceTable(&report))?;
    emit(&flexopt::report::summary::Wrote(&files))
}

/// The samples of the yields a robust run reports: 100,000 give a yield of 0.99 to about
/// +-0.0006 (95 %), in a fraction of a second on wei2017.
pub const ROBUST_SAMPLES: usize = 100_000;

/// A robust run's optimum beside the nominal study's: shown, and written as `robust.json`.
pub fn compare_robust(
    problem: &Problem,
    options: &StudyOptions,
    study: &Study,
    dir: &Path,
) -> Result<(), Failure> {
    if options.progress {
        eprintln!("running the nominal study and the Monte Carlo yields beside the robust one...");
    }
    let settings = Settings {
        samples: ROBUST_SAMPLES,
        seed: options.seed,
        threads: options.threads,
    };
    let comparison = flexopt::tolerance::robust::compare(
        problem,
        options,
        study.reported_design(),
        study.reported_objective(),
        settings,
    )
    .map_err(|e| {
        Failure::bad_input(format!("{}: key `tolerances`: {e}", problem.file.display()))
    })?;
    emit(&RobustTable(&comparison, problem))?;
    let files = write_robust(dir, &comparison).map_err(Failure::write_failed)?;
    emit(&flexopt::report::summary::Wrote(&files[..1]))
}
