//! The command line's grammar: every command, its arguments and their help.

use std::path::PathBuf;

use clap::builder::PossibleValuesParser;
use clap::{Parser, Subcommand};
use flexopt::model::hinge::HingeKind;
use flexopt::model::material::Material;
use flexopt::model::registry::MODELS;

#[derive(Parser)]
#[command(
    name = "flexopt",
    version,
    about = "Design and optimize compliant flexure-hinge mechanisms"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

/// What every command that reads a problem file says of it.
const PROBLEM: &str = "The problem file (TOML; `flexopt init` writes one to start from), or - \
                       to read it from standard input";

/// The exit codes, for every command's help.
const EXIT_CODES: &str = "Exit codes: 0 success; 1 files that could not be written; 2 a \
rejected problem file, design or option (the message names the file, the key and what is \
wrong); 3 no feasible design (run, pareto; refined by FE: none meets the constraints on the \
part); 4 feasible designs but none converged; 5 an optimum whose part cannot be made; 130 \
interrupted (Ctrl-C).";

/// The models a problem file can name, from the registry: the first is the default.
fn models() -> PossibleValuesParser {
    PossibleValuesParser::new(MODELS.iter().map(|m| m.name))
}

#[derive(Subcommand)]
pub enum Command {
    /// Write a problem file to start from: every key, the optional ones commented with
    /// their defaults, a ready set of variables, objective and constraints.
    #[command(
        after_help = "Then: flexopt run FILE. Exit codes: 0 written; 2 FILE exists \
                            (give --force) or cannot be written."
    )]
    Init {
        /// The model (`flexopt outputs --model M` describes each).
        #[arg(long, default_value = MODELS[0].name, value_parser = models())]
        model: String,
        /// The file to write (its stem names the problem); without it, the file goes to
        /// standard output.
        file: Option<PathBuf>,
        /// Overwrite FILE if it exists.
        #[arg(long)]
        force: bool,
    },
    /// Print the JSON Schema of problem files (for editors that complete and check keys,
    /// with a TOML language server such as taplo or Even Better TOML).
    Schema,
    /// Print the shell completion script for SHELL (bash, zsh, fish, elvish, powershell).
    #[command(after_help = "For bash: flexopt completions bash > \
                            ~/.local/share/bash-completion/completions/flexopt")]
    Completions { shell: clap_complete::Shell },
    /// List a model's parameters and outputs with their units and meaning.
    Outputs {
        /// The model.
        #[arg(long, default_value = MODELS[0].name, value_parser = models())]
        model: String,
    },
    /// Evaluate one design: every output, the objective and each constraint with its limit,
    /// margin and activity, as a table (in the file's units) or as JSON (SI, with each
    /// output's display unit beside).
    #[command(after_help = EXIT_CODES)]
    Eval {
        #[arg(help = PROBLEM)]
        problem: PathBuf,
        /// The design, `name=value` pairs in the problem file's units, comma-separated;
        /// fixed variables may be left out.
        #[arg(long)]
        design: String,
        /// `table` or `json`; default: a table on a terminal, JSON when the output goes to
        /// a file or a pipe (what scripts read).
        #[arg(long, value_parser = ["table", "json"])]
        format: Option<String>,
    },
    /// The part of one design: its outline for CAD and wire EDM (part.dxf, part.svg,
    /// part.json) and a dimensioned drawing (part.png).
    #[command(after_help = EXIT_CODES)]
    Export {
        #[arg(help = PROBLEM)]
        problem: PathBuf,
        #[command(flatten)]
        design: DesignArgs,
        /// Folder to write into (default: results/<problem name>/export).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Check one design on its part by finite elements: paper 004's load cases in plane
    /// stress and plane strain, each output's discretization error estimated (verify.json,
    /// stress.png, deformed.png, CalculiX decks part.inp and part3d.inp).
    #[command(after_help = EXIT_CODES)]
    Verify {
        #[arg(help = PROBLEM)]
        problem: PathBuf,
        #[command(flatten)]
        design: DesignArgs,
        /// Folder to write into (default: results/<problem name>/verify).
        #[arg(long)]
        out: Option<PathBuf>,
        /// The relative error every output must be estimated below (default 0.005).
        #[arg(long)]
        tolerance: Option<f64>,
    },
    /// One flexure hinge on its own: compliances, stiffnesses, rotation per moment and the
    /// rotation a stress limit allows, as JSON. Dimensions in mm: a strip takes --l --t, a
    /// circular notch --r --t, an elliptical one --a --b --t, a corner-filleted leaf --l --t
    /// --r.
    #[command(after_help = EXIT_CODES)]
    Hinge {
        /// The hinge's kind.
        #[arg(long, value_parser = PossibleValuesParser::new(HingeKind::NAMES))]
        kind: String,
        /// Length (strip, corner-filleted; fillets included), mm.
        #[arg(long)]
        l: Option<f64>,
        /// Least thickness, mm.
        #[arg(long)]
        t: Option<f64>,
        /// Notch radius (circular) or fillet radius (corner-filleted), mm.
        #[arg(long)]
        r: Option<f64>,
        /// Semi-axis along the hinge (elliptical), mm.
        #[arg(long)]
        a: Option<f64>,
        /// Semi-axis across the hinge (elliptical), mm.
        #[arg(long)]
        b: Option<f64>,
        /// Width of the hinge (out of the plane), mm.
        #[arg(long)]
        width: f64,
        /// A material preset.
        #[arg(long, default_value = Material::PRESETS[0], value_parser = PossibleValuesParser::new(Material::PRESETS))]
        material: String,
        /// The stress limit, MPa (default: a third of the material's ultimate strength).
        #[arg(long)]
        stress_limit: Option<f64>,
    },
    /// Curves of the outputs against one design variable (JSON and PNG).
    #[command(after_help = EXIT_CODES)]
    Sweep {
        #[arg(help = PROBLEM)]
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
        /// The design the other variables are held at, `name=value` pairs in the file's
        /// units; variables left out (or all, without it) take the middle of their bounds,
        /// an angle range that straddles zero the middle of its positive part.
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
    #[command(after_help = EXIT_CODES)]
    Run {
        #[arg(help = PROBLEM)]
        problem: PathBuf,
        #[command(flatten)]
        study: StudyArgs,
        /// Check the optimum on its part by finite elements too (into DIR/verify).
        #[arg(long)]
        verify: bool,
        /// Refine the optimum against the finite elements of its part (refined.json and the
        /// refined part's files; settings in the file's [refine]), or not (`none`),
        /// whatever the file's [refine] fidelity says.
        #[arg(long, value_parser = ["fe", "none"])]
        refine: Option<String>,
    },
    /// Trade-off front by the epsilon-constraint method: the limit of the problem's
    /// one-sided constraint on OUTPUT is stepped from A to B and the study run at each
    /// step (pareto.json, pareto.png).
    #[command(after_help = EXIT_CODES)]
    Pareto {
        #[arg(help = PROBLEM)]
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

/// Where a command takes its one design from.
#[derive(clap::Args)]
#[group(required = true, multiple = false)]
pub struct DesignArgs {
    /// The design, `name=value` pairs in the problem file's units, comma-separated; fixed
    /// variables may be left out.
    #[arg(long)]
    pub design: Option<String>,
    /// A report of `flexopt run` whose design to take (its `design_si`).
    #[arg(long)]
    pub optimum: Option<PathBuf>,
}

/// The options of a multistart study, shared by `run` and `pareto`.
#[derive(clap::Args)]
pub struct StudyArgs {
    /// Folder to write into (default: results/<problem name>).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Number of starts, per limit for `pareto` (default: the problem file's search.starts).
    #[arg(long)]
    pub starts: Option<usize>,
    /// Random seed (default: the problem file's search.seed).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Worker threads, 0 for every core (default: the problem file's search.threads).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Local solver (default: the problem file's search.solver).
    #[arg(long, value_parser = ["sqp", "nelder-mead"])]
    pub solver: Option<String>,
    /// No progress bar or progress lines.
    #[arg(long)]
    pub quiet: bool,
}
