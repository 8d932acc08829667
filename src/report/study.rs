//! The files a multistart study writes: `optimum.json`, `starts.json`, `starts.csv`,
//! `zones.json`, `zones.png` and `configurations.png`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use indexmap::IndexMap;
use serde::Serialize;

use super::configurations::configurations_png;
use super::folder::OutputSet;
use super::html::{self, ProblemText};
use super::part::{write_part, PartOf, PART_FILES};
use super::study_plots::zones_png;
use super::verify::{write_verify, Verdict, VerifyReport, VERIFY_FILES, VERIFY_FOLDER};
use super::{write_atomic, write_json, DesignReport, WriteError};
use crate::fe::verify::Verification;
use crate::optim::Status;
use crate::part::{Part, PartError};
use crate::problem::{Problem, Solver};
use crate::study::{Ends, Run, Study};

/// `optimum.json`: the optimal design with every output and how it was found.
#[derive(Debug, Clone, Serialize)]
pub struct OptimumReport {
    #[serde(flatten)]
    pub design: DesignReport,
    pub configuration: &'static str,
    pub solver: Solver,
    pub seed: u64,
    pub starts: usize,
    /// The start that found it, its zone, and its solve.
    pub start: usize,
    pub zone: Option<usize>,
    pub status: Status,
    pub kkt_residual: Option<f64>,
    pub iterations: usize,
    /// Whether this design's solve converged; `false` only when no start converged to a
    /// feasible design, and then `flexopt run` exits with code 4.
    pub converged: bool,
    /// How every start's solve ended.
    pub ends: Ends,
    /// The design is the mirror image (every angle negated) of the start's end: the same
    /// geometry, in the orientation the model draws ([`crate::model::Model::prefers_mirror`]).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub mirrored: bool,
    /// The run was interrupted: these results come from the starts that finished.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub partial: bool,
    /// No start was feasible: the outputs of the constraints that no start met together with
    /// the others. The design meets every other constraint and violates these least (sum of
    /// relative violations), then has the best objective within those violations.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cannot_be_met: Option<Vec<String>>,
    /// Why the design gives no part that can be made with the problem's `[part]` sizes;
    /// then no part files are written.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub part_problems: Option<Vec<String>>,
    /// The verdict of the part's FE check (`run --verify`), in the highest fidelity that
    /// ran: `feasible` above is the model's; this is the part's. Absent when no check ran.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub verdict: Option<Verdict>,
}

/// One line of `starts.json`.
#[derive(Debug, Clone, Serialize)]
pub struct StartRecord {
    pub start: usize,
    pub zone: Option<usize>,
    pub optimum: Option<usize>,
    /// The objective as the problem states it.
    pub objective: Option<f64>,
    pub feasible: bool,
    pub status: Status,
    pub iterations: usize,
    pub evaluations: usize,
    pub max_violation: f64,
    pub kkt_residual: Option<f64>,
    pub configuration: &'static str,
    /// Start and end designs in the problem file's units.
    pub x_start: IndexMap<String, f64>,
    pub x_end: IndexMap<String, f64>,
}

/// A distinct optimum in `zones.json`.
#[derive(Debug, Clone, Serialize)]
pub struct OptimumEntry {
    pub objective: f64,
    pub configuration: &'static str,
    /// Number of starts that reached it, and which.
    pub count: usize,
    pub starts: Vec<usize>,
    pub design: IndexMap<String, f64>,
}

#[derive(Debug, Clone, Serialize)]
pub struct ZoneEntry {
    pub rank: usize,
    pub low: Option<f64>,
    pub high: Option<f64>,
    pub count: usize,
    pub best: Option<f64>,
    pub worst: Option<f64>,
    pub optima: Vec<OptimumEntry>,
}

/// `zones.json`.
#[derive(Debug, Clone, Serialize)]
pub struct ZonesReport {
    pub objective_output: String,
    pub thresholds: Vec<f64>,
    pub zones: Vec<ZoneEntry>,
    /// Starts that did not end at a feasible point.
    pub not_feasible: usize,
    /// How the model names configurations; absent for a model whose topology is fixed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub configuration_rule: Option<&'static str>,
}

/// The configuration kind of a design of `problem`'s model.
fn configuration(problem: &Problem, x: &[f64]) -> &'static str {
    problem.depiction().configuration(x)
}

fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

