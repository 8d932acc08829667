//! The files of a finite-element check ([`crate::fe::verify`]): `verify.json`, `stress.png`
//! (von Mises stress on the part, its largest value marked), `deformed.png` (the deformed
//! shape, scaled, over the undeformed outline), the CalculiX decks `part.inp` (2D, plane
//! strain) and `part3d.inp` (the same mesh extruded through the width), and the table in the
//! style of paper 004's Table 2 that the command line prints.

use std::fmt::{self, Display};
use std::path::{Path, PathBuf};

use indexmap::IndexMap;
use plotters::prelude::*;
use serde::Serialize;

use super::folder::OutputSet;
use super::plot::{render_png, FAMILY};
use super::{write_atomic, write_json, WriteError};
use crate::fe::element::Element;
use crate::fe::mesh::Mesh;
use crate::fe::richardson::Estimate;
use crate::fe::verify::{Level, Output, SolidSolve, Verification};
use crate::fe::{Fidelity, Idealization};
use crate::part::analysis::FeCounterpart;
use crate::part::MM;
use crate::problem::display::percent;
use crate::problem::Problem;
use crate::vocab::units::Unit;
use compare::{analytic, displacements_at, value};

mod compare;
mod stress;
mod verdict;
use stress::stress_png;
pub use verdict::{model_gaps, Judged, ModelGap, PartFailure, Verdict, VerdictLines, MODEL_GAP};

/// The files a verification writes, in order.
pub const VERIFY_FILES: [&str; 5] = [
    "verify.json",
    "stress.png",
    "deformed.png",
    "part.inp",
    "part3d.inp",
];

/// The folder of a run's set that holds its check (`run --verify`), and where `verify`
/// writes by default.
pub const VERIFY_FOLDER: &str = "verify";

/// The mesh level of `part.inp` and of `part3d.inp` (the first mesh: its outputs are within
/// about 0.5 % of the extrapolated ones, `verify.json` lists them by level; the 3D deck is
/// the 3D check's finest solve, its graded layers through the half-width).
const DECK_LEVEL: usize = 0;

/// One FE output in `verify.json`.
#[derive(Debug, Clone, Serialize)]
pub struct OutputReport {
    pub unit: &'static str,
    /// The unit the tables show it in, the terminal's and the report's alike (its name).
    #[serde(rename = "display_unit", serialize_with = "unit_name")]
    pub display: Unit,
    pub meaning: &'static str,
    #[serde(flatten)]
    pub estimate: Estimate,
    /// The values on each mesh of the sequence, coarsest first.
    pub values: Vec<f64>,
    pub analytic: Option<f64>,
    /// `(analytic - FE) / FE`, in percent: how far the analytic model is from the FE.
    pub deviation_percent: Option<f64>,
    /// For the stresses: the value at the model's actuation force, the FE's own force being
    /// the actuator's largest force on the part of the FE's own stiffness
    /// ([`crate::part::Actuation::largest_force`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at_analytic_force: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub location_mm: Option<[f64; 2]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at: Option<String>,
}

/// `verify.json`.
#[derive(Debug, Clone, Serialize)]
pub struct VerifyReport {
    pub problem: String,
    /// The design in the problem file's units.
    pub design: IndexMap<String, f64>,
    pub tolerance: f64,
    /// Every output meant to converge (all but the peak stress) did, within the tolerance.
    pub converged: bool,
    pub test_force: f64,
    /// The actuation force on each loaded face of the actuation case, per idealization (N).
    pub actuation_force: IndexMap<&'static str, f64>,
    /// The model's actuation force (N), where it has one.
    pub analytic_actuation_force: Option<f64>,
    /// What the displacements are measured under, for the table.
    #[serde(skip)]
    pub displacements_at: String,
    pub levels: Vec<Level>,
    pub outputs: IndexMap<&'static str, IndexMap<&'static str, OutputReport>>,
    /// The whole check's time (s).
    pub seconds: f64,
    /// Why the sequence stopped before converging: the budget of degrees of freedom.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub budget_stop: Option<String>,
    /// The 3D solves behind the 3D values (in-plane mesh level, layers through the
    /// half-width).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub solid_solves: Vec<SolidSolve>,
    /// Why there are no 3D values.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solid_note: Option<String>,
    /// The whole part was solved: it or its check is not symmetric about the y axis.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub whole_part: bool,
    /// Why the modal outputs the part states are not there.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modal_note: Option<String>,
    /// The plate's width over its thinnest hinge, and the fidelity that ratio calls for
    /// ([`Fidelity::for_plate`]): the column to read.
    pub width_over_thickness: f64,
    pub read: Fidelity,
    /// The outputs the problem's constraints name that the part's check does not measure
    /// (nor the part's drawing give): a check with any is no verification of the design.
    pub not_measured_on_the_part: Vec<String>,
    /// The constraints judged on the part, in the highest fidelity that ran.
    pub verdict: Verdict,
}

