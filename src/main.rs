//! The `flexopt` command line: parse, call the library, print.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use flexopt::problem::design::parse_design;
use flexopt::problem::Problem;
use flexopt::report::DesignReport;
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
    /// Optimize: multistart local searches, zones, and the optimal design.
    Run {
        problem: PathBuf,
        #[arg(long)]
        out: Option<PathBuf>,
    },
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
        Command::Run { problem, out: _ } => {
            let problem = match Problem::load(&problem) {
                Ok(p) => p,
                Err(e) => return bad_input(e),
            };
            eprintln!("flexopt run: the multistart optimizer is not built yet; evaluating the middle of the bounds of {}", problem.name);
            let mid: Vec<f64> = problem
                .variables
                .iter()
                .map(|v| 0.5 * (v.lower + v.upper))
                .collect();
            print_json(&DesignReport::new(&problem, &mid))
        }
    }
}

fn bad_input(e: impl std::fmt::Display) -> ExitCode {
    eprintln!("error: {e}");
    ExitCode::from(BAD_INPUT)
}

fn print_json(value: &impl serde::Serialize) -> ExitCode {
    match serde_json::to_string_pretty(value) {
        Ok(s) => {
            println!("{s}");
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
            println!(
                "wrote {}",
                dir.join(format!("{}.json", spec.variable)).display()
            );
            println!(
                "wrote {}",
                dir.join(format!("{}.png", spec.variable)).display()
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(WRITE_FAILED)
        }
    }
}
