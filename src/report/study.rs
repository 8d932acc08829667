//! The files a multistart study writes: `optimum.json`, `starts.json`, `starts.csv`,
//! `zones.json`, `zones.png` and `configurations.png`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use indexmap::IndexMap;
use plotters::prelude::*;
use serde::Serialize;

use super::folder::OutputSet;
use super::part::{write_part, PART_FILES};
use super::plot::{draw_legend, format_tick, range, render_png, FAMILY};
use super::{write_atomic, write_json, DesignReport, WriteError};
use crate::model::Skeleton;
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
    problem.model().configuration(x)
}

fn in_file_units(problem: &Problem, x: &[f64]) -> IndexMap<String, f64> {
    problem
        .variables
        .iter()
        .zip(x)
        .map(|(v, &xi)| (v.name.clone(), v.unit.from_si(xi)))
        .collect()
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
            x_start: in_file_units(problem, &r.x_start),
            x_end: in_file_units(problem, &r.x_end),
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
                            design: in_file_units(problem, &rep.x_end),
                        }
                    })
                    .collect(),
            })
            .collect(),
        not_feasible: study.runs.len() - study.feasible_runs.len(),
        configuration_rule: problem.model().configuration_rule(),
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

const ZONE_COLOURS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
];

fn colour(rank: usize) -> RGBColor {
    ZONE_COLOURS[(rank - 1) % ZONE_COLOURS.len()]
}

/// Fig. 4 analogue: every feasible start's optimum, sorted, coloured by zone, with the
/// zone thresholds.
fn zones_png(path: &Path, problem: &Problem, study: &Study) -> Result<(), WriteError> {
    // in the objective's display unit, as the summary prints it
    let unit = super::display::output_unit(problem, problem.objective.index);
    let mut pts: Vec<(f64, usize)> = study
        .runs
        .iter()
        .filter_map(|r| r.zone.map(|z| (unit.from_si(r.objective), z)))
        .collect();
    pts.sort_by(|a, b| b.0.total_cmp(&a.0));
    let thresholds: Vec<f64> = problem
        .zones
        .thresholds
        .iter()
        .map(|&t| unit.from_si(t))
        .collect();
    let title = format!(
        "{}: optima of {} starts, sorted",
        problem.name,
        study.runs.len()
    );
    let ylabel = if problem.objective.absolute {
        format!("|{}|", problem.objective.output)
    } else {
        problem.objective.output.clone()
    };
    let ylabel = match unit.name.as_str() {
        "1" | "" => ylabel,
        u => format!("{ylabel} ({u})"),
    };
    render_png(path, (900, 560), |root| {
        let yr = range(pts.iter().map(|p| p.0).chain(thresholds.iter().copied()));
        let mut chart = ChartBuilder::on(root)
            .caption(&title, (FAMILY, 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d(0f64..(pts.len().max(1) as f64), yr.0..yr.1)?;
        chart
            .configure_mesh()
            .x_desc("start, sorted by its optimum")
            .y_desc(&ylabel)
            .label_style((FAMILY, 13))
            .light_line_style(TRANSPARENT)
            .bold_line_style(BLACK.mix(0.12))
            .y_label_formatter(&|v| format_tick(*v))
            .draw()?;
        for &t in &thresholds {
            chart.draw_series(LineSeries::new(
                [(0.0, t), (pts.len() as f64, t)],
                BLACK.mix(0.4).stroke_width(1),
            ))?;
        }
        for rank in 1..=study.clustering.zones.len() {
            let series: Vec<(f64, f64)> = pts
                .iter()
                .enumerate()
                .filter(|(_, p)| p.1 == rank)
                .map(|(i, p)| (i as f64 + 0.5, p.0))
                .collect();
            if series.is_empty() {
                continue;
            }
            let n = series.len();
            chart
                .draw_series(
                    series
                        .into_iter()
                        .map(|p| Circle::new(p, 3, colour(rank).filled())),
                )?
                .label(format!("zone {rank}: {n}"))
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, colour(rank).filled()));
        }
        draw_legend(&mut chart, 13)?;
        Ok(())
    })
}

