//! The `flexopt` command line: parse, call the library, print.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use std::io::IsTerminal;

use flexopt::pareto::{pareto, ParetoSpec};
use flexopt::problem::design::parse_design;
use flexopt::problem::{Problem, Solver};
use flexopt::report::study::write_all;
use flexopt::report::DesignReport;
use flexopt::study::{self, StudyOptions};
use flexopt::sweep::{sweep, SweepSpec};

/// Exit code for a rejected problem file, design or option.
const BAD_INPUT: u8 = 2;
/// Exit code for results that could not be written.
const WRITE_FAILED: u8 = 1;

#[derive(Parser)]
#[command(
    name = "flexopt",
    version,
    about = "Design and optimize compliant flexure-hinge mechanisms"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Evaluate one design and print every output as JSON.
    Eval {
        /// The problem file (TOML).
        problem: PathBuf,
        /// The design, `name=value` pairs in the problem file's units, comma-separated;
        /// fixed variables may be left out.
        #[arg(long)]
        design: String,
    },
    /// Curves of the outputs against one design variable (JSON and PNG).
    Sweep {
        problem: PathBuf,
        /// The variable to sweep.
        #[arg(long)]
        param: String,
        /// First value, in the variable's unit.
        #[arg(long, allow_hyphen_values = true)]
        from: f64,
        /// Last value, in the variable's unit.
        #[arg(long, allow_hyphen_values = true)]
        to: f64,
        /// Number of points.
        #[arg(long, default_value_t = 201)]
        steps: usize,
        /// The design the other variables are held at (default: the middle of the bounds).
        #[arg(long)]
        around: Option<String>,
        /// Outputs to record, comma-separated (default: all).
        #[arg(long, value_delimiter = ',')]
        outputs: Vec<String>,
        /// Folder to write into (default: results/<problem name>/sweep).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Optimize: local solves from many starts, optima sorted into zones, the optimal
    /// design exported (optimum.json, starts.json/.csv, zones.json, zones.png,
    /// configurations.png).
    Run {
        problem: PathBuf,
        #[command(flatten)]
        study: StudyArgs,
        /// Local solver (default: the problem file's search.solver).
        #[arg(long, value_parser = ["sqp", "nelder-mead"])]
        solver: Option<String>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Trade-off front by the epsilon-constraint method: the limit of the problem's
    /// one-sided constraint on OUTPUT is stepped from A to B and the study run at each
    /// step (pareto.json, pareto.png).
    Pareto {
        problem: PathBuf,
        /// The constrained output whose limit is stepped.
        #[arg(long)]
        vary: String,
        /// First limit, in the constraint's unit.
        #[arg(long, allow_hyphen_values = true)]
        from: f64,
        /// Last limit, in the constraint's unit.
        #[arg(long, allow_hyphen_values = true)]
        to: f64,
        /// Number of limits.
        #[arg(long, default_value_t = 11)]
        steps: usize,
        #[command(flatten)]
        study: StudyArgs,
    },
}

/// The options of a multistart study, shared by `run` and `pareto`.
#[derive(clap::Args)]
struct StudyArgs {
    /// Folder to write into (default: results/<problem name>).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Number of starts, per limit for `pareto` (default: the problem file's search.starts).
    #[arg(long)]
    starts: Option<usize>,
    /// Random seed (default: the problem file's search.seed).
    #[arg(long)]
    seed: Option<u64>,
    /// Worker threads, 0 for every core (default: the problem file's search.threads).
    #[arg(long)]
    threads: Option<usize>,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Eval { problem, design } => eval(&problem, &design),
        Command::Sweep {
            problem,
            param,
            from,
            to,
            steps,
            around,
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
            run_sweep(&problem, &spec, around.as_deref(), out)
        }
        Command::Run {
            problem,
            study,
            solver,
            quiet,
        } => {
            let (problem, mut options) = match study_setup(&problem, &study) {
                Ok(v) => v,
                Err(code) => return code,
            };
            if let Some(s) = solver {
                options.solver = if s == "sqp" {
                    Solver::Sqp
                } else {
                    Solver::NelderMead
                };
            }
            options.progress = !quiet && std::io::stderr().is_terminal();
            let dir = study.out.unwrap_or_else(|| problem.default_output_dir());
            run_study(&problem, &options, &dir)
        }
        Command::Pareto {
            problem,
            vary,
            from,
            to,
            steps,
            study,
        } => {
            let (problem, options) = match study_setup(&problem, &study) {
                Ok(v) => v,
                Err(code) => return code,
            };
            let spec = ParetoSpec {
                output: vary,
                from,
                to,
                steps,
            };
            let dir = study.out.unwrap_or_else(|| problem.default_output_dir());
            run_pareto(&problem, &spec, &options, &dir)
        }
    }
}

