//! `flexopt stroke`'s set: a network's outputs over its working stroke with its flexures'
//! large deflection, each beside the linear model's (`stroke.csv`, `stroke.svg`,
//! `stroke.json`), and the terminal's table of the full stroke.
//!
//! The linear value at a fraction of the stroke is the report's linear point
//! ([`StrokeReport::linear`]) scaled by the fraction for a motion or a stress, the same for a
//! stiffness or an amplification ([`Linear`]).

use std::fmt::{self, Display, Write as _};
use std::path::{Path, PathBuf};

use indexmap::IndexMap;
use serde::Serialize;

use super::folder::OutputSet;
use super::{write_atomic, write_json, WriteError};
use crate::model::large::report::{StrokeOptions, StrokePoint, StrokeReport};
use crate::problem::display::{csv, human};
use crate::problem::Problem;

mod figure;

/// The files of the set, in the order they are written.
pub const STROKE_FILES: [&str; 3] = ["stroke.csv", "stroke.svg", "stroke.json"];

/// How a quantity of the linear model follows the stroke.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Linear {
    /// In proportion to the fraction of the stroke (a motion, a stress).
    Scaled,
    /// The same over the stroke (a stiffness, an amplification).
    Constant,
}

/// One quantity of a point of the stroke, in the unit a person reads.
pub struct Column {
    /// Its CSV column, with its unit (`stroke_out_um`).
    pub name: String,
    /// Its name without the unit (`stroke_out`).
    pub label: String,
    /// The unit it is shown in (empty for a ratio).
    pub unit: &'static str,
    pub linear: Linear,
    /// From SI to `unit`.
    scale: f64,
    get: Box<dyn Fn(&StrokePoint) -> f64>,
}

impl Column {
    fn new(
        label: String,
        unit: &'static str,
        scale: f64,
        linear: Linear,
        get: impl Fn(&StrokePoint) -> f64 + 'static,
    ) -> Self {
        let tag = unit.replace('/', "_per_");
        let name = if tag.is_empty() {
            label.clone()
        } else {
            format!("{label}_{tag}")
        };
        Column {
            name,
            label,
            unit,
            linear,
            scale,
            get: Box::new(get),
        }
    }

    /// Its value at the point `p`, in its unit.
    pub fn value(&self, p: &StrokePoint) -> f64 {
        (self.get)(p) * self.scale
    }

    /// The linear model's value at `fraction` of the stroke, from its point `linear` at the
    /// full stroke.
    pub fn linear_at(&self, linear: &StrokePoint, fraction: f64) -> f64 {
        match self.linear {
            Linear::Scaled => self.value(linear) * fraction,
            Linear::Constant => self.value(linear),
        }
    }
}

/// The quantities of `report`'s points: the strokes, amplifications, stiffnesses, the
/// largest stress, each flexure's stress, each output port's parasitic motion and the
/// natural frequencies (where the network has them: the linear model's beside, the same
/// over the stroke).
pub fn columns(report: &StrokeReport) -> Vec<Column> {
    let (um, mpa, n_per_um) = (1e6, 1e-6, 1e-6);
    let mut c = vec![
        Column::new("stroke_in".into(), "um", um, Linear::Scaled, |p| {
            p.stroke_in
        }),
        Column::new("stroke_out".into(), "um", um, Linear::Scaled, |p| {
            p.stroke_out
        }),
        Column::new("amplification".into(), "", 1.0, Linear::Constant, |p| {
            p.amplification
        }),
        Column::new(
            "amplification_tangent".into(),
            "",
            1.0,
            Linear::Constant,
            |p| p.amplification_tangent,
        ),
        Column::new("k_in".into(), "N/um", n_per_um, Linear::Constant, |p| {
            p.k_in
        }),
        Column::new("k_out".into(), "N/um", n_per_um, Linear::Constant, |p| {
            p.k_out
        }),
        Column::new("stress_max".into(), "MPa", mpa, Linear::Scaled, |p| {
            p.stress_max
        }),
    ];
    for (i, name) in report.flexures.iter().enumerate() {
        let label = format!("stress_{name}");
        c.push(Column::new(label, "MPa", mpa, Linear::Scaled, move |p| {
            p.stresses[i]
        }));
    }
    for (i, name) in report.outputs.iter().enumerate() {
        let across = format!("parasitic_across_{name}");
        c.push(Column::new(across, "um", um, Linear::Scaled, move |p| {
            p.parasitic[i].across
        }));
        let rotation = format!("parasitic_rotation_{name}");
        c.push(Column::new(
            rotation,
            "mrad",
            1e3,
            Linear::Scaled,
            move |p| p.parasitic[i].rotation,
        ));
    }
    for i in 0..report.linear.frequencies.len() {
        let label = format!("f{}", i + 1);
        c.push(Column::new(label, "Hz", 1.0, Linear::Constant, move |p| {
            p.frequencies[i]
        }));
    }
    c
}

/// `|a - b|` relative to the larger of the two (0 where both are 0).
fn relative(a: f64, b: f64) -> Option<f64> {
    let size = a.abs().max(b.abs());
    let r = if size == 0.0 {
        0.0
    } else {
        (a - b).abs() / size
    };
    r.is_finite().then_some(r)
}

