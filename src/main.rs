//! The `flexopt` command line: parse, call the library, print.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;

mod args;
mod failure;
mod start_command;
mod stroke_command;
mod study_command;
mod tolerance_command;
mod verify_command;
use args::{Cli, Command, DesignArgs, StudyArgs};
use failure::{emit, print_json, Failure};
use start_command::load_problem;
use study_command::{run_pareto, run_study, study_setup};
use verify_command::{run_verify, verify_settings};

use flexopt::model::hinge::calculator;
use flexopt::pareto::ParetoSpec;
use flexopt::problem::design::{default_design, design_from_optimum, parse_around, parse_design};
use flexopt::problem::refine::FIDELITIES;
use flexopt::problem::{fit, Problem};
use flexopt::report::html::{write_report, ProblemText};
use flexopt::report::part::write_part_set;
use flexopt::report::summary::Wrote;
use flexopt::report::sweep::write_sweep;
use flexopt::report::table::DesignTable;
use flexopt::report::{check_writable, DesignReport};
use flexopt::sweep::{sweep, SweepSpec};

fn main() -> ExitCode {
    // past `ulimit -f` a write fails with EFBIG, which each writer reports naming its file
    // (exit 1), rather than the signal's silent death
    // SAFETY: at start-up, before any thread; SIG_IGN installs no handler
    #[cfg(unix)]
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
    match dispatch(Cli::parse().command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            // exit 4: feasible designs, written, that did not converge: no error
            let label = if f.code == 4 { "stopped" } else { "error" };
            eprintln!("{label}: {}", f.message);
            ExitCode::from(f.code)
        }
    }
}

fn dispatch(command: Command) -> Result<(), Failure> {
    match command {
        Command::Init {
            model,
            hinge,
            material,
            file,
            force,
        } => start_command::init(
            &model,
            hinge.as_deref(),
            material.as_deref(),
            file.as_deref(),
            force,
        ),
        Command::Schema => start_command::schema(),
        Command::Completions { shell } => start_command::completions(shell),
        Command::Outputs { problem, model } => start_command::outputs(&model, problem.as_deref()),
        Command::Eval {
            problem,
            design,
            format,
        } => eval(&problem, &design, format.as_deref()),
        Command::Export {
            problem,
            design,
            out,
        } => export(&problem, &design, out),
        Command::Hinge {
            kind,
            dimensions,
            width,
            material,
            stress_limit,
            format,
        } => hinge(
            &kind,
            &dimensions.given,
            width,
            &material,
            stress_limit,
            format.as_deref(),
        ),
        Command::Verify {
            problem,
            design,
            out,
            tolerance,
            max_dofs,
            no_3d,
        } => verify(&problem, &design, out, tolerance, max_dofs, no_3d),
        Command::Sweep {
            problem,
            param,
            from,
            to,
            steps,
            around,
            optimum,
            outputs,
            out,
        } => {
            let spec = SweepSpec {
                variable: param,
                from,
                to,
                steps,
                outputs,
            };
            let base = Base {
                around: around.as_deref(),
                optimum: optimum.as_deref(),
            };
            run_sweep(&problem, &spec, base, out)
        }
        Command::Run {
            problem,
            study,
            verify,
            refine,
            max_fe,
            report,
        } => run(&problem, study, verify, refine, max_fe, report),
        Command::Report { dir, problem } => report(&dir, problem.as_deref()),
        Command::Tolerance {
            problem,
            design,
            samples,
            seed,
            threads,
            out,
            fe,
            fe_samples,
        } => {
            let fe_samples = fe.then_some(fe_samples);
            tolerance(&problem, &design, samples, seed, threads, out, fe_samples)
        }
        Command::Pareto {
            problem,
            vary,
            from,
            to,
            steps,
            study,
        } => {
            let spec = ParetoSpec {
                output: vary,
                from,
                to,
                steps,
            };
            pareto(&problem, spec, &study)
        }
        Command::Stroke(args) => {
            let (problem, x) = chosen_design(&args.problem, &args.design)?;
            stroke_command::run(&problem, &x, &args)
        }
    }
}

/// `flexopt verify`: the chosen design's part checked by finite elements, at the
/// discretization error `tolerance` within `max_dofs`, in 3D too unless `no_3d`.
fn verify(
    path: &Path,
    design: &DesignArgs,
    out: Option<PathBuf>,
    tolerance: Option<f64>,
    max_dofs: Option<usize>,
    no_3d: bool,
) -> Result<(), Failure> {
    let (problem, x) = chosen_design(path, design)?;
    let mut settings = verify_settings(path, tolerance, max_dofs)?;
    settings.solid = !no_3d;
    let dir = out.unwrap_or_else(|| problem.default_output_dir().join("verify"));
    check_writable(&dir).map_err(|e| Failure::bad_input(format!("key `--out`: {e}")))?;
    run_verify(&problem, &x, &settings, &dir)
}

