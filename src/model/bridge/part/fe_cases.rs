//! The bridge's finite-element check (paper 004, Sec. 4.1), stated on its part: the lower
//! output block's clamping face held, the test force on each input face along the
//! actuator's axis, the test force on the output face with the input faces free, the
//! stresses under the actuation `true stroke * k_in + preload` (the stroke the actuator
//! makes against the part's `k_in`, paper 004's Eq. 13); the payload on the output
//! face and the actuator between the input faces for the modes. Each output is comparable
//! with the analytic output of the same meaning:
//!
//! - `x_in`: the increase of the distance between the input faces' mean positions under the
//!   test force on each; `k_in = force / x_in` (the analytic `k_in` is the same face-to-face
//!   stiffness, `1 / a11`).
//! - `y_out`: the output face's mean displacement towards the actuator's axis under the same
//!   load; `amplification = y_out / x_in` (positive when the output face moves inward as the
//!   input faces move apart, the sign of the analytic `amplification` of a bridge whose arms
//!   rise towards the output blocks).
//! - `k_out = force / (mean displacement of the output face)` under the test force on it,
//!   the input faces free (the analytic `k_out`).
//! - the section stress is what Eq. 12-17 predict (`stress_beam_max`); the peak stress is the
//!   part's real one, at a fillet (`stress_max`'s counterpart).
//! - under the stack (a spring of its stiffness between the input faces, driven by its free
//!   stroke, [`crate::part::analysis::Ports`]): `stroke_in`, `stroke_out`, `k_out_actuated`
//!   (`k_out` with the stack in place), the output's stiffness with the input faces held and
//!   the force that holds the output still under the stroke (no model output has these two).
//! - the output frequency is the analytic `output_frequency` (and `natural_frequency`); the
//!   lowest mode of either symmetry is `first_frequency`'s, which the model has no closed
//!   form of (its value is the output mode's).

use super::super::BridgeOutput;
use crate::model::Dimension;
use crate::part::analysis::{
    actuated_outputs, Actuated, ActuationCase, Analysis, Comparison, FeCounterpart, FeOutput,
    FeOutputId, Load, LoadCase, Measure, Modal, Ports, Quantity, Spring, Term,
};

/// The faces the part names ([`super::spec`]).
pub(super) const INPUT_LEFT: &str = "input_left";
pub(super) const INPUT_RIGHT: &str = "input_right";
pub(super) const OUTPUT_TOP: &str = "output_top";
pub(super) const CLAMP_BOTTOM: &str = "clamp_bottom";

// the outputs' places in the check's list
const AMPLIFICATION: usize = 2;
const K_IN: usize = 3;
const K_OUT: usize = 4;
const STRESS_SECTION: usize = 5;
const STRESS_MAX: usize = 6;
const OUTPUT_FREQUENCY: usize = 7;
const FIRST_FREQUENCY: usize = 8;
/// The first of the outputs under the stack ([`actuated_outputs`]).
const ACTUATED: usize = 9;

fn load(face: &str, direction: [f64; 2]) -> Load {
    Load {
        face: face.into(),
        direction,
        share: 1.0,
    }
}

fn term(face: &str, direction: [f64; 2]) -> Term {
    Term {
        weight: 1.0,
        face: face.into(),
        direction,
    }
}

fn output(
    name: &'static str,
    dimension: Dimension,
    meaning: &'static str,
    quantity: Quantity,
    display: Option<&'static str>,
) -> FeOutput {
    FeOutput {
        name,
        dimension,
        meaning,
        quantity,
        converges: true,
        display,
        analytic: None,
    }
}

