//! What the command line prints after a study or a front: summaries as [`Display`].

use std::fmt::{self, Display};
use std::path::PathBuf;

use crate::pareto::Pareto;
use crate::part::{Part, PartError};
use crate::problem::{Problem, Solver};
use crate::study::Study;

/// The summary of a study: starts, the best design and the zones, then the files written.
pub struct StudySummary<'a> {
    pub problem: &'a Problem,
    pub study: &'a Study,
    /// The optimum's part, where the model has one and the optimum is feasible.
    pub part: Option<&'a Result<Part, PartError>>,
    pub files: &'a [PathBuf],
}

impl Display for StudySummary<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (problem, study) = (self.problem, self.study);
        let solver = match study.options.solver {
            Solver::Sqp => "SQP",
            Solver::NelderMead => "Nelder-Mead",
        };
        writeln!(
            s,
            "{}: {} starts with {solver}, seed {}, in {:.1} ms; {} ended feasible",
            problem.name,
            study.runs.len(),
            study.options.seed,
            study.elapsed.as_secs_f64() * 1e3,
            study.feasible_runs.len()
        )?;
        if study.interrupted {
            writeln!(
                s,
                "INTERRUPTED: only the starts that finished are counted and written"
            )?;
        }
        let e = &study.ends;
        writeln!(
            s,
            "ends: {} converged, {} at the iteration limit, {} infeasible, {} failed",
            e.converged, e.iteration_limit, e.infeasible, e.failed
        )?;
        let label = match (study.any_feasible, study.best_converged) {
            (true, true) => "best",
            (true, false) => "best (NOT CONVERGED: no feasible start converged)",
            (false, _) => "least violating (infeasible)",
        };
        writeln!(
            s,
            "{label} {} = {:.6} ({})",
            problem.objective.output,
            study.reported_objective(),
            problem.model().configuration(study.reported_design())
        )?;
        if let Some(l) = &study.least_violating {
            let names: Vec<&str> = l
                .unmet
                .iter()
                .map(|&k| problem.constraints[k].output.as_str())
                .collect();
            writeln!(
                s,
                "  cannot be met with the other constraints: {}",
                names.join(", ")
            )?;
        }
        let design: Vec<String> = problem
            .variables
            .iter()
            .zip(study.reported_design())
            .map(|(v, &x)| format!("{}={:.6}", v.name, v.unit.from_si(x)))
            .collect();
        writeln!(s, "  design {}", design.join(","))?;
        writeln!(s, "zone  starts  optima  best        worst")?;
        for z in &study.clustering.zones {
            let f = |v: f64| {
                if v.is_finite() {
                    format!("{v:<10.6}")
                } else {
                    format!("{:<10}", "-")
                }
            };
            writeln!(
                s,
                "{:<5} {:<7} {:<7} {}  {}",
                z.rank,
                z.count,
                z.optima.len(),
                f(z.best),
                f(z.worst)
            )?;
        }
        match self.part {
            Some(Ok(part)) => {
                for w in &part.warnings {
                    writeln!(s, "part: warning: {w}")?;
                }
            }
            Some(Err(e)) => {
                writeln!(s, "part: the optimum gives no part that can be made:")?;
                for p in &e.problems {
                    writeln!(s, "  - {p}")?;
                }
            }
            None => {}
        }
        let missing = study.runs.len() - study.feasible_runs.len();
        if missing > 0 {
            writeln!(
                s,
                "{missing} starts did not end at a feasible design (see starts.json)"
            )?;
        }
        wrote(s, self.files)
    }
}

/// The table of a trade-off front, then the files written.
pub struct ParetoSummary<'a> {
    pub problem: &'a Problem,
    pub front: &'a Pareto,
    pub files: &'a [PathBuf],
}

impl Display for ParetoSummary<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        let front = self.front;
        writeln!(
            s,
            "{}: {} limits on {} x {} starts in {:.1} ms",
            self.problem.name,
            front.points.len(),
            front.output,
            front.starts,
            front.elapsed.as_secs_f64() * 1e3
        )?;
        writeln!(
            s,
            "{:>12}  {:>12}  {:>12}  active  front",
            format!("limit ({})", front.unit),
            front.objective,
            front.output
        )?;
        for p in &front.points {
            let show = |v: Option<f64>| v.map_or("infeasible".to_string(), |v| format!("{v:.6}"));
            writeln!(
                s,
                "{:>12}  {:>12}  {:>12}  {:<6}  {}",
                format!("{:.6}", p.limit),
                show(p.objective),
                show(p.value),
                if p.active { "yes" } else { "no" },
                if p.on_front { "yes" } else { "no" }
            )?;
        }
        wrote(s, self.files)
    }
}

/// The files written, one line each.
pub struct Wrote<'a>(pub &'a [PathBuf]);

impl Display for Wrote<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        wrote(s, self.0)
    }
}

fn wrote(s: &mut fmt::Formatter<'_>, files: &[PathBuf]) -> fmt::Result {
    for f in files {
        writeln!(s, "wrote {}", f.display())?;
    }
    Ok(())
}

/// What a run without a feasible start tells: the constraints that cannot be met with the
/// others, where the least violating design leaves them and what they ask.
pub fn infeasible_message(problem: &Problem, study: &Study) -> String {
    let head = format!(
        "{}: no start ended at a feasible design",
        problem.file.display()
    );
    let Some(l) = &study.least_violating else {
        return format!("{head}; optimum.json holds the least violating one");
    };
    let report = super::DesignReport::new(problem, &l.x);
    let unmet: Vec<String> = l
        .unmet
        .iter()
        .filter_map(|&k| report.constraints.get(k))
        .map(|c| {
            // six significant digits, as a designer reads them
            let show = |v: Option<f64>| {
                v.map_or("-".to_string(), |v| {
                    crate::problem::units::short(format!("{v:.5e}").parse().unwrap_or(v))
                })
            };
            let u = if c.unit == "1" {
                String::new()
            } else {
                format!(" {}", c.unit)
            };
            let wanted = match (c.lower, c.upper) {
                (Some(_), Some(_)) => format!("between {} and {}", show(c.lower), show(c.upper)),
                (Some(_), None) => format!(">= {}", show(c.lower)),
                _ => format!("<= {}", show(c.upper)),
            };
            format!("{} = {}{u} (wanted {wanted}{u})", c.output, show(c.value))
        })
        .collect();
    format!(
        "{head}; no start met {} together with the other constraints: {}. optimum.json holds \
         the design that meets the others and violates these least",
        if unmet.len() == 1 {
            "this one"
        } else {
            "these"
        },
        unmet.join("; ")
    )
}