/// `flexopt run`: the study, its optimum refined against the fidelity `refine` names within
/// `max_fe` checks where asked, checked by FE where `verify`, with its report where `report`.
fn run(
    path: &Path,
    study: StudyArgs,
    verify: bool,
    refine: Option<String>,
    max_fe: Option<i64>,
    report: bool,
) -> Result<(), Failure> {
    let (mut problem, options) = study_setup(path, &study)?;
    if let Some(r) = refine {
        problem.refine.enabled = FIDELITIES.get(&r).unwrap_or(false);
    }
    if let Some(n) = max_fe {
        let (lo, hi) = flexopt::problem::refine::MAX_FE;
        if !(lo..=hi).contains(&n) {
            return Err(Failure::bad_input(format!(
                "{}: key `--max-fe`: must lie between {lo} and {hi}, got {n}",
                problem.file.display()
            )));
        }
        problem.refine.max_fe = n as usize;
    }
    if !problem.refine.enabled {
        if let Some(e) = problem.stand_in_error("an unrefined run") {
            return Err(Failure::bad_input(e));
        }
    }
    let dir = output_dir(&problem, study.out)?;
    let report = report.then(|| problem_text(&problem));
    run_study(&problem, &options, &dir, verify, report.as_ref())
}

/// `flexopt report`: the design report of a run's folder `dir`, with the problem file's
/// text where `problem` names it.
fn report(dir: &Path, problem: Option<&Path>) -> Result<(), Failure> {
    let text = problem
        .map(|p| {
            flexopt::problem::read_problem_text(p)
                .map(|text| ProblemText {
                    path: p.display().to_string(),
                    text,
                })
                .map_err(|e| Failure::bad_input(format!("{}: key `--problem`: {e}", p.display())))
        })
        .transpose()?;
    let written = write_report(dir, text.as_ref())?;
    emit(&format!("wrote {}\n", written.display()))
}

/// `flexopt tolerance`: the chosen design's yield under the file's tolerances, by `samples`
/// Monte Carlo samples of the model, and by `fe_samples` of the part where given.
fn tolerance(
    path: &Path,
    design: &DesignArgs,
    samples: usize,
    seed: Option<u64>,
    threads: Option<usize>,
    out: Option<PathBuf>,
    fe_samples: Option<usize>,
) -> Result<(), Failure> {
    let (problem, x) = chosen_design(path, design)?;
    let settings = tolerance_command::settings(&problem, samples, seed, threads)?;
    let fe = fe_samples
        .map(|n| tolerance_command::fe_samples(&problem, n, settings))
        .transpose()?;
    let dir = out.unwrap_or_else(|| problem.default_output_dir().join("tolerance"));
    check_writable(&dir).map_err(|e| Failure::bad_input(format!("key `--out`: {e}")))?;
    tolerance_command::run(&problem, &x, settings, fe, &dir)
}

/// `flexopt pareto`: the front `spec` steps, a study at each step.
fn pareto(path: &Path, spec: ParetoSpec, study: &StudyArgs) -> Result<(), Failure> {
    let (problem, options) = study_setup(path, study)?;
    // a front's every point is an analytic optimum
    if let Some(e) = problem.stand_in_error("a front") {
        return Err(Failure::bad_input(e));
    }
    let dir = output_dir(&problem, study.out.clone())?;
    run_pareto(&problem, &spec, &options, &dir)
}

/// The problem file's text for `run --report`, read again from its path (standard input is
/// read once: then the report names the file only), where it is still the content the run
/// read.
fn problem_text(problem: &Problem) -> Option<ProblemText> {
    let text = flexopt::problem::read_problem_text(&problem.file).ok()?;
    (flexopt::problem::fingerprint(&text) == problem.fingerprint).then(|| ProblemText {
        path: problem.file.display().to_string(),
        text,
    })
}

/// The folder a study writes into (`--out`, else `results/<name>/`), checked before the
/// computation.
fn output_dir(problem: &Problem, out: Option<PathBuf>) -> Result<PathBuf, Failure> {
    let dir = out.unwrap_or_else(|| problem.default_output_dir());
    check_writable(&dir).map_err(|e| Failure::bad_input(format!("key `--out`: {e}")))?;
    Ok(dir)
}

/// The design a sweep runs around: `--around` (partial: the rest from the default), or the
/// default of [`default_design`].
/// Where a sweep's base design comes from: `--around` pairs or an optimum's report (else the
/// middle of the bounds).
struct Base<'a> {
    around: Option<&'a str>,
    optimum: Option<&'a Path>,
}