fn key(f: Fidelity) -> &'static str {
    match f {
        Fidelity::PlaneStress => "plane_stress",
        Fidelity::PlaneStrain => "plane_strain",
        Fidelity::Solid => "3d",
    }
}

/// Each fidelity the check made: its outputs and its actuation force.
fn fidelities(v: &Verification) -> Vec<(Fidelity, &[Output], f64)> {
    v.results
        .iter()
        .zip(&v.actuation_force)
        .map(|(r, &f)| (Fidelity::from(r.idealization), r.outputs.as_slice(), f))
        .chain(
            v.solid
                .iter()
                .map(|s| (Fidelity::Solid, s.outputs.as_slice(), s.actuation_force)),
        )
        .collect()
}

fn unit_name<S: serde::Serializer>(unit: &Unit, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&unit.name)
}

impl VerifyReport {
    pub fn new(problem: &Problem, x: &[f64], v: &Verification) -> Self {
        let a = analytic(problem, x, v);
        let model = problem.model();
        let actuation_force = (0..model.outputs().len())
            .find(|&i| problem.mechanism().fe_counterpart(i) == Some(FeCounterpart::ActuationForce))
            .and_then(|i| value(model, x, i));
        let mut outputs = IndexMap::new();
        for (fidelity, outputs_of, own_force) in fidelities(v) {
            let mut map = IndexMap::new();
            for o in outputs_of {
                let stated = &v.analysis.outputs[o.id.0];
                let analytic = a[o.id.0];
                let fe = o.estimate.value;
                let stress = stated.quantity.is_stress();
                map.insert(
                    o.name,
                    OutputReport {
                        unit: o.unit,
                        display: Unit::shown(stated.dimension, stated.display),
                        meaning: stated.meaning,
                        estimate: o.estimate,
                        values: o.values.clone(),
                        analytic,
                        deviation_percent: analytic.map(|an| 100.0 * (an - fe) / fe),
                        at_analytic_force: actuation_force
                            .filter(|_| stress)
                            .map(|f| fe * f / own_force),
                        location_mm: o.location_mm,
                        at: o.at.clone(),
                    },
                );
            }
            outputs.insert(key(fidelity), map);
        }
        let thinnest = v.thinnest_hinge();
        let read = Fidelity::for_plate(v.width, thinnest);
        let mut verdict = Verdict::new(problem, x, v, read);
        verdict.model_off = model_gaps(outputs.get(key(verdict.fidelity)));
        VerifyReport {
            problem: problem.name.clone(),
            design: problem.design_in_file_units(x),
            tolerance: v.tolerance,
            converged: v.converged,
            test_force: v.test_force,
            actuation_force: fidelities(v)
                .into_iter()
                .map(|(f, _, force)| (key(f), force))
                .collect(),
            analytic_actuation_force: actuation_force,
            displacements_at: displacements_at(v),
            levels: v.levels.clone(),
            outputs,
            seconds: v.seconds,
            budget_stop: v.budget_stop.map(|b| b.to_string()),
            solid_solves: v.solid.as_ref().map_or(Vec::new(), |s| s.solves.clone()),
            solid_note: v.solid_note.clone(),
            whole_part: v.whole_part,
            modal_note: v.modal_note.clone(),
            width_over_thickness: v.width / thinnest,
            read,
            not_measured_on_the_part: not_measured(problem, v),
            verdict,
        }
    }
}

