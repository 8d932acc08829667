//! The multistart study of a design problem: local solves from many starts, every result
//! kept, optima merged and sorted into zones, the best feasible design picked.

use std::ops::Range;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::{Duration, Instant};

use serde::Serialize;

use crate::optim::cluster::{cluster, ClusterSettings, Clustering, EndPoint};
use crate::optim::multistart::{self, Sampling as StartSampling};
use crate::optim::nelder_mead::{self, NelderMeadSettings};
use crate::optim::progress::Progress;
use crate::optim::sqp::{self, SqpSettings};
use crate::optim::staged::{self, HandOvers};
use crate::optim::{Problem as OptimProblem, Solution, Status};
use crate::problem::epigraph::Epigraph;
use crate::problem::nlp::{feasible_end, DesignNlp, FEASIBILITY_TOLERANCE};
use crate::problem::{Problem, Sampling, Sense, Solver};

pub mod least_violating;
mod overrides;
mod shards;
pub use least_violating::LeastViolating;
pub use overrides::{checked_threads, OverrideError, Overrides};
pub use shards::{merge, run_range, ShardError};

/// What a study runs with; the problem file's `[search]` gives the defaults.
#[derive(Debug, Clone)]
pub struct StudyOptions {
    pub starts: usize,
    pub seed: u64,
    pub solver: Solver,
    pub threads: usize,
    pub progress: bool,
    /// Set (by an interrupt) to stop: starts not begun are skipped, the study keeps the
    /// finished ones and says so (`Study::interrupted`).
    pub stop: Arc<AtomicBool>,
    /// When no start is feasible, search for the least violating design and the constraints
    /// that cannot be met ([`least_violating`]); a Pareto front, which only marks such
    /// points, turns it off.
    pub explain_infeasible: bool,
    /// The SQP's constraint screening ([`SqpSettings::screening`]); off by default: on the
    /// studies of issue 23 it did not pay (`examples/rules_timing.rs`, docs/performance.md).
    pub screening: bool,
}

impl StudyOptions {
    pub fn from_problem(problem: &Problem) -> Self {
        let s = &problem.search;
        StudyOptions {
            starts: s.starts,
            seed: s.seed,
            solver: s.solver,
            threads: s.threads,
            progress: false,
            stop: Arc::new(AtomicBool::new(false)),
            explain_infeasible: true,
            screening: false,
        }
    }
}

/// One local solve of the study.
#[derive(Debug, Clone, Serialize)]
pub struct Run {
    pub start: usize,
    /// Start and end designs, full model parameter vectors in SI.
    pub x_start: Vec<f64>,
    pub x_end: Vec<f64>,
    /// The objective as the problem states it.
    pub objective: f64,
    pub feasible: bool,
    pub solution: Solution,
    /// The distinct optimum and zone rank this run reached (feasible runs only).
    pub optimum: Option<usize>,
    pub zone: Option<usize>,
}

/// The result of a study.
#[derive(Debug, Clone)]
pub struct Study {
    pub runs: Vec<Run>,
    /// Clustering of the feasible runs; indices there refer to `feasible_runs`.
    pub clustering: Clustering,
    pub feasible_runs: Vec<usize>,
    /// The best feasible run that converged; else the best feasible run (see
    /// `best_converged`); else the least violating one when none is feasible.
    pub best: usize,
    pub any_feasible: bool,
    /// Whether `best` converged (KKT residual below the tolerance).
    pub best_converged: bool,
    /// Stopped by an interrupt: `runs` holds the starts that finished.
    pub interrupted: bool,
    /// How the local solves ended.
    pub ends: Ends,
    /// When no start is feasible (and the study was not interrupted): the design that meets
    /// every constraint it can and violates the rest least, and which cannot be met.
    pub least_violating: Option<LeastViolating>,
    /// The mirror image of the best run's end (full design, SI), when the study merges
    /// mirror images, the model prefers that orientation ([`crate::model::Model::prefers_mirror`])
    /// and the mirror is as feasible and as good: the design reported.
    pub mirrored: Option<Vec<f64>>,
    pub elapsed: Duration,
    pub options: StudyOptions,
    /// The starts solved: all of them (`0..options.starts`), or a shard's range
    /// ([`run_range`]) until [`merge`] joins the shards.
    pub range: Range<usize>,
}

