//! The part driven by its stack (issue 47): the check's outputs under the stack against the
//! identities of linear elasticity, level by level on the same meshes. The stroke under a
//! rigid stack is the free stroke and the output's the amplification times it; under a soft
//! one paper 004's Eq. 13 with the FE's own `k_in`; the output's stiffness with the stack in
//! place the Thevenin stiffness of the part's two-port compliance matrix, whose entries the
//! test measures itself, by separate loads on each port (its own measure of the input under
//! the output's load added to the part's statement). And the check of wei2017's optimum
//! shows the model's strokes and actuated stiffness beside the FE's; a constraint on an
//! output the part's check cannot measure is listed as not measured, never passed over.

use std::path::Path;

use flexopt::fe::element::Elastic;
use flexopt::fe::verify::{verify, Verification, VerifySettings};
use flexopt::part::analysis::{FeOutput, Measure, Quantity};
use flexopt::part::PartSpec;
use flexopt::problem::design::design_from_optimum;
use flexopt::problem::Problem;
use flexopt::report::verify::{VerifyReport, VerifyTable};
use flexopt::vocab::Dimension;

/// The test's own output: the input read as the part's `k_in` reads it, under the output's
/// load case.
const INPUT_BY_OUTPUT: &str = "test_input_by_output";

fn loaded(file: &str) -> (Problem, Vec<f64>) {
    let problem = Problem::load(Path::new(&format!("problems/{file}.toml"))).unwrap();
    let optimum = format!("results/{file}/optimum.json");
    let x = design_from_optimum(&problem, Path::new(&optimum))
        .unwrap()
        .x;
    (problem, x)
}

/// The part of `problem` at `x`, its statement with the test's measure added, and its actuator's
/// stiffness set to `stiffness`.
fn stated(problem: &Problem, x: &[f64], stiffness: Option<f64>) -> PartSpec {
    let mut spec = problem.mechanism().part_spec(x).unwrap().unwrap();
    let a = spec.analysis.as_mut().unwrap();
    let stroke = a.actuation.unwrap().stiffness.0;
    let Quantity::Stiffness(input) = a.outputs[stroke].quantity else {
        panic!("the actuation is scaled by a stiffness");
    };
    // the output's case: the case its stiffness `fe_k_out` is read under
    let k_out = a.output("fe_k_out").unwrap().0;
    let Quantity::Stiffness(output) = a.outputs[k_out].quantity else {
        panic!("fe_k_out is a stiffness");
    };
    let case = a.measures[output].case;
    let terms = a.measures[input].terms.clone();
    a.measures.push(Measure { case, terms });
    a.outputs.push(FeOutput {
        name: INPUT_BY_OUTPUT,
        dimension: Dimension::Length,
        meaning: "the input under the output's load",
        quantity: Quantity::Displacement(a.measures.len() - 1),
        converges: true,
        display: None,
        analytic: None,
    });
    spec.actuation.as_mut().unwrap().stiffness = stiffness;
    spec
}

fn checked(problem: &Problem, spec: &PartSpec) -> Verification {
    let m = problem.model().material().unwrap();
    let material = Elastic {
        youngs_modulus: m.youngs_modulus,
        poisson_ratio: m.poisson_ratio,
        density: m.density,
    };
    let settings = VerifySettings {
        max_levels: 3,
        modal: false,
        ..VerifySettings::default()
    };
    verify(spec, &material, &settings).unwrap()
}

/// Each idealization's values of `name` on each mesh, then the 3D estimate's.
fn values(v: &Verification, name: &str) -> Vec<Vec<f64>> {
    let of = |outputs: &[flexopt::fe::verify::Output]| -> Vec<f64> {
        outputs
            .iter()
            .find(|o| o.name == name)
            .unwrap()
            .values
            .clone()
    };
    v.results.iter().map(|r| of(&r.outputs)).collect()
}

fn close(a: f64, b: f64, tolerance: f64, what: &str) {
    assert!(
        (a - b).abs() <= tolerance * b.abs(),
        "{what}: {a} against {b} ({:.3e} relative)",
        (a - b) / b
    );
}