/// The outputs `problem`'s constraints name (each once) that `v` does not measure and the
/// part's drawing does not give.
fn not_measured(problem: &Problem, v: &Verification) -> Vec<String> {
    let mechanism = problem.mechanism();
    let measured = |output: usize| match mechanism.fe_counterpart(output) {
        Some(FeCounterpart::ActuationForce) => true,
        Some(FeCounterpart::Output(id)) => fidelities(v)
            .iter()
            .any(|(_, outputs, _)| outputs.iter().any(|o| o.id == id)),
        None => mechanism.drawn(output),
    };
    let mut names: Vec<String> = Vec::new();
    for c in &problem.constraints {
        if !measured(c.index) && !names.contains(&c.output) {
            names.push(c.output.clone());
        }
    }
    names
}

/// Writes the verification's files through `path` (a file name to where it goes).
pub fn write_verify(
    path: impl Fn(&str) -> PathBuf,
    report: &VerifyReport,
    v: &Verification,
) -> Result<Vec<PathBuf>, WriteError> {
    let files: Vec<PathBuf> = VERIFY_FILES.iter().map(|f| path(f)).collect();
    write_json(&files[0], report)?;
    stress_png(&files[1], &report.problem, v)?;
    deformed_png(&files[2], &report.problem, v)?;
    let fail = |p: &Path, e: &dyn Display| WriteError {
        path: p.to_path_buf(),
        message: e.to_string(),
    };
    let title = format!("{}: the part of flexopt verify", report.problem);
    let model = v.full_model(DECK_LEVEL).map_err(|e| fail(&files[3], &e))?;
    let deck = model.deck(&title, &v.material, v.width, 1.0);
    write_atomic(&files[3], deck.two_d(Idealization::PlaneStrain).as_bytes())?;
    write_atomic(&files[4], deck.three_d(&v.solid_layers()).as_bytes())?;
    Ok(files)
}

/// Writes the verification's files into `dir` as one set in place of the folder's earlier
/// one ([`super::folder`]); returns the paths in place.
pub fn write_verify_set(
    dir: &Path,
    report: &VerifyReport,
    v: &Verification,
) -> Result<Vec<PathBuf>, WriteError> {
    let set = OutputSet::begin(dir)?;
    set.write(|set| write_verify(|name| set.path(name), report, v))?;
    set.commit(&VERIFY_FILES)
}

/// The panels' common frame (mm): the whole part with a margin, and the image's size at
/// equal scale on both axes.
fn frame(v: &Verification, panels: u32) -> ((f64, f64), (f64, f64), (u32, u32)) {
    let [x0, y0, x1, y1] = v.part.bounding_box.map(|c| c * MM);
    let pad = 0.08 * (x1 - x0).max(y1 - y0);
    let (xr, yr) = ((x0 - pad, x1 + pad), (y0 - pad, y1 + pad));
    let panel_w = 900u32;
    let plot_w = (panel_w - 80) as f64;
    let plot_h = plot_w * (yr.1 - yr.0) / (xr.1 - xr.0);
    (xr, yr, (panel_w * panels, plot_h as u32 + 130))
}

type Chart<'a, 'b> = ChartContext<
    'a,
    BitMapBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// Each element of the half mesh and its mirror image (or of the whole part's mesh, where
/// that was solved) as the polygon of its corners, mm, with a value per element; `shift`
/// moves each node (m).
fn cells(
    v: &Verification,
    k: usize,
    shift: &dyn Fn(usize) -> [f64; 2],
) -> Vec<(Vec<(f64, f64)>, f64)> {
    let f = &v.results[k].fields;
    polygons(&f.mesh, &f.von_mises, shift, !v.whole_part)
}

/// [`cells`] of any element: its corners are where its sides start.
fn polygons<E: Element>(
    m: &Mesh<E>,
    von_mises: &[f64],
    shift: &dyn Fn(usize) -> [f64; 2],
    mirror: bool,
) -> Vec<(Vec<(f64, f64)>, f64)> {
    let mut out = Vec::with_capacity(2 * m.elements.len());
    for el in &m.elements {
        let value = el.as_ref().iter().map(|&n| von_mises[n]).sum::<f64>() / E::NODES as f64;
        let corners: Vec<(f64, f64)> = E::SIDES
            .iter()
            .map(|&(c, _)| {
                let n = el[c];
                let d = shift(n);
                (m.nodes[n][0] + d[0], m.nodes[n][1] + d[1])
            })
            .collect();
        let mm = |p: (f64, f64)| (p.0 * 1e3, p.1 * 1e3);
        out.push((corners.iter().map(|&p| mm(p)).collect(), value));
        if mirror {
            out.push((corners.iter().map(|&p| mm((-p.0, p.1))).collect(), value));
        }
    }
    out
}

