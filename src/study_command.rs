//! The commands that run studies: `run` (with its refinement and FE check) and `pareto`,
//! and the options they share.

use std::path::Path;

use crate::args::StudyArgs;
use crate::failure::{emit, Failure};
use crate::verify_command::check_design;
use flexopt::fe::verify::VerifySettings;
use flexopt::pareto::{pareto, ParetoSpec};
use flexopt::part::{Part, PartError};
use flexopt::problem::{fit, Problem};
use flexopt::refine::study::refine_study;
use flexopt::report::html::ProblemText;
use flexopt::report::pareto::write_pareto;
use flexopt::report::refine::{RefineSummary, RefinedReport};
use flexopt::report::study::{write_all_refined, RefinedFiles};
use flexopt::report::summary::{infeasible_message, ParetoSummary, StudySummary};
use flexopt::report::verify::{VerifyReport, VerifyTable};
use flexopt::study::{self, Overrides, Study, StudyOptions};

/// Loads the problem and applies the command line's overrides of its `[search]`.
pub(crate) fn study_setup(
    path: &Path,
    args: &StudyArgs,
) -> Result<(Problem, StudyOptions), Failure> {
    let StudyArgs {
        starts,
        seed,
        threads,
        ..
    } = *args;
    let problem = crate::start_command::load_problem(path)?;
    let overrides = Overrides {
        starts: starts.map(|s| s as i128),
        seed: seed.map(i128::from),
        threads: threads.map(|t| t as i128),
        solver: args.solver.as_deref(),
    };
    let mut options = StudyOptions::with_overrides(&problem, &overrides, "--")
        .map_err(|e| Failure::bad_input(e.message))?;
    options.progress = !args.quiet;
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    if options.threads > cores {
        eprintln!(
            "warning: {}: {} threads on {cores} cores: the starts run no faster than with \
             {cores}, and many more threads than cores slow them down",
            problem.file.display(),
            options.threads
        );
    }
    Ok((problem, options))
}

pub(crate) fn run_pareto(
    problem: &Problem,
    spec: &ParetoSpec,
    options: &StudyOptions,
    dir: &Path,
) -> Result<(), Failure> {
    let front = pareto(problem, spec, options).map_err(Failure::bad_input)?;
    let files = write_pareto(dir, &front).map_err(Failure::write_failed)?;
    emit(&ParetoSummary {
        problem,
        front: &front,
        files: &files,
    })?;
    if front.points.iter().any(|p| p.feasible) {
        Ok(())
    } else {
        Err(Failure::no_feasible(format!(
            "{}: no limit of the range admits a feasible design",
            problem.file.display()
        )))
    }
}

