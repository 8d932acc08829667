//! What the command line prints after a study or a front: summaries as [`Display`].

use std::fmt::{self, Display};
use std::path::PathBuf;

use crate::pareto::Pareto;
use crate::part::{Part, PartError};
use crate::problem::nlp::ACTIVE_TOLERANCE;
use crate::problem::{Problem, Solver};
use crate::report::verify::Verdict;
use crate::study::Study;

/// The summary of a study: starts, the best design and the zones, then the files written.
pub struct StudySummary<'a> {
    pub problem: &'a Problem,
    pub study: &'a Study,
    /// The optimum's part, where the model has one and the optimum is feasible.
    pub part: Option<&'a Result<Part, PartError>>,
    /// The verdict of the optimum's FE check (`run --verify`), where it ran.
    pub verdict: Option<&'a Verdict>,
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
        let x = study.reported_design();
        let unit = super::display::output_unit(problem, problem.objective.index);
        let configuration = match problem.depiction().configuration(x) {
            "-" => String::new(),
            c => format!(" ({c} configuration)"),
        };
        writeln!(
            s,
            "{label} {} = {}{configuration}",
            problem.objective.output,
            super::display::with_unit(study.reported_objective(), &unit),
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
        writeln!(s, "  design {}", super::display::design_line(problem, x))?;
        let report = super::DesignReport::new(problem, x);
        if !report.constraints.is_empty() {
            write!(s, "{}", super::table::ConstraintLines(&report.constraints))?;
            // the part's rules the optimum stands on are named beside the constraints
            let active: Vec<String> = report
                .constraints
                .iter()
                .filter(|c| c.active)
                .map(|c| c.output.clone())
                .chain(
                    report
                        .part_rules
                        .iter()
                        .filter(|r| r.active)
                        .map(|r| format!("part rule {} ({})", r.rule, r.description)),
                )
                .collect();
            // a robust optimum stands on its limits tightened by k spreads
            let at = match problem.search.robust {
                Some(r)
                    if report
                        .constraints
                        .iter()
                        .any(|c| c.margin_in_sigma.is_some()) =>
                {
                    format!(" ({:.3} first-order standard deviations inside)", r.k_sigma)
                }
                _ => String::new(),
            };
            writeln!(
                s,
                "  active{at}: {}",
                if active.is_empty() {
                    "none".to_string()
                } else {
                    active.join(", ")
                }
            )?;
        }
        if study.any_feasible {
            writeln!(s, "  {}", judged_by(self.verdict))?;
        }
        // the ranges of fit the design reaches or leaves; the others say nothing
        let at_edge: Vec<_> = report
            .fit_ranges
            .iter()
            .filter(|c| {
                let near = |b: Option<f64>| {
                    b.is_some_and(|b| (c.value - b).abs() <= ACTIVE_TOLERANCE * b.abs())
                };
                !c.inside || near(c.lower) || near(c.upper)
            })
            .cloned()
            .collect();
        if !at_edge.is_empty() {
            write!(s, "{}", super::table::FitLines(&at_edge))?;
        }
        writeln!(s, "zone  starts  optima  best        worst")?;
        for z in &study.clustering.zones {
            let f = |v: f64| format!("{:<10}", super::display::human(unit.from_si(v)));
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
        let unit_of = |name: &str| {
            self.problem
                .model()
                .output_index(name)
                .map(|i| super::display::output_unit(self.problem, i).name)
                .filter(|u| u != "1")
                .map_or(String::new(), |u| format!(" ({u})"))
        };
        let head = [
            format!("limit ({})", front.unit),
            format!("{}{}", front.objective, unit_of(&front.objective)),
            format!("{} ({})", front.output, front.unit),
            "active".to_string(),
            "front".to_string(),
        ];
        let objective_unit = self
            .problem
            .model()
            .output_index(&front.objective)
            .map(|i| super::display::output_unit(self.problem, i));
        let human = super::display::human;
        let rows: Vec<[String; 5]> = front
            .points
            .iter()
            .map(|p| {
                let objective = p.objective.map_or("infeasible".to_string(), |v| {
                    human(objective_unit.as_ref().map_or(v, |u| u.from_si(v)))
                });
                let front_mark = match (p.on_front, p.same_as) {
                    (true, Some(first)) => format!("same as {}", human(first)),
                    (true, None) => "yes".to_string(),
                    (false, _) => String::new(),
                };
                [
                    human(p.limit),
                    objective,
                    p.value.map_or("-".to_string(), human),
                    if p.active { "yes" } else { "" }.to_string(),
                    front_mark,
                ]
            })
            .collect();
        let width: Vec<usize> = (0..5)
            .map(|k| {
                rows.iter()
                    .map(|r| r[k].len())
                    .chain([head[k].len()])
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        let line = |s: &mut fmt::Formatter<'_>, r: &[String; 5]| {
            writeln!(
                s,
                "{:>w0$}  {:>w1$}  {:>w2$}  {:<w3$}  {}",
                r[0],
                r[1],
                r[2],
                r[3],
                r[4],
                w0 = width[0],
                w1 = width[1],
                w2 = width[2],
                w3 = width[3]
            )
        };
        line(s, &head)?;
        for r in &rows {
            line(s, r)?;
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

/// Which fidelity the optimum's constraints are judged by: the model's alone, or its part's
/// FE check where `run --verify` ran, with what the part fails.
fn judged_by(verdict: Option<&Verdict>) -> String {
    let Some(v) = verdict else {
        // the model: a closed form, a network's matrices, or its solve at the stroke
        return "judged by the model; --verify checks its part by finite elements".into();
    };
    let mut line = match v.fails.as_slice() {
        [] => format!(
            "judged by the part's {} FE: it meets every constraint the FE measures",
            v.fidelity.name()
        ),
        fails => format!(
            "judged by the part's {} FE: the part FAILS {}",
            v.fidelity.name(),
            fails
                .iter()
                .map(|f| f.shown.as_str())
                .collect::<Vec<_>>()
                .join("; ")
        ),
    };
    if !v.model_only.is_empty() {
        line += &format!("; by the model only: {}", v.model_only.join(", "));
    }
    line
}
