//! Issue 51, item 4: a stroke of micrometres reads in micrometres wherever a person reads
//! it. lever_network maximizing its tip's stroke (tens of micrometres, no unit in the file
//! for it): the terminal's table, the refinement's table, `starts.csv`'s header and the
//! report's headline give it in um, the value the model's SI one times 1e6.

use crate::common;

use std::path::{Path, PathBuf};

use common::flexopt_ok;
use flexopt::model::Dimension;
use flexopt::problem::design::default_design;
use flexopt::problem::refine::RefineSettings;
use flexopt::problem::Problem;
use flexopt::refine::study::StudyRefinement;
use flexopt::refine::{refine, HighFidelity, Measurement};
use flexopt::report::display::human;
use flexopt::report::refine::{RefineSummary, RefinedReport};
use flexopt::report::table::DesignTable;
use flexopt::report::DesignReport;
use flexopt::vocab::units::Unit;

/// problems/lever_network.toml maximizing stroke_out over 8 starts, written into `dir`.
fn stroke_lever(dir: &Path) -> (PathBuf, Problem) {
    let text = std::fs::read_to_string("problems/lever_network.toml")
        .unwrap()
        .replacen(
            "maximize = \"amplification\"",
            "maximize = \"stroke_out\"",
            1,
        )
        .replacen("starts = 300", "starts = 8", 1);
    assert!(text.contains("maximize = \"stroke_out\"") && text.contains("starts = 8\n"));
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(dir).unwrap();
    let file = dir.join("lever.toml");
    std::fs::write(&file, &text).unwrap();
    let p = Problem::parse(&file, &text).unwrap();
    (file, p)
}

fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("flexopt-units-{}-{name}", std::process::id()))
}

/// stroke_out at `x`, SI.
fn stroke(p: &Problem, x: &[f64]) -> f64 {
    let model = p.model();
    let mut out = [0.0];
    model.evaluate(x, &[model.output_index("stroke_out").unwrap()], &mut out);
    assert!(
        out[0] > 1e-6 && out[0] < 1e-3,
        "a stroke of micrometres: {}",
        out[0]
    );
    out[0]
}

/// The number in `text` right after `before`, up to the next space.
fn number_after(text: &str, before: &str) -> f64 {
    let at = text
        .find(before)
        .unwrap_or_else(|| panic!("{before:?} not in {text}"));
    let rest = text[at + before.len()..].trim_start();
    rest.split_whitespace().next().unwrap().parse().unwrap()
}

/// `si` as the reports write it in um.
fn in_um(si: f64) -> String {
    human(Unit::parse("um", Dimension::Length).unwrap().from_si(si))
}

fn assert_micrometres(shown: f64, si: f64, what: &str) {
    assert!(
        (shown - si * 1e6).abs() <= 1e-5 * si * 1e6,
        "{what}: {shown} against {} um",
        si * 1e6
    );
}

#[test]
fn the_terminal_table_shows_a_micrometre_stroke_in_micrometres() {
    let (_, p) = stroke_lever(&scratch("table"));
    let x = default_design(&p);
    let si = stroke(&p, &x);
    let report = DesignReport::new(&p, &x);
    let table = DesignTable {
        problem: &p,
        report: &report,
    }
    .to_string();
    let line = table
        .lines()
        .find(|l| l.trim_start().starts_with("stroke_out "))
        .unwrap();
    assert!(line.trim_end().ends_with(" um"), "{line}");
    assert_micrometres(number_after(line, "stroke_out"), si, line);
    assert_micrometres(
        number_after(&table, "maximize stroke_out ="),
        si,
        "objective",
    );
    assert!(table.contains(&format!("{} um", in_um(si))), "{table}");
}

/// A high fidelity that is the model itself: the refinement has nothing to correct.
struct Model(Problem);

impl HighFidelity for Model {
    fn describe(&self) -> String {
        "the model".into()
    }
    fn measures(&self, _x: &[f64], _output: usize) -> bool {
        true
    }
    fn measure(&self, x: &[f64], outputs: &[usize]) -> Result<Measurement, String> {
        let mut values = vec![0.0; outputs.len()];
        self.0.model().evaluate(x, outputs, &mut values);
        Ok(Measurement {
            values,
            errors: vec![None; outputs.len()],
            margins: vec![0.0; outputs.len()],
            detail: serde_json::Value::Null,
        })
    }
}

#[test]
fn the_refinement_table_shows_a_micrometre_stroke_in_micrometres() {
    let (_, p) = stroke_lever(&scratch("refine"));
    let x = default_design(&p);
    let si = stroke(&p, &x);
    let settings = RefineSettings {
        enabled: true,
        max_fe: 3,
        ..RefineSettings::default()
    };
    let r = refine(&p, &x, &Model(p.clone()), &settings);
    let study = StudyRefinement {
        all: vec![(0, r)],
        chosen: 0,
        spread: None,
    };
    let report = RefinedReport::new(&p, &settings, &study);
    let optimum = report.analytic_optimum.as_ref().unwrap();
    let row = optimum
        .outputs
        .iter()
        .find(|o| o.output == "stroke_out")
        .unwrap();
    assert_eq!(row.unit, "um");
    assert_micrometres(row.analytic, si, "refined.json");
    let table = RefineSummary(&report).to_string();
    assert_micrometres(number_after(&table, "stroke_out (um)"), si, &table);
    assert!(!table.contains("stroke_out (m)"), "{table}");
}

#[test]
fn the_run_its_csv_and_its_report_show_a_micrometre_stroke_in_micrometres() {
    let dir = scratch("report");
    let (file, p) = stroke_lever(&dir);
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    flexopt_ok(&[
        "run",
        file.to_str().unwrap(),
        "--quiet",
        "--report",
        "--out",
        o,
    ]);
    let optimum: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("optimum.json")).unwrap()).unwrap();
    assert_eq!(optimum["feasible"], true);
    assert_eq!(optimum["display_units"]["stroke_out"], "um");
    let x: Vec<f64> = p
        .variables
        .iter()
        .map(|v| optimum["design_si"][&v.name].as_f64().unwrap())
        .collect();
    let si = stroke(&p, &x);
    let csv = std::fs::read_to_string(out.join("starts.csv")).unwrap();
    assert!(
        csv.lines()
            .next()
            .unwrap()
            .contains(",objective_stroke_out_um,"),
        "{}",
        csv.lines().next().unwrap()
    );
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    let headline = format!("maximize stroke_out = <strong>{} um</strong>", in_um(si));
    assert!(html.contains(&headline), "{headline} not in the report");
    let _ = std::fs::remove_dir_all(&dir);
}