/// The identities of the stack on the part: level by level, both idealizations. `sign` turns
/// the output's stroke into its read along the output's load (-1 where they are opposite, the
/// bridge's output moving towards the axis under a load pushing it away).
fn identities(problem: &Problem, x: &[f64], stiffness: Option<f64>, sign: f64) {
    let spec = stated(problem, x, stiffness);
    let stroke = spec.actuation.unwrap().nominal_stroke;
    let v = checked(problem, &spec);
    let force = v.test_force;
    let get = |name| values(&v, name);
    let (k_in, amplification, k_out) = (get("fe_k_in"), get("fe_amplification"), get("fe_k_out"));
    let (stroke_in, stroke_out) = (get("fe_stroke_in"), get("fe_stroke_out"));
    let (actuated, blocked) = (get("fe_k_out_actuated"), get("fe_k_out_blocked"));
    let (held_force, by_output) = (get("fe_blocked_force"), get(INPUT_BY_OUTPUT));
    for k in 0..v.results.len() {
        for level in 0..k_in[k].len() {
            let at = |what: &str| format!("{what}, idealization {k}, level {level}");
            let (kin, a) = (k_in[k][level], amplification[k][level]);
            // Eq. 13 with the FE's own k_in; the free stroke for a rigid stack
            let eq13 = stiffness.map_or(stroke, |ka| stroke * ka / (kin + ka));
            close(stroke_in[k][level], eq13, 1e-9, &at("stroke_in"));
            close(stroke_out[k][level], a * eq13, 1e-9, &at("stroke_out"));
            // the two-port compliances, each from its own load: C_ii and C_oi under the
            // input's, C_oo and C_io under the output's, C_oi and C_io along the output's load
            let c_ii = 1.0 / kin;
            let c_oi = sign * a * c_ii;
            let c_oo = 1.0 / k_out[k][level];
            let c_io = by_output[k][level] / force;
            // Maxwell and Betti: the load on each port does the work the other one's reads
            close(c_io, c_oi, 1e-6, &at("reciprocity"));
            let thevenin = |c_a: f64| 1.0 / (c_oo - c_oi * c_io / (c_ii + c_a));
            let c_a = stiffness.map_or(0.0, |ka| 1.0 / ka);
            close(
                actuated[k][level],
                thevenin(c_a),
                1e-9,
                &at("k_out_actuated"),
            );
            close(blocked[k][level], thevenin(0.0), 1e-9, &at("k_out_blocked"));
            close(
                held_force[k][level],
                a * eq13 * thevenin(c_a),
                1e-9,
                &at("blocked_force"),
            );
            // the stack in place stiffens the output, and holding the input more so
            assert!(
                k_out[k][level] < actuated[k][level] && actuated[k][level] <= blocked[k][level]
            );
        }
    }
    // in 3D the output's stroke is the product it is in every solve; the stroke under the
    // stack Eq. 13 with the 3D k_in to the 3D values' error (each output carries its own
    // ratio of 3D to plane strain, a product's the product of its factors')
    let solid = &v.solid.as_ref().unwrap().outputs;
    let of = |name| solid.iter().find(|o| o.name == name).unwrap().estimate;
    let product = of("fe_amplification").value * of("fe_stroke_in").value;
    close(of("fe_stroke_out").value, product, 1e-9, "3D stroke_out");
    let kin = of("fe_k_in").value;
    let eq13 = stiffness.map_or(stroke, |ka| stroke * ka / (kin + ka));
    let error = of("fe_k_in").relative_error.unwrap();
    close(
        of("fe_stroke_in").value,
        eq13,
        error.max(1e-9),
        "3D stroke_in",
    );
}

#[test]
fn the_bridge_under_a_rigid_stack_makes_its_amplification_times_the_free_stroke() {
    // wei2017's stack is rigid (no stiffness in the file)
    let (problem, x) = loaded("wei2017");
    identities(&problem, &x, None, -1.0);
}

#[test]
fn the_bridge_under_a_soft_stack_makes_eq_13s_stroke_and_its_thevenin_stiffness() {
    let (problem, x) = loaded("wei2017");
    // about the bridge's own input stiffness: the stack loses half its stroke
    identities(&problem, &x, Some(6e6), -1.0);
}

#[test]
fn a_network_under_its_stack_makes_eq_13s_stroke_and_its_thevenin_stiffness() {
    // the lever's stack: 60 N/um; and a rigid one
    let (problem, x) = loaded("lever_network");
    identities(&problem, &x, Some(60e6), 1.0);
    identities(&problem, &x, None, 1.0);
}

