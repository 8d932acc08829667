//! The command line's grammar: every command, its arguments and their help.

use std::path::PathBuf;

use clap::builder::PossibleValuesParser;
use clap::{Parser, Subcommand};
use flexopt::model::hinge::HingeKind;
use flexopt::model::material::Material;
use flexopt::model::registry::MODELS;
use flexopt::problem::refine::FIDELITIES;
use flexopt::problem::SOLVERS;

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
const EXIT_CODES: &str = "Exit codes: 0 success; 1 files or output that could not be \
written; 2 a rejected problem file, design or option (the message names the file, the key \
and what is wrong); 3 no feasible design (run, pareto; refined by FE: none meets the \
constraints on the part); 4 feasible designs but none converged; 5 a part that cannot be \
made (export, verify; run: its optimum's); 130 interrupted (Ctrl-C).";

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
                            (give --force) or cannot be written, or the model has no hinges \
                            (--hinge) or no material (--material)."
    )]
    Init {
        /// The model (`flexopt outputs --model M` describes each).
        #[arg(long, default_value = MODELS[0].name, value_parser = models())]
        model: String,
        /// The kind of every hinge (models with hinges): the variables become its
        /// dimensions, with bounds inside its range of fit.
        #[arg(long, value_parser = PossibleValuesParser::new(HingeKind::NAMES))]
        hinge: Option<String>,
        /// The material preset (models with a [material] section).
        #[arg(long, value_parser = PossibleValuesParser::new(Material::PRESETS))]
        material: Option<String>,
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
        /// A problem file: its model's parameters as the file's sections make them (the
        /// dimensions of its hinge kinds) and its outputs.
        #[arg(conflicts_with = "model")]
        problem: Option<PathBuf>,
        /// The model, as `init` writes it (without a problem file).
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
        #[command(flatten)]
        design: DesignArgs,
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
    /// stress, plane strain and 3D, each output's discretization error estimated (verify.json,
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
        /// The most degrees of freedom a mesh of the half part may have (default 400000,
        /// about 1.6 GB): the meshes stop before one that would need more.
        #[arg(long)]
        max_dofs: Option<usize>,
        /// Leave out the 3D check (the part's mesh extruded through its width): the two 2D
        /// idealizations only, in about half the time.
        #[arg(long)]
        no_3d: bool,
    },
    /// One flexure hinge on its own: compliances, stiffnesses, rotation per moment and the
    /// rotation a stress limit allows, as JSON. Dimensions in mm, each kind its own.
    #[command(after_help = EXIT_CODES)]
    Hinge {
        /// The hinge's kind.
        #[arg(long, value_parser = PossibleValuesParser::new(HingeKind::NAMES))]
        kind: String,
        #[command(flatten)]
        dimensions: HingeDimensionArgs,
        /// Width of the hinge (out of the plane), mm.
        #[arg(long)]
        width: f64,
        /// A material preset.
        #[arg(long, default_value = Material::PRESETS[0], value_parser = PossibleValuesParser::new(Material::PRESETS))]
        material: String,
        /// The stress limit, MPa (default: a third of the material's ultimate strength).
        #[arg(long)]
        stress_limit: Option<f64>,
        /// `table` (each figure with its unit) or `json`; default: a table on a terminal,
        /// JSON when the output goes to a file or a pipe.
        #[arg(long, value_parser = ["table", "json"])]
        format: Option<String>,
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
        #[arg(long, conflicts_with = "optimum")]
        around: Option<String>,
        /// A report of `flexopt run` whose design the other variables are held at (its
        /// `design_si`), instead of `--around`.
        #[arg(long)]
        optimum: Option<PathBuf>,
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
        #[arg(long, value_parser = PossibleValuesParser::new(FIDELITIES.names()))]
        refine: Option<String>,
        /// The most FE checks a refined optimum may take, in place of the file's
        /// `[refine] max_fe` (2 to 200).
        #[arg(long)]
        max_fe: Option<i64>,
        /// Write report.html too: the set as one self-contained page for a design review
        /// (as `flexopt report` does, with the problem file stated).
        #[arg(long)]
        report: bool,
    },
    /// The design report of a run's folder: report.html, one self-contained page (pictures
    /// embedded, no network, printable) with the problem, the optimum, its constraints, the
    /// part, the FE check and refinement where the folder holds them, and the files with
    /// their hashes. It reads the folder's files; nothing is recomputed.
    #[command(
        after_help = "Exit codes: 0 written; 1 report.html could not be written; 2 DIR \
                            is not a run's folder, or --problem is not the file the run read."
    )]
    Report {
        /// The folder of a run (flexopt run PROBLEM --out DIR; default results/<name>/).
        dir: PathBuf,
        /// The problem file the run read, stated in full in the report (its content is
        /// checked against the run's).
        #[arg(long)]
        problem: Option<PathBuf>,
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
    /// One design under the tolerances of the file's [tolerances] (and wire EDM's defaults
    /// for a model with a part): each output's spread to first order from the exact
    /// gradients and by Monte Carlo, the yield with its confidence interval, and which
    /// tolerance drives which output (tolerance.json, histogram_<output>.png per
    /// constrained output, a table).
    #[command(after_help = EXIT_CODES)]
    Tolerance {
        #[arg(help = PROBLEM)]
        problem: PathBuf,
        #[command(flatten)]
        design: DesignArgs,
        /// Monte Carlo samples (2 to 10000000).
        #[arg(long, default_value_t = 100_000)]
        samples: usize,
        /// Random seed (default: the problem file's search.seed); sample i draws from its
        /// own stream, so the thread count changes nothing.
        #[arg(long)]
        seed: Option<u64>,
        /// Worker threads, 0 for every core (default: the problem file's search.threads).
        #[arg(long)]
        threads: Option<usize>,
        /// Folder to write into (default: results/<problem name>/tolerance).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Check the spread on the part too: the first --fe-samples of the Monte Carlo's
        /// samples, each checked by finite elements (the file's [refine] idealization, in
        /// parallel), the FE's spread and the part's yield beside the model's.
        #[arg(long)]
        fe: bool,
        /// Samples checked by FE with --fe (3 to 200).
        #[arg(long, default_value_t = 12, requires = "fe")]
        fe_samples: usize,
    },
    /// One network design with its flexures' large deflection over its working stroke,
    /// beside the linear model: the curves (stroke.csv, stroke.svg), the report with the
    /// critical load factor and the end point with twice the elements (stroke.json), and a
    /// table of the full stroke.
    #[command(after_help = EXIT_CODES)]
    Stroke(StrokeArgs),
}

