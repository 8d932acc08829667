//! The command line's grammar: every command, its arguments and their help.

use std::path::PathBuf;

use clap::{Parser, Subcommand};

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

#[derive(Subcommand)]
pub enum Command {
    /// Evaluate one design: every output, the objective and each constraint with its limit,
    /// margin and activity, as a table (in the file's units) or as JSON (SI, with each
    /// output's display unit beside).
    Eval {
        /// The problem file (TOML).
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
    Export {
        /// The problem file (TOML).
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
    Verify {
        /// The problem file (TOML).
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
    Hinge {
        /// strip, circular, elliptical or corner-filleted.
        #[arg(long)]
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
        /// A material preset (al7075-t6, 65si2mn).
        #[arg(long, default_value = "al7075-t6")]
        material: String,
        /// The stress limit, MPa (default: a third of the material's ultimate strength).
        #[arg(long)]
        stress_limit: Option<f64>,
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
    Run {
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