/// The check, the same for every design.
pub fn analysis() -> Analysis {
    // displacements in um beside the part's mm; the rest in their dimension's usual unit
    let um = Some("um");
    let (k_in, amplification) = (
        BridgeOutput::KIn as usize,
        BridgeOutput::Amplification as usize,
    );
    let mut outputs = vec![
        FeOutput {
            analytic: Some(Comparison::PerTestForce {
                stiffness: k_in,
                times: None,
            }),
            ..output(
                "fe_x_in",
                Dimension::Length,
                "increase of the distance between the input faces under the test force",
                Quantity::Displacement(0),
                um,
            )
        },
        FeOutput {
            analytic: Some(Comparison::PerTestForce {
                stiffness: k_in,
                times: Some(amplification),
            }),
            ..output(
                "fe_y_out",
                Dimension::Length,
                "output face's displacement towards the axis under the same load",
                Quantity::Displacement(1),
                um,
            )
        },
        output(
            "fe_amplification",
            Dimension::Ratio,
            "y_out / x_in",
            Quantity::Ratio {
                numerator: 1,
                denominator: 0,
            },
            None,
        ),
        output("fe_k_in", Dimension::Stiffness, "test force / x_in", Quantity::Stiffness(0), None),
        output(
            "fe_k_out",
            Dimension::Stiffness,
            "test force on the output face / its displacement, inputs free",
            Quantity::Stiffness(2),
            Some("N/mm"),
        ),
        FeOutput {
            analytic: Some(Comparison::Output(BridgeOutput::StressMax as usize)),
            ..output(
                "fe_stress_section",
                Dimension::Stress,
                "largest beam stress |N|/(w t) + 6|M|/(w t^2) at the hinges' root sections under the actuation",
                Quantity::SectionStress,
                None,
            )
        },
        FeOutput {
            converges: false,
            ..output(
                "fe_stress_max",
                Dimension::Stress,
                "largest nodal von Mises stress under the actuation",
                Quantity::PeakStress,
                None,
            )
        },
        output(
            "fe_output_frequency",
            Dimension::Frequency,
            "lowest symmetric (output) mode",
            Quantity::SymmetricFrequency,
            None,
        ),
        output(
            "fe_natural_frequency",
            Dimension::Frequency,
            "lowest mode of either symmetry",
            Quantity::LowestFrequency,
            None,
        ),
    ];
    debug_assert_eq!(outputs.len(), ACTUATED);
    let ports = Ports {
        input: 0,
        output: 1,
        output_loaded: 2,
        input_by_output: 3,
    };
    outputs.extend(actuated_outputs(ports, Some("N/mm")));
    Analysis {
        clamped: vec![CLAMP_BOTTOM.into()],
        cases: vec![
            LoadCase {
                name: "on each input face, pushing them apart".into(),
                loads: vec![load(INPUT_LEFT, [-1.0, 0.0]), load(INPUT_RIGHT, [1.0, 0.0])],
            },
            LoadCase {
                name: "on the output face, the input faces free".into(),
                loads: vec![load(OUTPUT_TOP, [0.0, 1.0])],
            },
        ],
        measures: vec![
            // x_in: the right face's outward displacement first, then the left one's
            Measure {
                case: 0,
                terms: vec![term(INPUT_RIGHT, [1.0, 0.0]), term(INPUT_LEFT, [-1.0, 0.0])],
            },
            // y_out: the output face towards the actuator's axis
            Measure {
                case: 0,
                terms: vec![term(OUTPUT_TOP, [0.0, -1.0])],
            },
            // the output face along its load
            Measure {
                case: 1,
                terms: vec![term(OUTPUT_TOP, [0.0, 1.0])],
            },
            // x_in under the output's load, negated: per force towards the axis, the way
            // y_out reads the output (the stack and the output as two ports)
            Measure {
                case: 1,
                terms: vec![
                    Term {
                        weight: -1.0,
                        ..term(INPUT_RIGHT, [1.0, 0.0])
                    },
                    Term {
                        weight: -1.0,
                        ..term(INPUT_LEFT, [-1.0, 0.0])
                    },
                ],
            },
        ],
        outputs,
        actuation: Some(ActuationCase {
            name: "fe_actuation_force",
            case: 0,
            stiffness: FeOutputId(K_IN),
        }),
        modal: Some(Modal {
            payload: OUTPUT_TOP.into(),
            actuator: Some(Spring {
                faces: [INPUT_LEFT.into(), INPUT_RIGHT.into()],
                direction: [1.0, 0.0],
            }),
            start: 1,
        }),
    }
}

/// The check's output that measures the bridge's output `output`.
pub fn counterpart(output: BridgeOutput) -> Option<FeCounterpart> {
    use BridgeOutput::*;
    let id = |k| Some(FeCounterpart::Output(FeOutputId(k)));
    match output {
        Amplification => id(AMPLIFICATION),
        KIn => id(K_IN),
        KOut => id(K_OUT),
        // the part's real peak (at a fillet); the beam stress the model computes is
        // stress_beam_max's counterpart
        StressMax => id(STRESS_MAX),
        StressBeamMax => id(STRESS_SECTION),
        ForceInMax => Some(FeCounterpart::ActuationForce),
        NaturalFrequency | OutputFrequency => id(OUTPUT_FREQUENCY),
        FirstFrequency => id(FIRST_FREQUENCY),
        StrokeIn => Some(FeCounterpart::Output(Actuated::StrokeIn.id(ACTUATED))),
        StrokeOut => Some(FeCounterpart::Output(Actuated::StrokeOut.id(ACTUATED))),
        KOutActuated => Some(FeCounterpart::Output(Actuated::KOutActuated.id(ACTUATED))),
        _ => None,
    }
}
