//! The refinement of a study's optimum (or of each zone's best optimum) by the finite
//! elements, as `run` does it with `[refine]` or `--refine fe`.

use super::fe::{analysis_at, is_modal, FeFidelity};
use super::{refine, RefineStatus, Refinement};
use crate::problem::refine::RefineFrom;
use crate::problem::Problem;
use crate::study::Study;

/// Each refinement with the rank of the zone it started in, and the index of the one to
/// report: a converged feasible one first, then any feasible one, by objective; else the
/// least violating.
pub struct StudyRefinement {
    pub all: Vec<(usize, Refinement)>,
    pub chosen: usize,
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

/// Refines each design (with its zone's rank) and picks the one to report.
fn refine_designs(problem: &Problem, starts: Vec<(usize, Vec<f64>)>) -> StudyRefinement {
    let mechanism = problem.mechanism();
    let settings = &problem.refine;
    // the modes only when a frequency is asked: the part's check says which outputs are
    let analysis = starts.iter().find_map(|(_, x)| analysis_at(mechanism, x));
    let modal = analysis.is_some_and(|a| {
        problem
            .constraints
            .iter()
            .map(|c| c.index)
            .chain([problem.objective.index])
            .any(|o| is_modal(mechanism, &a, o))
    });
    let fe = FeFidelity::new(mechanism, settings, modal);
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
    StudyRefinement { all, chosen }
}