pub fn optimum_report(
    problem: &Problem,
    study: &Study,
    part: Option<&Result<Part, PartError>>,
) -> OptimumReport {
    let run = &study.runs[study.best];
    let x = study.reported_design();
    let (start, zone, solution) = match &study.least_violating {
        Some(l) => (l.from, None, &l.solution),
        None => (run.start, run.zone, &run.solution),
    };
    OptimumReport {
        design: DesignReport::new(problem, x),
        configuration: configuration(problem, x),
        solver: study.options.solver,
        seed: study.options.seed,
        starts: study.runs.len(),
        start,
        zone,
        status: solution.status.clone(),
        kkt_residual: solution.kkt_residual,
        iterations: solution.iterations,
        converged: study.best_converged,
        ends: study.ends,
        mirrored: study.mirrored.is_some() && study.least_violating.is_none(),
        partial: study.interrupted,
        cannot_be_met: study.least_violating.as_ref().map(|l| {
            l.unmet
                .iter()
                .map(|&k| problem.constraints[k].output.clone())
                .collect()
        }),
        part_problems: match part {
            Some(Err(e)) => Some(e.problems.clone()),
            _ => None,
        },
        verdict: None,
    }
}

pub fn start_records(problem: &Problem, study: &Study) -> Vec<StartRecord> {
    study
        .runs
        .iter()
        .map(|r: &Run| StartRecord {
            start: r.start,
            zone: r.zone,
            optimum: r.optimum,
            objective: finite(r.objective),
            feasible: r.feasible,
            status: r.solution.status.clone(),
            iterations: r.solution.iterations,
            evaluations: r.solution.evaluations,
            max_violation: r.solution.max_violation,
            kkt_residual: r.solution.kkt_residual,
            configuration: configuration(problem, &r.x_end),
            x_start: problem.design_in_file_units(&r.x_start),
            x_end: problem.design_in_file_units(&r.x_end),
        })
        .collect()
}

pub fn zones_report(problem: &Problem, study: &Study) -> ZonesReport {
    let c = &study.clustering;
    let run_of = |k: usize| &study.runs[study.feasible_runs[k]];
    ZonesReport {
        objective_output: problem.objective.output.clone(),
        thresholds: problem.zones.thresholds.clone(),
        zones: c
            .zones
            .iter()
            .map(|z| ZoneEntry {
                rank: z.rank,
                low: z.low,
                high: z.high,
                count: z.count,
                best: finite(z.best),
                worst: finite(z.worst),
                optima: z
                    .optima
                    .iter()
                    .map(|&k| {
                        let o = &c.optima[k];
                        let rep = run_of(o.representative);
                        OptimumEntry {
                            objective: o.objective,
                            configuration: configuration(problem, &rep.x_end),
                            count: o.members.len(),
                            starts: o.members.iter().map(|&m| run_of(m).start).collect(),
                            design: problem.design_in_file_units(&rep.x_end),
                        }
                    })
                    .collect(),
            })
            .collect(),
        not_feasible: study.runs.len() - study.feasible_runs.len(),
        configuration_rule: problem.depiction().configuration_rule(),
    }
}

fn csv(problem: &Problem, records: &[StartRecord]) -> String {
    let unit = super::display::output_unit(problem, problem.objective.index);
    let objective = match unit.name.as_str() {
        "1" | "" => format!("objective_{}", problem.objective.output),
        u => format!("objective_{}_{u}", problem.objective.output),
    };
    let mut s = format!(
        "start,zone,optimum,{objective},feasible,status,iterations,evaluations,max_violation,\
         kkt_residual,configuration"
    );
    for prefix in ["start", "end"] {
        for v in &problem.variables {
            let _ = write!(s, ",{prefix}_{}_{}", v.name, v.unit.name);
        }
    }
    s.push('\n');
    let opt = |v: Option<f64>| v.map(super::display::csv).unwrap_or_default();
    let idx = |v: Option<usize>| v.map(|v| v.to_string()).unwrap_or_default();
    for r in records {
        let status = match &r.status {
            Status::Converged => "converged",
            Status::IterationLimit => "iteration_limit",
            Status::Infeasible => "infeasible",
            Status::Failed(_) => "failed",
        };
        let _ = write!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{}",
            r.start,
            idx(r.zone),
            idx(r.optimum),
            opt(r.objective.map(|v| unit.from_si(v))),
            r.feasible,
            status,
            r.iterations,
            r.evaluations,
            super::display::csv(r.max_violation),
            opt(r.kkt_residual),
            r.configuration
        );
        for v in r.x_start.values().chain(r.x_end.values()) {
            let _ = write!(s, ",{}", super::display::csv(*v));
        }
        s.push('\n');
    }
    s
}

