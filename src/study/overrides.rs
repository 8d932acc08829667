//! The overrides of a problem file's `[search]` that a command's options (or the Python
//! package's arguments) give, checked once for both, each refusal naming the option.

use super::StudyOptions;
use crate::problem::schema::{STARTS, THREADS};
use crate::problem::{Problem, SOLVERS};

/// Overrides of `[search]`; integers wide enough that every caller's value is checked, not
/// cut.
#[derive(Debug, Clone, Copy, Default)]
pub struct Overrides<'a> {
    pub starts: Option<i128>,
    pub seed: Option<i128>,
    pub threads: Option<i128>,
    pub solver: Option<&'a str>,
}

/// An override or a problem refused: the whole message (file, key, what is wrong) and the
/// key it names, if any.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OverrideError {
    pub key: Option<String>,
    pub message: String,
}

impl StudyOptions {
    /// The options of a study of `problem`: its `[search]` with `overrides`, whose keys the
    /// messages name with `prefix` (`--` on the command line). Refused too: a problem whose
    /// ranges of fit no design in the bounds meets, and one with nothing to optimize.
    pub fn with_overrides(
        problem: &Problem,
        overrides: &Overrides,
        prefix: &str,
    ) -> Result<Self, OverrideError> {
        if let Some(why) = crate::problem::fit::unreachable(problem) {
            return Err(OverrideError {
                key: None,
                message: why,
            });
        }
        let file = problem.file.display();
        let refuse = |key: &str, what: String| OverrideError {
            key: Some(key.to_string()),
            message: format!("{file}: key `{key}`: {what}"),
        };
        if problem.free_variables().next().is_none() {
            return Err(refuse(
                "variables",
                "every variable has a fixed `value`, so there is nothing to optimize; give at \
                 least one `lower` and `upper` instead (`flexopt eval` and `flexopt sweep` take \
                 a fixed design)"
                    .into(),
            ));
        }
        let range = |name: &str, value: Option<i128>, (lo, hi): (i64, i64)| match value {
            Some(v) if !(i128::from(lo)..=i128::from(hi)).contains(&v) => Err(refuse(
                &format!("{prefix}{name}"),
                format!("must lie between {lo} and {hi}, got {v}"),
            )),
            _ => Ok(value.map(|v| v as u64)),
        };
        let starts = range("starts", overrides.starts, STARTS)?;
        let threads = checked_threads(overrides.threads)
            .map_err(|what| refuse(&format!("{prefix}threads"), what))?;
        // the file's seed is a TOML integer: one range for both
        let seed = range("seed", overrides.seed, (0, i64::MAX))?;
        let mut options = StudyOptions::from_problem(problem);
        if let Some(name) = overrides.solver {
            options.solver = SOLVERS.get(name).ok_or_else(|| {
                let names = SOLVERS.names().join(", ");
                let what = format!("unknown solver \"{name}\"; expected one of {names}");
                refuse(&format!("{prefix}solver"), what)
            })?;
        }
        options.starts = starts.map_or(options.starts, |s| s as usize);
        options.threads = threads.unwrap_or(options.threads);
        options.seed = seed.unwrap_or(options.seed);
        Ok(options)
    }
}

/// A thread count a command (or the Python package) gives, in the range `search.threads`
/// takes: the one check of every `--threads`, as a thread each is started whether or not
/// there is work for it. `None` where none is given (the file's); the error says what is
/// wrong, for the caller to name the file and the key.
pub fn checked_threads(threads: Option<i128>) -> Result<Option<usize>, String> {
    let (lo, hi) = THREADS;
    match threads {
        Some(t) if !(i128::from(lo)..=i128::from(hi)).contains(&t) => {
            Err(format!("must lie between {lo} and {hi}, got {t}"))
        }
        _ => Ok(threads.map(|t| t as usize)),
    }
}