/// How the local solves of a study ended, by status.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Ends {
    pub converged: usize,
    pub iteration_limit: usize,
    /// Stopped at a point that minimizes the constraint violation but violates them.
    pub infeasible: usize,
    pub failed: usize,
}

impl Study {
    /// The design the study reports, as the model's full parameter vector in SI: the best
    /// run's end, or the least violating design when no start is feasible.
    pub fn reported_design(&self) -> &[f64] {
        match (&self.least_violating, &self.mirrored) {
            (Some(l), _) => &l.x,
            (None, Some(m)) => m,
            (None, None) => &self.runs[self.best].x_end,
        }
    }

    /// The objective, as the problem states it, at [`Self::reported_design`].
    pub fn reported_objective(&self) -> f64 {
        match &self.least_violating {
            Some(l) => l.objective,
            None => self.runs[self.best].objective,
        }
    }
}

impl Ends {
    fn count(runs: &[Run]) -> Self {
        let mut e = Ends::default();
        for r in runs {
            match r.solution.status {
                Status::Converged => e.converged += 1,
                Status::IterationLimit => e.iteration_limit += 1,
                Status::Infeasible => e.infeasible += 1,
                Status::Failed(_) => e.failed += 1,
            }
        }
        e
    }
}

/// The mirror image of `run`'s end (full design, SI) when the model prefers it and it
/// lies within the bounds, meets the constraints and has the same objective (relative
/// `1e-12`): the same geometry, drawn the other way round.
fn preferred_mirror(problem: &Problem, nlp: &DesignNlp, run: &Run) -> Option<Vec<f64>> {
    if !problem.depiction().prefers_mirror(&run.x_end) {
        return None;
    }
    let u = nlp.mirror(&run.solution.x)?;
    let mut c = vec![0.0; nlp.constraint_count()];
    let f = nlp.evaluate(&u, &mut c);
    let same =
        (nlp.objective_at(&u, f) - run.objective).abs() <= 1e-12 * run.objective.abs().max(1e-300);
    let feasible =
        crate::optim::problem::max_violation(&c, nlp.equality_count()) <= FEASIBILITY_TOLERANCE;
    // the end mirrored exactly, not through the scaling's rounding
    let mut x = run.x_end.clone();
    (same && feasible && problem.model().mirror(&mut x)).then_some(x)
}

/// Runs the study of `problem`.
pub fn run(problem: &Problem, options: &StudyOptions) -> Study {
    solve_range(problem, options, 0..options.starts)
}