fn panel<'a, 'b>(
    area: &'a DrawingArea<BitMapBackend<'b>, plotters::coord::Shift>,
    caption: &str,
    xr: (f64, f64),
    yr: (f64, f64),
) -> Result<Chart<'a, 'b>, super::plot::DrawError> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FAMILY, 17))
        .margin(10)
        .x_label_area_size(36)
        .y_label_area_size(44)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("x (mm)")
        .y_desc("y (mm)")
        .label_style((FAMILY, 12))
        .draw()?;
    Ok(chart)
}

/// `deformed.png`: the deformed outline under the actuation, scaled, over the undeformed.
fn deformed_png(path: &Path, problem: &str, v: &Verification) -> Result<(), WriteError> {
    let (xr, yr, size) = frame(v, v.results.len() as u32);
    let [x0, _, x1, _] = v.part.bounding_box;
    let title = format!("{problem}: deformed shape under the actuation (grey: undeformed)");
    render_png(path, size, |root| {
        let root = root.titled(&title, (FAMILY, 20))?;
        let areas = root.split_evenly((1, v.results.len()));
        for (area, r) in areas.iter().zip(&v.results) {
            let f = &r.fields;
            let largest = f
                .displacement
                .chunks(2)
                .map(|d| d[0].hypot(d[1]))
                .fold(0.0, f64::max);
            // the largest displacement drawn as a twentieth of the part's width
            let scale = if largest > 0.0 {
                0.05 * (x1 - x0) / largest
            } else {
                1.0
            };
            let caption = format!("{} (displacements x {:.0})", r.idealization.name(), scale);
            let mut chart = panel(area, &caption, xr, yr)?;
            let m = &f.mesh;
            for (k, style) in [(0.0, RGBColor(170, 170, 170)), (scale, BLUE)] {
                for b in &m.boundary {
                    // the half's edges and their mirror images; the cut is not outline
                    let halved = !v.whole_part;
                    if halved && b.nodes.iter().all(|&n| m.nodes[n][0].abs() < 1e-12) {
                        continue;
                    }
                    let pts: Vec<(f64, f64)> = b
                        .nodes
                        .iter()
                        .map(|&n| {
                            let p = m.nodes[n];
                            let d = [f.displacement[2 * n], f.displacement[2 * n + 1]];
                            ((p[0] + k * d[0]) * 1e3, (p[1] + k * d[1]) * 1e3)
                        })
                        .collect();
                    let mirrored: Vec<(f64, f64)> = pts.iter().map(|p| (-p.0, p.1)).collect();
                    chart.draw_series(std::iter::once(PathElement::new(
                        pts,
                        style.stroke_width(2),
                    )))?;
                    if halved {
                        chart.draw_series(std::iter::once(PathElement::new(
                            mirrored,
                            style.stroke_width(2),
                        )))?;
                    }
                }
            }
        }
        Ok(())
    })
}

/// The table the command line prints: FE (both idealizations) against the analytic model,
/// in the style of paper 004's Table 2.
pub struct VerifyTable<'a>(pub &'a VerifyReport);

/// `v` with `digits` significant digits, in plain decimals.
fn significant(v: f64, digits: i32) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let decimals = (digits - 1 - v.abs().log10().floor() as i32).max(0) as usize;
    format!("{v:.decimals$}")
}

/// A value in the unit a designer reads, with that unit.
fn shown(o: &OutputReport, v: f64) -> (f64, &str) {
    let unit = match o.display.name.as_str() {
        "1" => "",
        name => name,
    };
    (o.display.from_si(v), unit)
}

