//! A study in shards: ranges of its starts solved apart (in other processes, on other
//! machines) and merged into exactly the study one run of all of them gives, as every start
//! draws from its own seeded stream and the clustering sees the runs in the order of their
//! starts.

use std::ops::Range;
use std::time::{Duration, Instant};

use super::{from_runs, solve_range, Origin, Run, Study, StudyOptions};
use crate::problem::{Problem, Solver, SOLVERS};

fn solver_name(solver: Solver) -> &'static str {
    SOLVERS
        .0
        .iter()
        .find(|(_, s)| *s == solver)
        .map_or("?", |(name, _)| name)
}

/// The shard `range` of the study `options` describes: the same start points as the whole
/// study's (all are drawn, so that a Latin hypercube keeps its strata), only those with an
/// index in `range` (not empty) solved. Shards that cover `0..options.starts` [`merge`]
/// into exactly the study [`super::run`] gives.
pub fn run_range(
    problem: &Problem,
    options: &StudyOptions,
    range: Range<usize>,
) -> Result<Study, ShardError> {
    if range.start >= range.end {
        return Err(ShardError(format!(
            "the start range {}..{} is empty",
            range.start, range.end
        )));
    }
    if range.end > options.starts {
        return Err(ShardError(format!(
            "the start range {}..{} is not within the study's {} starts",
            range.start, range.end, options.starts
        )));
    }
    Ok(solve_range(problem, options, range))
}

/// Why shards do not make one study, or a range is not one of its shards.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ShardError(pub String);

impl std::fmt::Display for ShardError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ShardError {}

/// The study of `problem` from its shards ([`run_range`]), in any order: their runs joined
/// and clustered, zoned and judged as [`super::run`] does with them, so that the result is the
/// whole study's. The shards must be of one study of `problem` (its file's content and model;
/// starts, seed, solver) and their ranges must cover its starts once each.
pub fn merge(problem: &Problem, mut shards: Vec<Study>) -> Result<Study, ShardError> {
    let begin = Instant::now();
    let Some(first) = shards.first() else {
        return Err(ShardError("no shards to merge".into()));
    };
    let options = first.options.clone();
    let origin = Origin::of(problem);
    if let Some(other) = shards.iter().find(|s| s.origin != origin) {
        return Err(ShardError(format!(
            "the shard of starts {}..{} is of another problem ({}) than the one merged into \
             ({origin}): merge the shards of one problem file into that problem",
            other.range.start, other.range.end, other.origin
        )));
    }
    let same = |o: &StudyOptions| {
        o.starts == options.starts && o.seed == options.seed && o.solver == options.solver
    };
    if let Some(other) = shards.iter().find(|s| !same(&s.options)) {
        return Err(ShardError(format!(
            "the shards are of different studies: {} starts, seed {}, solver {} against {} \
             starts, seed {}, solver {}",
            options.starts,
            options.seed,
            solver_name(options.solver),
            other.options.starts,
            other.options.seed,
            solver_name(other.options.solver)
        )));
    }
    shards.sort_by_key(|s| (s.range.start, s.range.end));
    let mut next = 0;
    for s in &shards {
        if s.range.start != next {
            let what = if s.range.start < next {
                "overlap"
            } else {
                "leave a gap"
            };
            return Err(ShardError(format!(
                "the shards' start ranges {what} at start {}",
                s.range.start.min(next)
            )));
        }
        next = s.range.end;
    }
    if next != options.starts {
        return Err(ShardError(format!(
            "the shards' start ranges end at {next}, not at the study's {} starts",
            options.starts
        )));
    }
    let interrupted = shards.iter().any(|s| s.interrupted);
    let solving: Duration = shards.iter().map(|s| s.elapsed).sum();
    let runs: Vec<Run> = shards.into_iter().flat_map(|s| s.runs).collect();
    let mut study = from_runs(problem, &options, runs, interrupted, 0..options.starts);
    study.elapsed = solving + begin.elapsed();
    Ok(study)
}
