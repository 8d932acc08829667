//! Paper 004 (Wei et al. 2017), Tables 2 and 3: the analytical columns at Table 1's optimum.

use crate::common;

use common::*;
use flexopt::model::bridge::{BridgeOutput, OUTPUTS};
use flexopt::model::Model;

fn outputs_at_optimum() -> impl Fn(&str) -> f64 {
    let model = wei2017();
    let wanted: Vec<usize> = (0..BridgeOutput::ALL.len()).collect();
    let mut out = vec![0.0; wanted.len()];
    Model::evaluate(&model, &table1_optimum(), &wanted, &mut out);
    move |name| out[OUTPUTS.iter().position(|o| o.name == name).unwrap()]
}

/// Rounds to `digits` significant digits, as the paper prints.
#[test]
fn table2_displacements_under_the_fea_input_force_of_10_newton() {
    let out = outputs_at_optimum();
    let (x_in, y_out) = (out("a11") * 10.0, out("a21") * 10.0);
    assert_eq!(printed(y_out * 1e6, 3), 18.3, "Yout = {} um", y_out * 1e6);
    assert_eq!(printed(x_in * 1e6, 3), 1.42, "Xin = {} um", x_in * 1e6);
}

#[test]
fn table2_stiffnesses() {
    let out = outputs_at_optimum();
    assert_eq!(printed(out("k_in"), 3), 7.02e6, "Kin = {}", out("k_in"));
    assert_eq!(printed(out("k_out"), 2), 3.8e4, "Kout = {}", out("k_out"));
}

#[test]
fn table3_amplification() {
    let out = outputs_at_optimum();
    assert_eq!(
        printed(out("amplification"), 4),
        12.86,
        "da = {}",
        out("amplification")
    );
}

#[test]
fn table2_stress_within_one_percent() {
    let out = outputs_at_optimum();
    let s = out("stress_max");
    assert!(rel(s, 148e6, 1.0) < 0.01, "sigma_max = {} MPa", s / 1e6);
    // the aligned optimum has equal hinges: both carry the same stress
    assert!(rel(out("stress_b"), out("stress_d"), 1.0) < 1e-12);
}

#[test]
fn stroke_convention() {
    let out = outputs_at_optimum();
    // no actuator stiffness given: the true stroke is the nominal one (Eq. 13, k_pzt -> inf)
    assert_eq!(out("stroke_in"), 17.4e-6);
    assert!(rel(out("stroke_out"), out("amplification") * 17.4e-6, 1.0) < 1e-15);
    // Eq. 12, 14
    assert!(rel(out("force_in_max"), 17.4e-6 * out("k_in") + 40.0, 1.0) < 1e-15);
}