fn solve_range(problem: &Problem, options: &StudyOptions, range: Range<usize>) -> Study {
    // the problems each start is solved in, in turn, the study's own last
    let stages = DesignNlp::stages(problem);
    let nlp = stages.last().expect("a study solves its own problem last");
    let n = nlp.dimension();
    let sampling = match problem.search.sampling {
        Sampling::Uniform => StartSampling::Uniform,
        Sampling::LatinHypercube => StartSampling::LatinHypercube,
    };
    let starts = multistart::start_points(
        &vec![0.0; n],
        &vec![1.0; n],
        options.starts,
        options.seed,
        sampling,
    );
    let starts = &starts[range.clone()];
    let tolerance = problem.search.tolerance;
    let max_iterations = problem.search.max_iterations;
    // the progress's best: a feasible end's objective as the problem states it
    let unit = crate::problem::display::output_unit(problem, problem.objective.index);
    let label = |s: &Solution| -> Option<(f64, String)> {
        feasible_end(s).then(|| {
            let value = nlp.objective_at(&s.x[..n], s.objective);
            let rank = crate::problem::nlp::merit(problem.objective.sense, false, value);
            let text = crate::problem::display::with_unit(value, &unit);
            (rank, format!("{} {text}", problem.objective.output))
        })
    };
    let progress = options
        .progress
        .then(|| Progress::new("local solves", range.len(), &label));
    let progress = progress.as_ref();
    let begin = Instant::now();
    let plain: Vec<&dyn OptimProblem> = stages.iter().map(|s| s as _).collect();
    // a stage's end reflected (scaled variables, every stage's the same), for the next
    // stage to take on from where the end itself breaks its constraints; not where the
    // problem tells mirror images apart
    let merge = problem.zones.merge_mirror_images;
    let mirror = |u: &[f64]| nlp.mirror(u).filter(|_| merge);
    // the epigraph's bound on the largest part is the same at the mirror image
    let ep_mirror = |v: &[f64]| {
        let mut m = mirror(&v[..n])?;
        m.extend_from_slice(&v[n..]);
        Some(m)
    };
    // each stage's solves from the ends of the stage before, shared by the starts
    let hand_overs: Vec<HandOvers> = stages.iter().map(|_| HandOvers::new()).collect();
    let solutions = match options.solver {
        Solver::Sqp => {
            let settings = SqpSettings {
                tolerance,
                max_iterations,
                screening: options.screening,
                ..SqpSettings::default()
            };
            let sqp = |p: &dyn OptimProblem, x0: &[f64]| sqp::solve(p, x0, &settings);
            // a minimized maximum: its kinks removed by the epigraph form, whose extra
            // variable is dropped again below
            match Epigraph::new(nlp) {
                Some(ep) => {
                    let ep_stages: Vec<Epigraph> =
                        stages.iter().filter_map(Epigraph::new).collect();
                    let ep_stages: Vec<&dyn OptimProblem> =
                        ep_stages.iter().map(|s| s as _).collect();
                    let starts: Vec<Vec<f64>> = starts.iter().map(|u| ep.start(u)).collect();
                    multistart::run_until(
                        &ep,
                        &starts,
                        |_, x0| in_stages(&ep_stages, x0, &sqp, &ep_mirror, &hand_overs),
                        options.threads,
                        progress,
                        &options.stop,
                    )
                    .into_iter()
                    .map(|s| {
                        s.map(|mut s| {
                            s.x.truncate(n);
                            s
                        })
                    })
                    .collect()
                }
                None => multistart::run_until(
                    nlp,
                    starts,
                    |_, x0| in_stages(&plain, x0, &sqp, &mirror, &hand_overs),
                    options.threads,
                    progress,
                    &options.stop,
                ),
            }
        }
        Solver::NelderMead => {
            let settings = NelderMeadSettings {
                tolerance,
                max_iterations: max_iterations.min(60),
                ..NelderMeadSettings::default()
            };
            let nm = |p: &dyn OptimProblem, x0: &[f64]| nelder_mead::solve(p, x0, &settings);
            multistart::run_until(
                nlp,
                starts,
                |_, x0| in_stages(&plain, x0, &nm, &mirror, &hand_overs),
                options.threads,
                progress,
                &options.stop,
            )
        }
    };
    let interrupted = solutions.iter().any(Option::is_none);
    let runs: Vec<Run> = solutions
        .into_iter()
        .enumerate()
        .filter_map(|(k, s)| Some((k, s?)))
        .map(|(k, s)| {
            let feasible = feasible_end(&s);
            Run {
                start: range.start + k,
                x_start: nlp.full_design(&starts[k]),
                x_end: nlp.full_design(&s.x),
                objective: nlp.objective_at(&s.x, s.objective),
                feasible,
                solution: s,
                optimum: None,
                zone: None,
            }
        })
        .collect();
    let mut study = from_runs(problem, options, runs, interrupted, range);
    study.elapsed = begin.elapsed();
    study
}

/// The solution from `x0` of the last of `stages`, each a relaxation of the next: the
/// start solved in the first, its end taken on through the rest ([`staged::solve`] nested,
/// the stages before the last solved as one relaxation of it). An end that breaks a
/// constraint the stage before left out is taken on from its `mirror` image instead where
/// that meets them all (wei2017: 97 of 300 first stages end at the optimum's mirror image
/// whose output block meets the actuator, and went on to a worse optimum from there).
/// The whole problem's solves from the ends before are shared by the starts whose ends
/// round to one point ([`HandOvers`], one per stage): wei2017's 79 second stages from one
/// optimum of the relaxation are 4 solves.
fn in_stages(
    stages: &[&dyn OptimProblem],
    x0: &[f64],
    solve: &dyn Fn(&dyn OptimProblem, &[f64]) -> Solution,
    mirror: &dyn Fn(&[f64]) -> Option<Vec<f64>>,
    hand_overs: &[HandOvers],
) -> Solution {
    match stages {
        [] => unreachable!("a start is solved in one stage at least"),
        [whole] => solve(*whole, x0),
        [before @ .., whole] => staged::solve(
            *whole,
            x0,
            FEASIBILITY_TOLERANCE,
            |x| in_stages(before, x, solve, mirror, hand_overs),
            |p, x| {
                let (lower, upper) = p.bounds();
                hand_overs[before.len()].solve(x, lower, upper, |y| solve(p, y))
            },
            mirror,
        ),
    }
}

