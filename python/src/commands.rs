//! The library's other commands on one design: the tolerance analysis, the part's files and
//! the finite-element check, with the command line's checks and messages.

use std::path::Path;

use flexopt::fe::verify::{verify_design, VerifySettings};
use flexopt::refine::study::refine_design;
use flexopt::report::part::write_part_set;
use flexopt::report::refine::RefinedReport;
use flexopt::report::tolerance::ToleranceReport;
use flexopt::report::verify::VerifyReport;
use flexopt::report::{check_writable, DesignReport};
use flexopt::tolerance::{analyze, monte_carlo::Settings};

use crate::error::Error;
use crate::problem::Problem;

/// The samples `flexopt tolerance --samples` takes.
const SAMPLES: (usize, usize) = (2, 10_000_000);

/// The `samples` of `tolerance` checked against [`SAMPLES`] as a signed integer (a
/// negative one raised `OverflowError` as a `usize`).
pub fn samples(p: &Problem, samples: i64) -> Result<usize, Error> {
    match usize::try_from(samples) {
        Ok(n) if (SAMPLES.0..=SAMPLES.1).contains(&n) => Ok(n),
        _ => {
            let what = format!(
                "must lie between {} and {}, got {samples}",
                SAMPLES.0, SAMPLES.1
            );
            Err(Error::bad_input(p.file(), "samples", what))
        }
    }
}

/// The report of `flexopt tolerance` (`tolerance.json`) at the design `x` (SI), of
/// `samples` checked by [`samples`].
pub fn tolerance(
    p: &Problem,
    x: &[f64],
    samples: usize,
    seed: Option<u64>,
    threads: Option<usize>,
) -> Result<ToleranceReport, Error> {
    let problem = &p.inner;
    if let Some(e) = problem.stand_in_error("a tolerance analysis") {
        return Err(e.into());
    }
    let settings = Settings {
        samples,
        seed: seed.unwrap_or(problem.search.seed),
        threads: threads.unwrap_or(problem.search.threads),
    };
    let analysis =
        analyze(problem, x, settings).map_err(|e| Error::bad_input(p.file(), "tolerances", e))?;
    Ok(ToleranceReport::new(problem, x, &analysis))
}

fn cannot_be_made(p: &Problem, e: impl std::fmt::Display) -> Error {
    let what = format!("this design gives no part that can be made: {e}");
    Error::bad_input(p.file(), "", what).with_code(5)
}

/// The part's files of `flexopt export` at the design `x` (SI), written into `dir` as one
/// set: their paths.
pub fn export(p: &Problem, x: &[f64], dir: &Path) -> Result<Vec<String>, Error> {
    let problem = &p.inner;
    check_writable(dir).map_err(|e| Error::bad_input(p.file(), "out", e))?;
    let part = problem.mechanism().part_or_error(x).map_err(|e| {
        // a model without a part is a problem file's mistake, not its part's
        let code = if problem.mechanism().part_spec(x).is_some() {
            5
        } else {
            2
        };
        cannot_be_made(p, e).with_code(code)
    })?;
    let report = DesignReport::new(problem, x);
    let files = write_part_set(
        dir,
        &problem.name,
        &report.design,
        &part,
        &report.part_rules,
    )
    .map_err(|e| Error {
        message: e.to_string(),
        file: Some(dir.display().to_string()),
        key: None,
        code: 1,
    })?;
    Ok(files.iter().map(|f| f.display().to_string()).collect())
}

/// The report of `flexopt verify` (`verify.json`) at the design `x` (SI).
pub fn verify(
    p: &Problem,
    x: &[f64],
    tolerance: Option<f64>,
    max_dofs: Option<usize>,
) -> Result<VerifyReport, Error> {
    let problem = &p.inner;
    let mut settings = VerifySettings::default();
    if let Some(t) = tolerance {
        if !(1e-6..=0.1).contains(&t) {
            let what = format!("must lie between 1e-6 and 0.1, got {t}");
            return Err(Error::bad_input(p.file(), "tolerance", what));
        }
        settings.tolerance = t;
        settings.per_thickness = VerifySettings::per_thickness_for(t);
    }
    if let Some(n) = max_dofs {
        if !(1_000..=50_000_000).contains(&n) {
            let what = format!("must lie between 1000 and 50000000, got {n}");
            return Err(Error::bad_input(p.file(), "max_dofs", what));
        }
        settings.max_dofs = n;
    }
    if let Some(Err(e)) = problem.mechanism().part(x) {
        return Err(cannot_be_made(p, e));
    }
    let v = verify_design(problem.mechanism(), x, &settings)
        .map_err(|e| Error::bad_input(p.file(), "", format!("cannot check this design: {e}")))?;
    Ok(VerifyReport::new(problem, x, &v))
}

/// The report of `run --refine fe` (`refined.json`) for the design `x` (SI) refined against
/// the finite elements of its part, with `[refine]`'s settings and `max_fe` in place of its
/// budget where given.
pub fn refine(p: &Problem, x: &[f64], max_fe: Option<i64>) -> Result<RefinedReport, Error> {
    let mut problem = (*p.inner).clone();
    // asked for, as `--refine fe` asks for it whatever the file's `[refine] enabled`
    problem.refine.enabled = true;
    if let Some(n) = max_fe {
        let (lo, hi) = flexopt::problem::refine::MAX_FE;
        if !(lo..=hi).contains(&n) {
            let what = format!("must lie between {lo} and {hi}, got {n}");
            return Err(Error::bad_input(p.file(), "max_fe", what));
        }
        problem.refine.max_fe = n as usize;
    }
    problem
        .mechanism()
        .part_or_error(x)
        .map_err(|e| cannot_be_made(p, e))?;
    let r = refine_design(&problem, x);
    Ok(RefinedReport::new(&problem, &problem.refine, &r))
}