fn load_around(path: &Path, base: Base) -> Result<(Problem, Vec<f64>), Failure> {
    let problem = load_problem(path)?;
    let parsed = match (base.around, base.optimum) {
        (Some(text), _) => parse_around(&problem, text),
        (None, Some(report)) => design_from_optimum(&problem, report),
        (None, None) => {
            let x = default_design(&problem);
            return Ok((problem, x));
        }
    };
    let parsed = parsed.map_err(Failure::bad_input)?;
    warn(path, &parsed.warnings);
    Ok((problem, parsed.x))
}

fn warn(path: &Path, warnings: &[String]) {
    for w in warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
}

fn eval(path: &Path, design: &DesignArgs, format: Option<&str>) -> Result<(), Failure> {
    let (problem, x) = chosen_design(path, design)?;
    let report = DesignReport::new(&problem, &x);
    for name in report.non_finite_outputs() {
        eprintln!(
            "warning: {}: output {name} has no finite value at this design",
            path.display()
        );
    }
    warn(path, &fit::warnings(&problem, &report.fit_ranges));
    let table = format.map_or(std::io::stdout().is_terminal(), |f| f == "table");
    if table {
        emit(&DesignTable {
            problem: &problem,
            report: &report,
        })
    } else {
        print_json(&report)
    }
}

/// The design of `--design` or `--optimum`, inside the model's domain.
fn chosen_design(path: &Path, args: &DesignArgs) -> Result<(Problem, Vec<f64>), Failure> {
    let problem = load_problem(path)?;
    let (parsed, key) = match (&args.design, &args.optimum) {
        (Some(text), _) => (parse_design(&problem, text), "--design"),
        (None, Some(report)) => (design_from_optimum(&problem, report), "--optimum"),
        (None, None) => unreachable!("clap requires one of --design and --optimum"),
    };
    let parsed = parsed.map_err(Failure::bad_input)?;
    warn(path, &parsed.warnings);
    if let Some(why) = problem.model().domain_error(&parsed.x) {
        return Err(Failure::bad_input(format!(
            "{}: key `{key}`: outside the model's domain: {why}",
            path.display()
        )));
    }
    Ok((problem, parsed.x))
}

fn export(path: &Path, design: &DesignArgs, out: Option<PathBuf>) -> Result<(), Failure> {
    let (problem, x) = chosen_design(path, design)?;
    let dir = out.unwrap_or_else(|| problem.default_output_dir().join("export"));
    check_writable(&dir).map_err(|e| Failure::bad_input(format!("key `--out`: {e}")))?;
    let part = problem.mechanism().part_or_error(&x).map_err(|e| {
        let message = format!(
            "{}: this design gives no part that can be made: {e}",
            path.display()
        );
        // a model without a part is a problem file's mistake, not its part's
        if problem.mechanism().part_spec(&x).is_some() {
            Failure::cannot_be_made(message)
        } else {
            Failure::bad_input(message)
        }
    })?;
    warn(path, &part.warnings);
    let report = DesignReport::new(&problem, &x);
    let files = write_part_set(
        &dir,
        &problem.name,
        &report.design,
        &part,
        &report.part_rules,
    )
    .map_err(Failure::write_failed)?;
    emit(&Wrote(&files))
}

/// `flexopt hinge`: one hinge's report as JSON; every bad value is bad input.
fn hinge(
    kind: &str,
    given: &[(&str, f64)],
    width: f64,
    material: &str,
    stress_limit: Option<f64>,
    format: Option<&str>,
) -> Result<(), Failure> {
    let report = calculator::from_options(kind, given, width, material, stress_limit)
        .map_err(Failure::bad_input)?;
    for c in report.fit_ranges.iter().filter(|c| !c.inside) {
        eprintln!("warning: {}", c.warning());
    }
    if format.map_or(std::io::stdout().is_terminal(), |f| f == "table") {
        emit(&flexopt::report::hinge::HingeTable(&report))
    } else {
        print_json(&report)
    }
}

fn run_sweep(
    path: &Path,
    spec: &SweepSpec,
    base: Base,
    out: Option<PathBuf>,
) -> Result<(), Failure> {
    let (problem, base) = load_around(path, base)?;
    let result = sweep(&problem, spec, &base).map_err(Failure::bad_input)?;
    warn(path, result.gaps().as_slice());
    let dir = out.unwrap_or_else(|| problem.default_output_dir().join("sweep"));
    check_writable(&dir).map_err(|e| Failure::bad_input(format!("key `--out`: {e}")))?;
    let files = write_sweep(&dir, &result).map_err(Failure::write_failed)?;
    emit(&Wrote(&files))
}