#[test]
fn a_very_stiff_stack_acts_as_a_rigid_one() {
    let (problem, x) = loaded("lever_network");
    let check = |stiffness| {
        let v = checked(&problem, &stated(&problem, &x, stiffness));
        let last = |name| *values(&v, name)[1].last().unwrap();
        (last("fe_stroke_out"), last("fe_k_out_actuated"))
    };
    let (rigid, stiff) = (check(None), check(Some(1e15)));
    close(stiff.0, rigid.0, 1e-6, "stroke_out");
    close(stiff.1, rigid.1, 1e-6, "k_out_actuated");
}

/// The table's row of `name`.
fn row<'a>(table: &'a str, name: &str) -> &'a str {
    table
        .lines()
        .find(|l| l.starts_with(&format!("{name} ")))
        .unwrap_or_else(|| panic!("no row {name} in\n{table}"))
}

#[test]
fn verify_of_the_wei2017_optimum_measures_its_strokes_on_the_part() {
    let (problem, x) = loaded("wei2017");
    let v = flexopt::fe::verify::verify_design(problem.mechanism(), &x, &VerifySettings::default())
        .unwrap();
    let report = VerifyReport::new(&problem, &x, &v);
    let table = VerifyTable(&report).to_string();
    let model = problem.model();
    let analytic = |name: &str| {
        let i = model.output_index(name).unwrap();
        let mut out = [0.0];
        model.evaluate(&x, &[i], &mut out);
        out[0]
    };
    for (fe, own, unit) in [
        ("fe_stroke_in", "stroke_in", 1e-6),
        ("fe_stroke_out", "stroke_out", 1e-6),
        ("fe_k_out_actuated", "k_out_actuated", 1e3),
    ] {
        let reported = &report.outputs["plane_stress"][fe];
        let a = reported.analytic.unwrap();
        close(a, analytic(own), 1e-12, fe);
        // the analytic column shows the model's value in the row's unit, where "-" was:
        // the token before the deviation's two ("+8.7 %")
        let line = row(&table, fe);
        let tokens: Vec<&str> = line.split_whitespace().collect();
        let shown: f64 = tokens[tokens.len() - 3]
            .parse()
            .unwrap_or_else(|_| panic!("{line}"));
        close(shown * unit, a, 1e-4, line);
        // a rigid stack makes its free stroke; the model's the same
        if fe == "fe_stroke_in" {
            close(reported.estimate.value, 17.4e-6, 1e-12, fe);
        }
    }
    // every constraint wei2017 names is measured on the part (its spans drawn on it)
    assert!(report.not_measured_on_the_part.is_empty());
    assert!(!table.contains("not measured"), "{table}");
}

#[test]
fn a_constraint_the_part_cannot_measure_is_listed_and_the_design_not_called_verified() {
    let dir = std::env::temp_dir().join(format!("flexopt-actuated-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("wei2017_settling.toml");
    // hinge b's stress has no counterpart on the part (the FE's stresses are the part's)
    let text = std::fs::read_to_string("problems/wei2017.toml").unwrap()
        + "\n[[constraints]]\noutput = \"stress_b\"\nunit = \"MPa\"\nupper = 1000\n";
    std::fs::write(&file, text).unwrap();
    let problem = Problem::load(&file).unwrap();
    let x = design_from_optimum(&problem, Path::new("results/wei2017/optimum.json"))
        .unwrap()
        .x;
    let settings = VerifySettings {
        max_levels: 3,
        modal: false,
        solid: false,
        ..VerifySettings::default()
    };
    let v = flexopt::fe::verify::verify_design(problem.mechanism(), &x, &settings).unwrap();
    let report = VerifyReport::new(&problem, &x, &v);
    assert_eq!(
        report.not_measured_on_the_part,
        vec!["stress_b".to_string()]
    );
    let json = serde_json::to_value(&report).unwrap();
    assert_eq!(json["not_measured_on_the_part"][0], "stress_b");
    let table = VerifyTable(&report).to_string();
    assert!(
        row(&table, "stress_b").contains("not measured on the part"),
        "{table}"
    );
    assert!(table.contains("NOT verified on the part"), "{table}");
    std::fs::remove_dir_all(&dir).unwrap();
}