pub(crate) fn run_study(
    problem: &Problem,
    options: &StudyOptions,
    dir: &Path,
    verify: bool,
    report: Option<&Option<ProblemText>>,
) -> Result<(), Failure> {
    // Ctrl-C stops the starts not yet begun; the finished ones are written, marked partial
    let stop = options.stop.clone();
    let _ = ctrlc::set_handler(move || stop.store(true, std::sync::atomic::Ordering::Relaxed));
    let study = study::run(problem, options);
    if study.interrupted && study.runs.is_empty() {
        return Err(Failure::interrupted(format!(
            "{}: interrupted before any start finished; nothing was written",
            problem.file.display()
        )));
    }
    if let Some(why) = unevaluated_optimum(problem, &study) {
        return Err(Failure::no_feasible(why));
    }
    let checks = fit::checks(problem, study.reported_design());
    for w in fit::warnings(problem, &checks) {
        eprintln!("warning: {}: {w}", problem.file.display());
    }
    // the optimum's part, for a feasible optimum of a model that has one; and the least
    // violating design's where it breaks a rule of the part the study keeps to: then the
    // part's sizes are what no start met, and its check names them (exit 5)
    let rule_broken = || {
        flexopt::problem::part_rules::enforced(problem).is_some()
            && flexopt::problem::part_rules::checks(problem, study.reported_design())
                .iter()
                .any(|r| !r.met)
    };
    let part = (study.any_feasible || (!study.interrupted && rule_broken()))
        .then(|| problem.mechanism().part(study.reported_design()))
        .flatten();
    warn_skipped_fe(problem, &study, part.as_ref(), verify);
    // the refinement by the finite elements, of a feasible optimum with a part
    let refined = (problem.refine.enabled && matches!(part, Some(Ok(_))) && !study.interrupted)
        .then(|| {
            if options.progress {
                eprintln!(
                    "refining the optimum against the finite elements of its part (at most {} \
                     FE checks)...",
                    problem.refine.max_fe
                );
            }
            let r = refine_study(problem, &study);
            let report = RefinedReport::new(problem, &problem.refine, &r);
            let design = r.all[r.chosen].1.result.as_ref().map(|c| c.x.clone());
            let part = design.and_then(|x| problem.mechanism().part(&x)?.ok());
            (report, part)
        });
    // the FE check of the optimum, before the set is written: its folder `verify/` is part
    // of the set, so that a later run without --verify leaves no check of another optimum
    let check = verify && study.any_feasible && !study.interrupted && matches!(part, Some(Ok(_)));
    let checked = check.then(|| {
        if options.progress {
            eprintln!("checking the optimum's part by finite elements...");
        }
        check_design(problem, study.reported_design(), &VerifySettings::default())
    });
    let verified = match &checked {
        Some(Ok((report, v))) => Some((report, v)),
        _ => None,
    };
    let files = write_all_refined(
        dir,
        problem,
        &study,
        part.as_ref(),
        refined.as_ref().map(|(report, part)| RefinedFiles {
            report,
            part: part.as_ref(),
        }),
        verified,
        report.map(Option::as_ref),
    )
    .map_err(Failure::write_failed)?;
    emit(&StudySummary {
        problem,
        study: &study,
        part: part.as_ref(),
        verdict: verified.map(|(report, _)| &report.verdict),
        files: &files,
    })?;
    if let Some((report, _)) = &refined {
        emit(&RefineSummary(report))?;
    }
    let checked = match checked {
        Some(Ok(c)) => Some(c),
        Some(Err(e)) => return Err(e),
        None => None,
    };
    if let Some((report, _)) = &checked {
        emit(&VerifyTable(report))?;
    }
    if problem.search.robust.is_some() && study.any_feasible && !study.interrupted {
        crate::tolerance_command::compare_robust(problem, options, &study, dir)?;
        // robust.json joins the set after it: the page is made again to show it
        if let Some(text) = report {
            flexopt::report::html::write_report(dir, text.as_ref())?;
        }
    }
    exit_status(
        problem,
        options,
        &study,
        part.as_ref(),
        refined.as_ref().map(|(r, _)| r),
        checked.as_ref().map(|(r, _)| r),
    )
}

/// The FE steps asked for (`[refine]`, `--verify`) and skipped, said whatever the exit code
/// says already.
fn warn_skipped_fe(
    problem: &Problem,
    study: &Study,
    part: Option<&Result<Part, PartError>>,
    verify: bool,
) {
    let Some(why) = no_fe_step(problem, study, part) else {
        return;
    };
    if problem.refine.enabled {
        eprintln!(
            "warning: {}: the optimum is not refined against finite elements: {why}",
            problem.file.display()
        );
    }
    if verify {
        eprintln!(
            "warning: {}: --verify: the optimum's part is not checked by finite elements: \
             {why}",
            problem.file.display()
        );
    }
}