/// `stroke.json`: the report over the stroke (SI: m, N/m, Pa, rad), with what it was solved
/// at and the convergence estimate of each quantity.
#[derive(Debug, Clone, Serialize)]
pub struct StrokeRun {
    pub problem: String,
    pub model: String,
    /// What the values are: the model with its flexures' large deflection.
    pub fidelity: String,
    /// The design, in the problem file's units.
    pub design: IndexMap<String, f64>,
    pub units: &'static str,
    /// Load steps from the unloaded part to the full stroke.
    pub steps: usize,
    /// The force (N) that drives the input in the actuator's place; `None`: the actuator.
    pub force: Option<f64>,
    /// The critical load factor is looked for up to this multiple of the stroke.
    pub critical_up_to: f64,
    /// The outputs at the full stroke (the curve's last point).
    pub at_stroke: StrokePoint,
    /// Each quantity's `|n - 2n|` at the full stroke relative to the larger (n elements a
    /// flexure against twice as many: the discretization error's estimate), by its label.
    pub convergence: IndexMap<String, Option<f64>>,
    #[serde(flatten)]
    pub report: StrokeReport,
}

impl StrokeRun {
    pub fn new(
        problem: &Problem,
        x: &[f64],
        options: &StrokeOptions,
        report: StrokeReport,
    ) -> Self {
        let at_stroke = report.at_stroke().clone();
        let convergence = columns(&report)
            .iter()
            .map(|c| {
                let estimate = report
                    .finer
                    .as_ref()
                    .and_then(|f| relative(c.value(&at_stroke), c.value(f)));
                (c.label.clone(), estimate)
            })
            .collect();
        StrokeRun {
            problem: problem.name.clone(),
            model: problem.model().name().into(),
            fidelity: fidelity(report.elements),
            design: problem.design_in_file_units(x),
            units: "SI (m, N/m, Pa, rad)",
            steps: options.steps,
            force: options.force,
            critical_up_to: options.critical_up_to,
            at_stroke,
            convergence,
            report,
        }
    }
}

/// The fidelity of a solve with `elements` beam elements a flexure.
pub fn fidelity(elements: usize) -> String {
    format!("model, large deflection, {elements} elements a flexure")
}

/// A CSV field: quoted where it holds a comma, a quote or a line break.
fn field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// `stroke.csv`: a row a point of the path, each quantity beside its linear value.
pub fn stroke_csv(report: &StrokeReport) -> String {
    let columns = columns(report);
    let mut s = String::from("fraction");
    for c in &columns {
        let _ = write!(
            s,
            ",{},{}",
            field(&c.name),
            field(&format!("linear_{}", c.name))
        );
    }
    s.push('\n');
    for p in &report.curve {
        s.push_str(&csv(p.fraction));
        for c in &columns {
            let linear = c.linear_at(&report.linear, p.fraction);
            let _ = write!(s, ",{},{}", csv(c.value(p)), csv(linear));
        }
        s.push('\n');
    }
    s
}

/// Writes the set into `dir` in place of the folder's earlier one ([`super::folder`]);
/// returns the paths in place.
pub fn write_stroke_set(dir: &Path, run: &StrokeRun) -> Result<Vec<PathBuf>, WriteError> {
    let set = OutputSet::begin(dir)?;
    set.write(|set| {
        let [csv_file, svg_file, json_file] = STROKE_FILES.map(|f| set.path(f));
        write_atomic(&csv_file, stroke_csv(&run.report).as_bytes())?;
        figure::stroke_svg(&svg_file, run)?;
        write_json(&json_file, run)
    })?;
    set.commit(&STROKE_FILES)
}

/// The terminal's table: each quantity at the full stroke, large against linear, with its
/// convergence estimate; the critical load factor.
pub struct StrokeTable<'a>(pub &'a StrokeRun);

impl Display for StrokeTable<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        let run = self.0;
        let r = &run.report;
        let drive = match run.force {
            Some(f) => format!("a force of {} N at the input", human(f)),
            None => "the actuator's full stroke".into(),
        };
        writeln!(
            s,
            "{} at its working stroke ({drive}): {}, the linear model beside",
            run.problem, run.fidelity
        )?;
        writeln!(
            s,
            "{:<28} {:>12} {:>12} {:>12} {:>10}  unit",
            "at full stroke", "large", "linear", "large/linear", "|n-2n|"
        )?;
        for c in columns(r) {
            let (large, linear) = (c.value(&run.at_stroke), c.linear_at(&r.linear, 1.0));
            let ratio = if linear == 0.0 {
                "-".into()
            } else {
                format!("{:.4}", large / linear)
            };
            let estimate = run.convergence.get(&c.label).copied().flatten();
            let estimate = estimate.map_or("-".into(), |e| format!("{e:.1e}"));
            let line = format!(
                "{:<28} {:>12} {:>12} {:>12} {:>10}  {}",
                c.label,
                human(large),
                human(linear),
                ratio,
                estimate,
                c.unit
            );
            writeln!(s, "{}", line.trim_end())?;
        }
        match r.critical_load_factor {
            Some(c) => writeln!(
                s,
                "critical load factor: {} x the stroke (the tangent stiffness stops being \
                 positive definite)",
                human(c)
            ),
            None => writeln!(
                s,
                "critical load factor: none up to {} x the stroke",
                human(run.critical_up_to)
            ),
        }?;
        writeln!(
            s,
            "|n-2n|: the change at the full stroke with {} elements a flexure, relative",
            2 * r.elements
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_with_commas_are_quoted() {
        assert_eq!(field("stress_b_MPa"), "stress_b_MPa");
        assert_eq!(field("a,b"), "\"a,b\"");
        assert_eq!(field("a\"b"), "\"a\"\"b\"");
    }

    #[test]
    fn relative_of_zeros_is_zero() {
        assert_eq!(relative(0.0, 0.0), Some(0.0));
        assert_eq!(relative(2.0, 1.0), Some(0.5));
        assert_eq!(relative(f64::NAN, 1.0), None);
    }
}
