//! The least violating design of a problem no start could satisfy, and the constraints that
//! cannot be met.
//!
//! A local solve that cannot reach the feasible set stops where its largest violation is
//! smallest, which spreads the violation over every constraint it trades against, feasible
//! ones included, and names none. Here, from the ends of the study's solves:
//!
//! 1. the l1 elastic problem ([`crate::problem::elastic`]) with every constraint elastic: the
//!    constraints it leaves violated are the candidates;
//! 2. each candidate in turn, smallest violation first, is tried alone against the ones kept
//!    so far (those hard, the other candidates dropped); one that can then be met joins them.
//!    This is the elastic filter's deletion pass of Chinneck (2008, ch. 6) turned around: it
//!    keeps every constraint that can be met with the ones before it, and the rest form the
//!    set that cannot be met together with those;
//! 3. the l1 problem with the kept constraints hard and the rest elastic gives the least
//!    violation of the rest;
//! 4. with those violations allowed and nothing more, the design's own objective is improved.
//!
//! Every step runs from every end, on the study's threads, and keeps the best by a fixed
//! order (value, then start), so the result does not depend on the thread count. The
//! problem is not convex: "cannot be met" means no start of this study met it.

use crate::optim::multistart;
use crate::optim::sqp::{self, SqpSettings};
use crate::optim::{Problem as _, Solution};
use crate::problem::elastic::{Elastic, Goal, Treatment};
use crate::problem::nlp::{feasible_end, DesignNlp, FEASIBILITY_TOLERANCE};

/// The outcome of the search.
#[derive(Debug, Clone)]
pub struct LeastViolating {
    /// The design, scaled as the solvers see it, and as the model's full parameter vector
    /// in SI.
    pub u: Vec<f64>,
    pub x: Vec<f64>,
    /// The objective there, as the problem states it.
    pub objective: f64,
    /// The constraints (indices into the problem's) that no start met together with the
    /// others.
    pub unmet: Vec<usize>,
    /// The index of the end the design came from.
    pub from: usize,
    /// The last solve: in elastic form, its status and counts.
    pub solution: Solution,
}

/// One step: the best elastic solve from every end.
struct Best {
    v: Vec<f64>,
    from: usize,
    solution: Solution,
}

fn best_of(
    elastic: &Elastic,
    ends: &[Vec<f64>],
    settings: &SqpSettings,
    threads: usize,
) -> Option<Best> {
    let starts: Vec<Vec<f64>> = ends.iter().map(|u| elastic.start(u)).collect();
    let solutions = multistart::run(
        elastic,
        &starts,
        |p, x0| sqp::solve(p, x0, settings),
        threads,
        None,
    );
    solutions
        .into_iter()
        .enumerate()
        .filter(|(_, s)| feasible_end(s))
        .min_by(|(a, sa), (b, sb)| sa.objective.total_cmp(&sb.objective).then(a.cmp(b)))
        .map(|(from, solution)| Best {
            v: solution.x.clone(),
            from,
            solution,
        })
}

/// Searches from the scaled ends `ends` of a study's solves; `None` when no elastic solve
/// could be evaluated (every end outside the model's domain).
pub fn search(
    nlp: &DesignNlp,
    ends: &[Vec<f64>],
    settings: &SqpSettings,
    threads: usize,
) -> Option<LeastViolating> {
    let mut found = search_scaled(nlp, ends, settings, threads)?;
    let mut c = vec![0.0; nlp.constraint_count()];
    found.objective = nlp.stated_objective(nlp.evaluate(&found.u, &mut c));
    found.x = nlp.full_design(&found.u);
    Some(found)
}

fn search_scaled(
    nlp: &DesignNlp,
    ends: &[Vec<f64>],
    settings: &SqpSettings,
    threads: usize,
) -> Option<LeastViolating> {
    let n = nlp.dimension();
    let count = nlp.problem.constraints.len();
    let violated = |e: &Elastic, b: &Best| -> Vec<(usize, f64)> {
        (0..count)
            .filter_map(|k| Some((k, e.slack(&b.v, k)?)))
            .filter(|&(_, s)| s > FEASIBILITY_TOLERANCE)
            .collect()
    };

    // 1. every constraint elastic
    let all = Elastic::new(nlp, &vec![Treatment::Elastic; count], Goal::Violation);
    let first = best_of(&all, ends, settings, threads)?;
    let mut candidates = violated(&all, &first);
    candidates.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
    let mut hard: Vec<bool> = vec![true; count];
    for &(k, _) in &candidates {
        hard[k] = false;
    }

    // 2. each candidate against the constraints kept so far
    let mut ends_now: Vec<Vec<f64>> = ends.to_vec();
    ends_now.push(first.v[..n].to_vec());
    for &(k, _) in &candidates {
        let treatment: Vec<Treatment> = (0..count)
            .map(|j| match (j == k, hard[j]) {
                (true, _) => Treatment::Elastic,
                (false, true) => Treatment::Hard,
                (false, false) => Treatment::Dropped,
            })
            .collect();
        let alone = Elastic::new(nlp, &treatment, Goal::Violation);
        if let Some(b) = best_of(&alone, &ends_now, settings, threads) {
            if b.solution.objective <= FEASIBILITY_TOLERANCE {
                hard[k] = true;
            }
        }
    }
    let unmet: Vec<usize> = (0..count).filter(|&k| !hard[k]).collect();

    // 3. the least violation of the rest, the kept ones hard
    let treatment: Vec<Treatment> = hard
        .iter()
        .map(|&h| {
            if h {
                Treatment::Hard
            } else {
                Treatment::Elastic
            }
        })
        .collect();
    let rest = Elastic::new(nlp, &treatment, Goal::Violation);
    let least = match best_of(&rest, &ends_now, settings, threads) {
        Some(b) => b,
        // no end met the kept ones all at once: the first step's design is the answer
        None => {
            return Some(LeastViolating {
                x: Vec::new(),
                objective: f64::NAN,
                u: first.v[..n].to_vec(),
                unmet: candidates.iter().map(|c| c.0).collect(),
                from: first.from,
                solution: first.solution,
            })
        }
    };

    // 4. the objective, within the violations reached (and 1e-12 more, for the rounding of
    //    the start's rows)
    let slacks = rest.slacks(&least.v).to_vec();
    let mut next = slacks.iter();
    let relaxed: Vec<Treatment> = treatment
        .iter()
        .map(|t| match t {
            Treatment::Elastic => {
                let s = next.next().copied().unwrap_or(0.0);
                Treatment::Relaxed(s + 1e-12)
            }
            other => *other,
        })
        .collect();
    let improve = Elastic::new(nlp, &relaxed, Goal::Objective);
    let u_least = least.v[..n].to_vec();
    let improved = sqp::solve(&improve, &u_least, settings);
    let mut c = vec![0.0; improve.constraint_count()];
    let merit_least = improve.evaluate(&u_least, &mut c);
    let better = feasible_end(&improved) && improved.objective <= merit_least;
    // the last end is the first step's design
    let from = if least.from < ends.len() {
        least.from
    } else {
        first.from
    };
    Some(if better {
        LeastViolating {
            x: Vec::new(),
            objective: f64::NAN,
            u: improved.x[..n].to_vec(),
            unmet,
            from,
            solution: improved,
        }
    } else {
        LeastViolating {
            x: Vec::new(),
            objective: f64::NAN,
            u: u_least,
            unmet,
            from,
            solution: least.solution,
        }
    })
}