/// Loads the problem and applies the command line's overrides of its `[search]`.
fn study_setup(path: &Path, args: &StudyArgs) -> Result<(Problem, StudyOptions), ExitCode> {
    let StudyArgs {
        starts,
        seed,
        threads,
        ..
    } = *args;
    let problem = Problem::load(path).map_err(bad_input)?;
    if problem.free_variables().next().is_none() {
        return Err(bad_input(format!(
            "{}: key `variables`: every variable has a fixed `value`, so there is nothing to \
             optimize; give at least one `lower` and `upper` instead (`flexopt eval` and \
             `flexopt sweep` take a fixed design)",
            problem.file.display()
        )));
    }
    let mut options = StudyOptions::from_problem(&problem);
    if let Some(s) = starts {
        if !(1..=1_000_000).contains(&s) {
            return Err(bad_input(format!(
                "{}: key `--starts`: must lie between 1 and 1000000, got {s}",
                problem.file.display()
            )));
        }
        options.starts = s;
    }
    if threads.is_some_and(|t| t > 1024) {
        return Err(bad_input(format!(
            "{}: key `--threads`: must lie between 0 and 1024",
            problem.file.display()
        )));
    }
    options.seed = seed.unwrap_or(options.seed);
    options.threads = threads.unwrap_or(options.threads);
    Ok((problem, options))
}

fn run_pareto(
    problem: &Problem,
    spec: &ParetoSpec,
    options: &StudyOptions,
    dir: &Path,
) -> ExitCode {
    use std::fmt::Write as _;
    let front = match pareto(problem, spec, options) {
        Ok(f) => f,
        Err(e) => return bad_input(e),
    };
    let files = match front.write(dir) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(WRITE_FAILED);
        }
    };
    let mut text = format!(
        "{}: {} limits on {} x {} starts in {:.1} ms\n",
        problem.name,
        front.points.len(),
        front.output,
        front.starts,
        front.elapsed.as_secs_f64() * 1e3
    );
    let _ = writeln!(
        text,
        "{:>12}  {:>12}  {:>12}  active  front",
        format!("limit ({})", front.unit),
        front.objective,
        front.output
    );
    for p in &front.points {
        let show = |v: Option<f64>| v.map_or("infeasible".to_string(), |v| format!("{v:.6}"));
        let _ = writeln!(
            text,
            "{:>12}  {:>12}  {:>12}  {:<6}  {}",
            format!("{:.6}", p.limit),
            show(p.objective),
            show(p.value),
            if p.active { "yes" } else { "no" },
            if p.on_front { "yes" } else { "no" }
        );
    }
    for f in files {
        let _ = writeln!(text, "wrote {}", f.display());
    }
    emit(&text);
    if front.points.iter().any(|p| p.feasible) {
        ExitCode::SUCCESS
    } else {
        eprintln!(
            "error: {}: no limit of the range admits a feasible design",
            problem.file.display()
        );
        ExitCode::from(NO_FEASIBLE_DESIGN)
    }
}

/// Exit code for a study in which no start ended feasible.
const NO_FEASIBLE_DESIGN: u8 = 3;

fn run_study(problem: &Problem, options: &StudyOptions, dir: &Path) -> ExitCode {
    let study = study::run(problem, options);
    let files = match write_all(dir, problem, &study) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(WRITE_FAILED);
        }
    };
    let mut text = summary(problem, &study);
    for f in files {
        text.push_str(&format!("wrote {}\n", f.display()));
    }
    emit(&text);
    if study.any_feasible {
        ExitCode::SUCCESS
    } else {
        eprintln!(
            "error: {}: no start ended at a feasible design; optimum.json holds the least violating one",
            problem.file.display()
        );
        ExitCode::from(NO_FEASIBLE_DESIGN)
    }
}