/// The study of the starts `range` from their runs (in the order of their starts; their
/// optimum and zone are set here): the clustering, the best run, the ends, the least
/// violating design and the mirror image, as [`run`] and [`merge`] conclude them; a shard
/// sent elsewhere is rebuilt by it from its runs. Its `elapsed` is zero, for the caller to
/// set.
pub fn from_runs(
    problem: &Problem,
    options: &StudyOptions,
    mut runs: Vec<Run>,
    interrupted: bool,
    range: Range<usize>,
) -> Study {
    let nlp = &DesignNlp::new(problem);
    for r in &mut runs {
        r.optimum = None;
        r.zone = None;
    }
    let tolerance = problem.search.tolerance;
    let max_iterations = problem.search.max_iterations;
    let feasible_runs: Vec<usize> = (0..runs.len()).filter(|&i| runs[i].feasible).collect();
    let points: Vec<EndPoint> = feasible_runs
        .iter()
        .map(|&i| EndPoint {
            x: runs[i].solution.x.clone(),
            objective: runs[i].objective,
        })
        .collect();
    let z = &problem.zones;
    let settings = ClusterSettings {
        x_tolerance: z.x_tolerance,
        objective_tolerance: z.objective_tolerance,
        maximize: problem.objective.sense == Sense::Maximize,
        thresholds: z.thresholds.clone(),
    };
    let mirror = |u: &[f64]| {
        if z.merge_mirror_images {
            nlp.mirror(u)
        } else {
            None
        }
    };
    let clustering = cluster(&points, &settings, &mirror);
    for (k, &i) in feasible_runs.iter().enumerate() {
        runs[i].optimum = Some(clustering.optimum_of[k]);
        runs[i].zone = Some(clustering.zone_of[k]);
    }
    let any_feasible = !feasible_runs.is_empty();
    // the optima are sorted best first and so are their members: the first converged
    // member is the best converged run
    let best_converged_run = clustering
        .optima
        .iter()
        .flat_map(|o| o.members.iter().map(|&k| feasible_runs[k]))
        .find(|&i| runs[i].solution.status == Status::Converged);
    let best = if let Some(i) = best_converged_run {
        i
    } else if any_feasible {
        feasible_runs[clustering.optima[0].representative]
    } else {
        // the least violating run that could be evaluated
        (0..runs.len())
            .filter(|&i| runs[i].objective.is_finite())
            .min_by(|&a, &b| {
                runs[a]
                    .solution
                    .max_violation
                    .total_cmp(&runs[b].solution.max_violation)
                    .then(a.cmp(&b))
            })
            .unwrap_or(0)
    };
    let ends = Ends::count(&runs);
    let least_violating = if any_feasible || interrupted || !options.explain_infeasible {
        None
    } else {
        let settings = SqpSettings {
            tolerance,
            max_iterations,
            ..SqpSettings::default()
        };
        let from: Vec<usize> = (0..runs.len())
            .filter(|&i| runs[i].solution.x.iter().all(|x| x.is_finite()))
            .collect();
        let ends: Vec<Vec<f64>> = from.iter().map(|&i| runs[i].solution.x.clone()).collect();
        least_violating::search(nlp, &ends, &settings, options.threads).map(|mut l| {
            l.from = runs[from[l.from]].start;
            l
        })
    };
    let mirrored = (any_feasible && z.merge_mirror_images)
        .then(|| preferred_mirror(problem, nlp, &runs[best]))
        .flatten();
    Study {
        least_violating,
        mirrored,
        best_converged: best_converged_run.is_some(),
        interrupted,
        ends,
        runs,
        clustering,
        feasible_runs,
        best,
        any_feasible,
        elapsed: Duration::ZERO,
        options: options.clone(),
        range,
    }
}