impl Display for VerifyTable<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        let r = self.0;
        let finest = r.levels.last();
        writeln!(
            s,
            "{}: finite-element check (paper 004 Sec. 4.1), {} meshes, the finest {} elements on \
             the {} part, in {:.2} s; errors estimated by Richardson extrapolation{}",
            r.problem,
            r.levels.len(),
            finest.map_or(0, |l| l.elements),
            if r.whole_part { "whole" } else { "half" },
            r.seconds,
            match (&r.budget_stop, r.converged) {
                (_, true) => String::new(),
                (Some(stop), false) => format!(
                    " (NOT all within {} %: stopped, {stop})",
                    percent(r.tolerance)
                ),
                (None, false) => format!(" (NOT all within {} %)", percent(r.tolerance)),
            }
        )?;
        let columns: Vec<(&str, &IndexMap<&'static str, OutputReport>)> =
            r.outputs.iter().map(|(k, m)| (*k, m)).collect();
        let read = key(r.read);
        let title = |k: &str| match k {
            "plane_stress" => "FE plane stress",
            "plane_strain" => "FE plane strain",
            _ => "FE 3D",
        };
        let mut head = format!("{:<21}", "");
        for (k, _) in &columns {
            head += &format!(" {:>24}", title(k));
        }
        head += &format!(
            " {:>10} {:>20}",
            "analytic",
            format!("deviation ({})", r.read.name())
        );
        writeln!(s, "{}", head.trim_end())?;
        let (_, first) = columns[0];
        for (name, a) in first {
            let (_, unit) = shown(a, 1.0);
            let cell = |o: Option<&OutputReport>| {
                let Some(o) = o else {
                    return "-".to_string();
                };
                let (v, _) = shown(o, o.estimate.value);
                let e = &o.estimate;
                match e.relative_error {
                    Some(r) if e.converging => {
                        format!("{} (+-{} %)", significant(v, 5), significant(100.0 * r, 2))
                    }
                    // the spread of a sequence that turns bounds its error
                    Some(r) if e.oscillating => {
                        format!(
                            "{} (+-{} % spread)",
                            significant(v, 5),
                            significant(100.0 * r, 2)
                        )
                    }
                    _ => format!("{} (not conv.)", significant(v, 5)),
                }
            };
            let analytic = a
                .analytic
                .map_or("-".to_string(), |v| significant(shown(a, v).0, 5));
            let deviation = r
                .outputs
                .get(read)
                .and_then(|m| m.get(name))
                .and_then(|o| o.deviation_percent)
                .map_or("-".to_string(), |x| format!("{x:+.1} %"));
            let label = if unit.is_empty() {
                name.to_string()
            } else {
                format!("{name} ({unit})")
            };
            let mut line = format!("{label:<21}");
            for (_, m) in &columns {
                line += &format!(" {:>24}", cell(m.get(name)));
            }
            writeln!(s, "{line} {analytic:>10} {deviation:>20}")?;
        }
        for name in &r.not_measured_on_the_part {
            writeln!(
                s,
                "{name:<21} {:>24}",
                "not measured on the part (model only)"
            )?;
        }
        let forces: Vec<String> = r
            .actuation_force
            .iter()
            .map(|(k, f)| format!("{f:.1} N {}", title(k).trim_start_matches("FE ")))
            .collect();
        writeln!(
            s,
            "{}stresses at the actuation force ({}{})",
            r.displacements_at,
            forces.join(", "),
            r.analytic_actuation_force
                .map_or(String::new(), |f| format!(", analytic {f:.1} N"))
        )?;
        let solid = match &r.solid_note {
            Some(why) => format!("no 3D check: {why}"),
            None => {
                let largest = r.solid_solves.iter().map(|s| s.dofs).max().unwrap_or(0);
                format!(
                    "3D: the finest plane strain times 3D / plane strain from {} solves through \
                     the half-width (1 to {} graded layers, the largest {} degrees of freedom)",
                    r.solid_solves.len(),
                    r.solid_solves.iter().map(|s| s.layers).max().unwrap_or(0),
                    largest
                )
            }
        };
        if let Some(why) = &r.modal_note {
            writeln!(s, "no natural frequencies: {why}")?;
        }
        if !r.not_measured_on_the_part.is_empty() {
            writeln!(
                s,
                "NOT verified on the part: its check does not measure {}, which the constraints \
                 name",
                r.not_measured_on_the_part.join(", ")
            )?;
        }
        write!(s, "{}", VerdictLines(&r.verdict))?;
        writeln!(
            s,
            "{solid}; the plate is {:.3} times as wide as its thinnest hinge is thick: read {} \
             (plane stress below {}, plane strain above {}, 3D between)",
            r.width_over_thickness,
            r.read.name(),
            crate::fe::element::SOLID_RULE.0,
            crate::fe::element::SOLID_RULE.1
        )
    }
}
