//! The refinement of a study's optimum (or of each zone's best optimum) by the finite
//! elements, as `run` does it with `[refine]` or `--refine fe`.

use super::fe::{analysis_at, is_modal, FeFidelity};
use super::spread::{measure_spread, FeSpread, SpreadSettings};
use super::{refine, RefineStatus, Refinement};
use crate::problem::refine::RefineFrom;
use crate::problem::Problem;
use crate::study::Study;
use crate::tolerance::analyze;
use crate::tolerance::monte_carlo::Settings;

/// Each refinement with the rank of the zone it started in, and the index of the one to
/// report: a converged feasible one first, then any feasible one, by objective; else the
/// least violating.
pub struct StudyRefinement {
    pub all: Vec<(usize, Refinement)>,
    pub chosen: usize,
    /// A robust problem's refined design (feasible as measured) under the tolerances: the
    /// FE's spread on [`ROBUST_SPREAD_SAMPLES`] samples, or why it could not be measured.
    pub spread: Option<Result<FeSpread, String>>,
}

/// The samples of the analytic Monte Carlo a robust refinement's design is checked on by FE
/// ([`super::spread`]): each is an FE check of a few seconds in 3D; eight give each
/// output's FE spread within a few per cent through the model's deviations (the
/// regression's standard error, `beta_error`, says how well).
pub const ROBUST_SPREAD_SAMPLES: usize = 8;

/// The analytic Monte Carlo's samples the FE's spread is mapped onto for the part's yield.
pub const ROBUST_YIELD_SAMPLES: usize = 100_000;

/// The FE spread of a robust problem's refined design `x`.
fn robust_spread(problem: &Problem, x: &[f64]) -> Result<FeSpread, String> {
    let settings = Settings {
        samples: ROBUST_YIELD_SAMPLES,
        seed: problem.search.seed,
        threads: problem.search.threads,
    };
    let analysis = analyze(problem, x, settings)?;
    let high = spread_fidelity(problem, x);
    let spread_settings = SpreadSettings {
        samples: ROBUST_SPREAD_SAMPLES,
        seed: problem.search.seed,
        threads: problem.search.threads,
    };
    measure_spread(problem, x, &analysis, &high, spread_settings).map_err(|e| e.to_string())
}

/// The designs to refine: the study's reported optimum, or the best optimum of each zone
/// (the reported one for its own zone), each with its zone's rank.
fn starts(problem: &Problem, study: &Study) -> Vec<(usize, Vec<f64>)> {
    let best_zone = study.runs[study.best].zone.unwrap_or(0);
    let reported = (best_zone, study.reported_design().to_vec());
    if problem.refine.from == RefineFrom::Optimum {
        return vec![reported];
    }
    let c = &study.clustering;
    let mut out = Vec::new();
    for z in &c.zones {
        let Some(&first) = z.optima.first() else {
            continue;
        };
        if z.rank == best_zone {
            out.push(reported.clone());
        } else {
            let run = study.feasible_runs[c.optima[first].representative];
            out.push((z.rank, study.runs[run].x_end.clone()));
        }
    }
    out
}

/// Refines the optimum (or each zone's) of a feasible `study`.
pub fn refine_study(problem: &Problem, study: &Study) -> StudyRefinement {
    refine_designs(problem, starts(problem, study))
}

/// Refines one design `x` (SI, every parameter), as `run` refines a study's optimum.
pub fn refine_design(problem: &Problem, x: &[f64]) -> StudyRefinement {
    refine_designs(problem, vec![(0, x.to_vec())])
}

/// The FE check the problem's `[refine]` asks for at designs like those of `xs` (SI): the
/// modes only when a frequency is asked, which the part's check at the first design that
/// has a part says.
pub fn fe_fidelity<'p>(problem: &'p Problem, xs: &[&[f64]]) -> FeFidelity<'p> {
    let mechanism = problem.mechanism();
    let analysis = xs.iter().find_map(|x| analysis_at(mechanism, x));
    let modal = analysis.is_some_and(|a| {
        problem
            .constraints
            .iter()
            .map(|c| c.index)
            .chain([problem.objective.index])
            .any(|o| is_modal(mechanism, &a, o))
    });
    FeFidelity::new(mechanism, &problem.refine, modal)
}

/// The FE check of a spread's samples at designs near `x`: the refinement's, without the
/// 3D check where the file's `[refine] idealization` is a 2D one (the refinement takes the
/// 3D check for its margins, which a spread does not need).
pub fn spread_fidelity<'p>(problem: &'p Problem, x: &[f64]) -> FeFidelity<'p> {
    let mut fe = fe_fidelity(problem, &[x]);
    fe.settings.solid = fe
        .idealization
        .is_none_or(|f| f == crate::fe::Fidelity::Solid);
    fe
}

/// Refines each design (with its zone's rank) and picks the one to report.
fn refine_designs(problem: &Problem, starts: Vec<(usize, Vec<f64>)>) -> StudyRefinement {
    let settings = &problem.refine;
    let xs: Vec<&[f64]> = starts.iter().map(|(_, x)| x.as_slice()).collect();
    let fe = fe_fidelity(problem, &xs);
    let all: Vec<(usize, Refinement)> = starts
        .into_iter()
        .map(|(zone, x)| (zone, refine(problem, &x, &fe, settings)))
        .collect();
    let rank = |r: &Refinement| -> (u8, f64) {
        let Some(c) = &r.result else {
            return (3, f64::INFINITY);
        };
        let o = &problem.objective;
        let objective = crate::problem::nlp::merit(o.sense, false, c.objective);
        match (c.feasible, r.status == RefineStatus::Converged) {
            (true, true) => (0, objective),
            (true, false) => (1, objective),
            _ => (2, c.violations.iter().sum()),
        }
    };
    let chosen = (0..all.len())
        .min_by(|&a, &b| {
            let (ra, rb) = (rank(&all[a].1), rank(&all[b].1));
            ra.0.cmp(&rb.0).then(ra.1.total_cmp(&rb.1))
        })
        .unwrap_or(0);
    let spread = all[chosen]
        .1
        .result
        .as_ref()
        .filter(|c| c.feasible && problem.search.robust.is_some())
        .map(|c| robust_spread(problem, &c.x));
    StudyRefinement {
        all,
        chosen,
        spread,
    }
}