/// Fig. 5 analogue: the model's drawing of every feasible start's optimum as a chain of
/// members ([`crate::model::Model::skeleton`]), one row per zone that has optima, drawn to
/// scale (one mm is as long across as along) with each member at its thickness.
fn configurations_png(path: &Path, problem: &Problem, study: &Study) -> Result<(), WriteError> {
    let model = problem.model();
    let lines: Vec<(usize, Skeleton)> = study
        .runs
        .iter()
        .filter_map(|r| Some((r.zone?, model.skeleton(&r.x_end)?)))
        .collect();
    let ranks: Vec<usize> = study
        .clustering
        .zones
        .iter()
        .map(|z| z.rank)
        .filter(|&r| lines.iter().any(|l| l.0 == r))
        .collect();
    let pad = 0.5
        * lines
            .iter()
            .flat_map(|l| l.1.thickness_mm.iter().copied())
            .fold(0.0, f64::max);
    let xr = range(lines.iter().flat_map(|l| l.1.nodes_mm.iter().map(|p| p.0)));
    let yr = range(lines.iter().flat_map(|l| l.1.nodes_mm.iter().map(|p| p.1)));
    let (xr, yr) = ((xr.0 - pad, xr.1 + pad), (yr.0 - pad, yr.1 + pad));
    // equal scales: the plot's height follows the drawing's, within reason, and the
    // shorter range grows to fill the plot
    const WIDTH: u32 = 1000;
    const LEFT: u32 = 56;
    const BOTTOM: u32 = 40;
    const CAPTION: u32 = 28;
    const MARGIN: u32 = 10;
    let plot_w = (WIDTH - LEFT - 2 * MARGIN) as f64;
    let per_mm = plot_w / (xr.1 - xr.0);
    let plot_h = ((yr.1 - yr.0) * per_mm).clamp(120.0, 480.0);
    let grow = (plot_h / per_mm - (yr.1 - yr.0)) / 2.0;
    let yr = (yr.0 - grow.max(0.0), yr.1 + grow.max(0.0));
    let shrink = ((yr.1 - yr.0) * per_mm - plot_h).max(0.0) / per_mm / 2.0;
    let yr = (yr.0 + shrink, yr.1 - shrink);
    let row = plot_h as u32 + BOTTOM + CAPTION + 2 * MARGIN;
    let title = format!(
        "{}: configurations by zone ({})",
        problem.name,
        model.skeleton_legend()
    );
    let rows = ranks.len().max(1) as u32;
    render_png(path, (WIDTH, 36 + row * rows), |root| {
        let root = root.titled(&title, (FAMILY, 16))?;
        let panels = root.split_evenly((rows as usize, 1));
        for (&rank, area) in ranks.iter().zip(&panels) {
            let count = lines.iter().filter(|l| l.0 == rank).count();
            let mut chart = ChartBuilder::on(area)
                .caption(format!("zone {rank}: {count} starts"), (FAMILY, 15))
                .margin(MARGIN)
                .x_label_area_size(BOTTOM)
                .y_label_area_size(LEFT)
                .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)?;
            chart
                .configure_mesh()
                .x_desc("x (mm)")
                .y_desc("y (mm)")
                .label_style((FAMILY, 12))
                .light_line_style(TRANSPARENT)
                .bold_line_style(BLACK.mix(0.1))
                .x_label_formatter(&|v| format_tick(*v))
                .y_label_formatter(&|v| format_tick(*v))
                .draw()?;
            for (_, skeleton) in lines.iter().filter(|l| l.0 == rank) {
                let members = skeleton
                    .nodes_mm
                    .windows(2)
                    .zip(&skeleton.rigid)
                    .zip(&skeleton.thickness_mm);
                for ((seg, &rigid), &t) in members {
                    let (a, b) = (seg[0], seg[1]);
                    if rigid || t <= 0.0 {
                        chart
                            .draw_series(LineSeries::new([a, b], BLACK.mix(0.4).stroke_width(1)))?;
                        continue;
                    }
                    // the member as a band of its thickness about its centre line
                    let len = (b.0 - a.0).hypot(b.1 - a.1).max(1e-12);
                    let n = (-(b.1 - a.1) / len * t / 2.0, (b.0 - a.0) / len * t / 2.0);
                    let band = vec![
                        (a.0 + n.0, a.1 + n.1),
                        (b.0 + n.0, b.1 + n.1),
                        (b.0 - n.0, b.1 - n.1),
                        (a.0 - n.0, a.1 - n.1),
                    ];
                    chart.draw_series([Polygon::new(band, colour(rank).mix(0.5).filled())])?;
                }
            }
        }
        Ok(())
    })
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
    write_all_refined(dir, problem, study, part, None)
}

/// The files of a refinement, written with the study's set.
pub struct RefinedFiles<'a> {
    pub report: &'a super::refine::RefinedReport,
    /// The refined design's part, where it has one.
    pub part: Option<&'a Part>,
}

/// The names of the refined design's part files.
pub const REFINED_PART_FILES: [&str; 4] = [
    "refined_part.dxf",
    "refined_part.svg",
    "refined_part.json",
    "refined_part.png",
];

/// [`write_all`], with `refined.json` and the refined design's part files in the set.
pub fn write_all_refined(
    dir: &Path,
    problem: &Problem,
    study: &Study,
    part: Option<&Result<Part, PartError>>,
    refined: Option<RefinedFiles>,
) -> Result<Vec<PathBuf>, WriteError> {
    let set = OutputSet::begin(dir)?;
    let records = start_records(problem, study);
    let files = [
        "optimum.json",
        "starts.json",
        "starts.csv",
        "zones.json",
        "zones.png",
        "configurations.png",
    ];
    let path = |name: &str| set.path(name);
    let optimum = optimum_report(problem, study, part);
    write_json(&path(files[0]), &optimum)?;
    write_json(&path(files[1]), &records)?;
    write_atomic(&path(files[2]), csv(problem, &records).as_bytes())?;
    write_json(&path(files[3]), &zones_report(problem, study))?;
    zones_png(&path(files[4]), problem, study)?;
    // a model without a drawing of its configurations writes the first five
    let best = study.reported_design();
    let mut written: Vec<&str> = files[..5].to_vec();
    if problem.model().skeleton(best).is_some() {
        configurations_png(&path(files[5]), problem, study)?;
        written.push(files[5]);
    }
    if let Some(Ok(part)) = part {
        write_part(path, &problem.name, &optimum.design.design, part)?;
        written.extend(PART_FILES);
    }
    if let Some(r) = refined {
        write_json(&path("refined.json"), r.report)?;
        written.push("refined.json");
        if let (Some(part), Some(design)) = (r.part, r.report.refined.as_ref()) {
            let named = |f: &str| set.path(&format!("refined_{f}"));
            write_part(named, &problem.name, &design.design, part)?;
            written.extend(REFINED_PART_FILES);
        }
    }
    set.commit(&written)
}