fn summary(problem: &Problem, study: &study::Study) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let best = &study.runs[study.best];
    let solver = match study.options.solver {
        Solver::Sqp => "SQP",
        Solver::NelderMead => "Nelder-Mead",
    };
    let _ = writeln!(
        s,
        "{}: {} starts with {solver}, seed {}, in {:.1} ms; {} ended feasible",
        problem.name,
        study.runs.len(),
        study.options.seed,
        study.elapsed.as_secs_f64() * 1e3,
        study.feasible_runs.len()
    );
    let label = if study.any_feasible {
        "best"
    } else {
        "least violating (infeasible)"
    };
    let _ = writeln!(
        s,
        "{label} {} = {:.6} ({})",
        problem.objective.output,
        best.objective,
        study::configuration(problem, &best.x_end)
    );
    let design: Vec<String> = problem
        .variables
        .iter()
        .zip(&best.x_end)
        .map(|(v, &x)| format!("{}={:.6}", v.name, v.unit.from_si(x)))
        .collect();
    let _ = writeln!(s, "  design {}", design.join(","));
    let _ = writeln!(s, "zone  starts  optima  best        worst");
    for z in &study.clustering.zones {
        let f = |v: f64| {
            if v.is_finite() {
                format!("{v:<10.6}")
            } else {
                format!("{:<10}", "-")
            }
        };
        let _ = writeln!(
            s,
            "{:<5} {:<7} {:<7} {}  {}",
            z.rank,
            z.count,
            z.optima.len(),
            f(z.best),
            f(z.worst)
        );
    }
    let missing = study.runs.len() - study.feasible_runs.len();
    if missing > 0 {
        let _ = writeln!(
            s,
            "{missing} starts ended infeasible or failed (see starts.json)"
        );
    }
    s
}

/// Writes to stdout; a reader that has gone away (a closed pipe) is not an error worth a
/// panic, and the command just stops printing.
fn emit(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(text.as_bytes()).and_then(|()| out.flush());
}

fn bad_input(e: impl std::fmt::Display) -> ExitCode {
    eprintln!("error: {e}");
    ExitCode::from(BAD_INPUT)
}

fn print_json(value: &impl serde::Serialize) -> ExitCode {
    match serde_json::to_string_pretty(value) {
        Ok(s) => {
            emit(&format!("{s}\n"));
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: cannot format the result: {e}");
            ExitCode::from(WRITE_FAILED)
        }
    }
}

fn load_design(path: &Path, design: Option<&str>) -> Result<(Problem, Vec<f64>), ExitCode> {
    let problem = Problem::load(path).map_err(bad_input)?;
    let x = match design {
        Some(text) => {
            let parsed = parse_design(&problem, text).map_err(bad_input)?;
            for w in &parsed.warnings {
                eprintln!("warning: {}: {w}", path.display());
            }
            parsed.x
        }
        None => problem
            .variables
            .iter()
            .map(|v| 0.5 * (v.lower + v.upper))
            .collect(),
    };
    Ok((problem, x))
}

fn eval(path: &Path, design: &str) -> ExitCode {
    let (problem, x) = match load_design(path, Some(design)) {
        Ok(v) => v,
        Err(code) => return code,
    };
    if let Some(why) = problem.model().domain_error(&x) {
        return bad_input(format!(
            "{}: key `--design`: outside the model's domain: {why}",
            path.display()
        ));
    }
    let report = DesignReport::new(&problem, &x);
    for name in report.non_finite_outputs() {
        eprintln!(
            "warning: {}: output {name} has no finite value at this design",
            path.display()
        );
    }
    print_json(&report)
}

fn run_sweep(
    path: &Path,
    spec: &SweepSpec,
    around: Option<&str>,
    out: Option<PathBuf>,
) -> ExitCode {
    let (problem, base) = match load_design(path, around) {
        Ok(v) => v,
        Err(code) => return code,
    };
    let result = match sweep(&problem, spec, &base) {
        Ok(s) => s,
        Err(e) => return bad_input(e),
    };
    let dir = out.unwrap_or_else(|| problem.default_output_dir().join("sweep"));
    match result.write(&dir) {
        Ok(()) => {
            for ext in ["json", "png"] {
                emit(&format!(
                    "wrote {}\n",
                    dir.join(format!("{}.{ext}", spec.variable)).display()
                ));
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(WRITE_FAILED)
        }
    }
}