/// The options of `flexopt stroke`.
#[derive(clap::Args)]
pub struct StrokeArgs {
    #[arg(help = PROBLEM)]
    pub problem: PathBuf,
    #[command(flatten)]
    pub design: DesignArgs,
    /// Folder to write into (default: results/<problem name>/stroke).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Beam elements a flexure (1 to 64); the convergence estimate solves the full stroke
    /// with twice as many.
    #[arg(long, default_value_t = 8)]
    pub elements: usize,
    /// Load steps from the unloaded part to the full stroke: the curves' points (1 to 1000).
    #[arg(long, default_value_t = 10)]
    pub steps: usize,
    /// Drive the input by this force (N, the whole mechanism's, along the input's
    /// direction) in the actuator's place.
    #[arg(long, value_name = "NEWTONS", allow_hyphen_values = true)]
    pub force: Option<f64>,
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
    #[arg(long, value_parser = PossibleValuesParser::new(SOLVERS.names()))]
    pub solver: Option<String>,
    /// No progress bar or progress lines.
    #[arg(long)]
    pub quiet: bool,
}

/// The dimension flags of `flexopt hinge`, one per stem over every kind's dimension table,
/// so that a new kind brings its flags with it: clap's derive cannot make fields from a
/// table, hence [`clap::Args`] by hand.
pub struct HingeDimensionArgs {
    /// The flags given, `(stem, mm)`, in the order of [`hinge_stems`].
    pub given: Vec<(&'static str, f64)>,
}

/// What a stem means and the kinds it means that in.
type Meaning = (&'static str, Vec<&'static str>);

/// Each distinct stem over every kind, in the order of first appearance, with its help:
/// what it is for each kind that takes it.
fn hinge_stems() -> Vec<(&'static str, String)> {
    let mut stems: Vec<(&'static str, Vec<Meaning>)> = Vec::new();
    for &kind in HingeKind::ALL {
        for d in kind.dimensions() {
            let at = match stems.iter().position(|(s, _)| *s == d.stem) {
                Some(i) => i,
                None => {
                    stems.push((d.stem, Vec::new()));
                    stems.len() - 1
                }
            };
            // kinds whose dimension means the same share one description
            let meanings = &mut stems[at].1;
            match meanings.iter_mut().find(|(what, _)| *what == d.description) {
                Some((_, kinds)) => kinds.push(kind.name()),
                None => meanings.push((d.description, vec![kind.name()])),
            }
        }
    }
    stems
        .into_iter()
        .map(|(stem, meanings)| {
            let text: Vec<String> = meanings
                .iter()
                .map(|(what, kinds)| format!("{what} ({})", kinds.join(", ")))
                .collect();
            // a capital first, as clap's other help texts
            let text = text.join("; ");
            let mut chars = text.chars();
            let first = chars.next().map(|c| c.to_uppercase().to_string());
            (
                stem,
                format!("{}{}, mm", first.unwrap_or_default(), chars.as_str()),
            )
        })
        .collect()
}

impl clap::FromArgMatches for HingeDimensionArgs {
    fn from_arg_matches(matches: &clap::ArgMatches) -> Result<Self, clap::Error> {
        Self::from_arg_matches_mut(&mut matches.clone())
    }

    fn from_arg_matches_mut(matches: &mut clap::ArgMatches) -> Result<Self, clap::Error> {
        let given = hinge_stems()
            .into_iter()
            .filter_map(|(stem, _)| matches.remove_one::<f64>(stem).map(|v| (stem, v)))
            .collect();
        Ok(HingeDimensionArgs { given })
    }

    fn update_from_arg_matches(&mut self, matches: &clap::ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

impl clap::Args for HingeDimensionArgs {
    fn augment_args(cmd: clap::Command) -> clap::Command {
        hinge_stems().into_iter().fold(cmd, |cmd, (stem, help)| {
            cmd.arg(
                clap::Arg::new(stem)
                    .long(stem)
                    .value_name("MM")
                    .value_parser(clap::value_parser!(f64))
                    .help(help),
            )
        })
    }

    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        Self::augment_args(cmd)
    }
}