/// Writes every file of the study into `dir` as one set ([`super::folder`]): staged under a
/// folder unique to the run, moved into place under the folder's lock, `manifest.json` last;
/// returns the paths in place. With `part` (the optimum's, where the model has one) the set
/// holds the part's files too, or `optimum.json` says why there is no part.
pub fn write_all(
    dir: &Path,
    problem: &Problem,
    study: &Study,
    part: Option<&Result<Part, PartError>>,
) -> Result<Vec<PathBuf>, WriteError> {
    write_all_refined(dir, problem, study, part, None, None, None)
}

/// The files of a refinement, written with the study's set.
pub struct RefinedFiles<'a> {
    pub report: &'a super::refine::RefinedReport,
    /// The refined design's part, where it has one.
    pub part: Option<&'a Part>,
}

/// The names of the refined design's part files.
pub const REFINED_PART_FILES: [&str; 5] = [
    "refined_part.dxf",
    "refined_part.svg",
    "refined_part.json",
    "refined_part.png",
    "refined_part.step",
];

/// [`write_all`], with `refined.json` and the refined design's part files in the set, the
/// FE check of the optimum (`run --verify`) as its folder `verify/`, itself a set, and, with
/// `report` (`run --report`), `report.html` of the set, written last (it lists the others),
/// stating the problem file where it is given.
pub fn write_all_refined(
    dir: &Path,
    problem: &Problem,
    study: &Study,
    part: Option<&Result<Part, PartError>>,
    refined: Option<RefinedFiles>,
    verified: Option<(&VerifyReport, &Verification)>,
    report: Option<Option<&ProblemText>>,
) -> Result<Vec<PathBuf>, WriteError> {
    let set = OutputSet::begin(dir)?;
    let written = set.write(|set| {
        let verdict = verified.map(|(report, _)| &report.verdict);
        let mut written = write_study(set, problem, study, part, verdict)?;
        if let Some(r) = refined {
            write_json(&set.path("refined.json"), r.report)?;
            written.push("refined.json");
            if let (Some(part), Some(design)) = (r.part, r.report.refined.as_ref()) {
                let named = |f: &str| set.path(&format!("refined_{f}"));
                // the design in model order, every parameter, for its rules
                let mut x = vec![0.0; problem.variables.len()];
                for v in &problem.variables {
                    x[v.parameter] = design.design_si[&v.name];
                }
                let rules = crate::problem::part_rules::checks(problem, &x);
                write_part(
                    named,
                    &problem.name,
                    &design.design,
                    part,
                    PartOf::Refined,
                    &rules,
                )?;
                written.extend(REFINED_PART_FILES);
            }
        }
        if let Some((report, v)) = verified {
            write_verify(|f| set.path(VERIFY_FOLDER).join(f), report, v)?;
            set.seal_folder(VERIFY_FOLDER, &VERIFY_FILES)?;
            written.push(VERIFY_FOLDER);
        }
        if let Some(text) = report {
            html::write_staged(&set.path(html::REPORT), &set.path(""), &written, text)?;
            written.push(html::REPORT);
        }
        Ok(written)
    })?;
    set.commit(&written)
}

/// The files of a study, in the order they are written (a model without a drawing of its
/// configurations writes the first five), before the part's.
pub const STUDY_FILES: [&str; 6] = [
    "optimum.json",
    "starts.json",
    "starts.csv",
    "zones.json",
    "zones.png",
    "configurations.png",
];

/// Writes the study's files and the optimum's part into the set's staging folder; returns
/// their names.
fn write_study(
    set: &OutputSet,
    problem: &Problem,
    study: &Study,
    part: Option<&Result<Part, PartError>>,
    verdict: Option<&Verdict>,
) -> Result<Vec<&'static str>, WriteError> {
    let records = start_records(problem, study);
    let files = STUDY_FILES;
    let path = |name: &str| set.path(name);
    let mut optimum = optimum_report(problem, study, part);
    optimum.verdict = verdict.cloned();
    write_json(&path(files[0]), &optimum)?;
    write_json(&path(files[1]), &records)?;
    write_atomic(&path(files[2]), csv(problem, &records).as_bytes())?;
    write_json(&path(files[3]), &zones_report(problem, study))?;
    zones_png(&path(files[4]), problem, study)?;
    let best = study.reported_design();
    let mut written = files[..5].to_vec();
    if problem.depiction().skeleton(best).is_some() {
        configurations_png(&path(files[5]), problem, study)?;
        written.push(files[5]);
    }
    if let Some(Ok(part)) = part {
        write_part(
            path,
            &problem.name,
            &optimum.design.design,
            part,
            PartOf::Design,
            &optimum.design.part_rules,
        )?;
        written.extend(PART_FILES);
    }
    Ok(written)
}