/// What the run ends with, the first that holds: interrupted; feasible but not converged
/// (4); no makeable end, or an optimum whose part cannot be made (5); a refinement that did
/// not converge or found nothing feasible on the part (4, 3); the part failing a limit by
/// the FE check (3); no feasible design (3); else success.
fn exit_status(
    problem: &Problem,
    options: &StudyOptions,
    study: &Study,
    part: Option<&Result<Part, PartError>>,
    refined: Option<&RefinedReport>,
    checked: Option<&VerifyReport>,
) -> Result<(), Failure> {
    if study.interrupted {
        Err(Failure::interrupted(format!(
            "{}: interrupted: {} of {} starts finished; the files written hold those \
             (\"partial\": true in optimum.json)",
            problem.file.display(),
            study.runs.len(),
            options.starts
        )))
    } else if study.any_feasible && !study.best_converged {
        Err(Failure {
            code: 4,
            message: format!(
                "{}: no feasible start converged; optimum.json holds the best feasible design, \
                 unconverged (\"converged\": false): raise search.max_iterations or check the \
                 tolerance",
                problem.file.display()
            ),
        })
    } else if let (false, Some(Err(e))) = (study.any_feasible, part) {
        Err(Failure::cannot_be_made(format!(
            "{}: no start ended at a design whose part can be made with the [part] sizes; \
             optimum.json holds the least violating one, whose part breaks the rules the \
             study keeps to: {e}",
            problem.file.display()
        )))
    } else if let Some(Err(e)) = part {
        Err(Failure::cannot_be_made(format!(
            "{}: the optimum gives no part that can be made with the [part] sizes: {e}; its \
             analytic results are written, its part files are not (optimum.json: \
             part_problems)",
            problem.file.display()
        )))
    } else if let Some(r) = refined.filter(|r| !r.converged || !r.feasible) {
        let what = if r.feasible {
            (
                4,
                "the refinement stopped at its budget of FE checks with a design that meets \
                 every constraint as measured (refined.json), before it converged (raise \
                 [refine] max_fe or --max-fe)",
            )
        } else {
            (
                3,
                "the refinement found no design that meets every constraint as measured by \
                 the finite elements; refined.json holds the least violating one",
            )
        };
        Err(Failure {
            code: what.0,
            message: format!("{}: {}", problem.file.display(), what.1),
        })
    } else if let Some(report) = checked.filter(|_| study.any_feasible) {
        part_verdict(problem, report)
    } else if study.any_feasible {
        Ok(())
    } else {
        Err(Failure::no_feasible(infeasible_message(problem, study)))
    }
}

/// Exit 3 when the FE check of the optimum (`--verify`) finds its part failing a limit the
/// model met: the verdict is the highest fidelity's.
fn part_verdict(problem: &Problem, report: &VerifyReport) -> Result<(), Failure> {
    let fails = &report.verdict.fails;
    if fails.is_empty() {
        return Ok(());
    }
    let shown: Vec<&str> = fails.iter().map(|f| f.shown.as_str()).collect();
    Err(Failure::no_feasible(format!(
        "{}: the optimum meets every constraint in the model, but its part fails by the {} \
         finite elements: {}",
        problem.file.display(),
        report.verdict.fidelity.name(),
        shown.join("; ")
    )))
}

/// Why the feasible starts' best design is no optimum: the model gives no value there for an
/// output the report reads (the objective, a constraint), which the study's own outputs did
/// not show. Said before anything is written, so that no set holds an optimum that "ended
/// feasible" and reads infeasible.
fn unevaluated_optimum(problem: &Problem, study: &Study) -> Option<String> {
    if !study.any_feasible || study.interrupted {
        return None;
    }
    let x = study.reported_design();
    let report = flexopt::report::DesignReport::new(problem, x);
    let mut missing: Vec<&str> = report
        .constraints
        .iter()
        .filter(|c| c.value.is_none())
        .map(|c| c.output.as_str())
        .collect();
    if report.objective.is_none() {
        missing.insert(0, problem.objective.output.as_str());
    }
    if missing.is_empty() {
        return None;
    }
    let why = problem
        .model()
        .domain_error(x)
        .unwrap_or_else(|| "the model gives no finite number there".into());
    Some(format!(
        "{}: the starts ended feasible, but at their best design {} has no value: {why}; \
         nothing was written",
        problem.file.display(),
        missing.join(", ")
    ))
}

/// Why the optimum gets no finite-element step (`--verify`, `--refine fe`), if it gets none.
fn no_fe_step(
    problem: &Problem,
    study: &Study,
    part: Option<&Result<Part, PartError>>,
) -> Option<String> {
    if study.interrupted {
        Some("the run was interrupted".into())
    } else if !study.any_feasible {
        Some("no start ended feasible, so there is no optimum to check (exit code 3)".into())
    } else {
        match part {
            None => Some(format!("the {} model has no part", problem.model().name())),
            Some(Err(_)) => Some("the optimum gives no part that can be made (exit code 5)".into()),
            Some(Ok(_)) => None,
        }
    }
}
