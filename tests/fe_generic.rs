//! A part that is not the bridge, with a finite-element check of its own, stated from
//! outside the library with the part layer's types ([`flexopt::part::analysis`]): the
//! verifier knows no model's faces or outputs, so any part that names its faces can be
//! checked.
//!
//! The part: a straight strip clamped at both ends, pushed down at its middle by the test
//! force on a short pad of its upper side. Timoshenko's beam clamped at both ends under a
//! central load `P`, span `S`: `delta = P S^3 / (192 E I) + P S / (4 kappa G A)`; the end
//! moment of the load spread over the pad (`2 c` long), `P (S / 8 - c^2 / (6 S))`, which
//! shear leaves as it is for a symmetric load; the mean deflection along each half of the
//! span half the middle's (the bending shape and the shear's straight line alike).

use flexopt::fe::verify::{verify, Verification, VerifySettings};
use flexopt::fe::{Elastic, Idealization};
use flexopt::part::analysis::{
    ActuationCase, Analysis, FeOutput, FeOutputId, Load, LoadCase, Measure, Quantity, Term,
};
use flexopt::part::{Actuation, Face, HingeSite, PartSpec, Solid};

const STEEL: Elastic = Elastic {
    youngs_modulus: 200e9,
    poisson_ratio: 0.3,
    density: 7800.0,
};

/// The pad's half length, each strip's length and thickness, the plate's width (m): a span
/// 42 times the thickness, the pad a twentieth of it.
const C: f64 = 0.5e-3;
const L: f64 = 10e-3;
const T: f64 = 0.5e-3;
const W: f64 = 10e-3;
/// The actuation: a stroke of the pad (m), no preload.
const STROKE: f64 = 20e-6;

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<[f64; 2]> {
    vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
}

fn face(name: &str, a: [f64; 2], b: [f64; 2]) -> Face {
    Face {
        name: name.into(),
        a,
        b,
    }
}

fn output(name: &'static str, unit: &'static str, quantity: Quantity) -> FeOutput {
    FeOutput {
        name,
        unit,
        meaning: "",
        quantity,
        converges: quantity != Quantity::PeakStress,
        display: (1.0, unit),
        analytic: None,
    }
}

/// The check: the ends clamped, the test force down on the pad; the pad's displacement, the
/// mean deflection of the upper side (each half its own face, the left one read by its
/// mirror on the half), the stiffness, their ratio, the stresses under the stroke.
fn analysis() -> Analysis {
    let down = [0.0, -1.0];
    let term = |face: &str, weight: f64| Term {
        weight,
        face: face.into(),
        direction: down,
    };
    Analysis {
        clamped: vec!["ends".into()],
        cases: vec![LoadCase {
            name: "down on the pad".into(),
            loads: vec![Load {
                face: "pad".into(),
                direction: down,
                share: 1.0,
            }],
        }],
        measures: vec![
            Measure {
                case: 0,
                terms: vec![term("pad", 1.0)],
            },
            Measure {
                case: 0,
                terms: vec![term("upper_right", 0.5), term("upper_left", 0.5)],
            },
        ],
        outputs: vec![
            output("pad", "m", Quantity::Displacement(0)),
            output("upper_side", "m", Quantity::Displacement(1)),
            output("stiffness", "N/m", Quantity::Stiffness(0)),
            output(
                "side_per_pad",
                "1",
                Quantity::Ratio {
                    numerator: 1,
                    denominator: 0,
                },
            ),
            output("stress_section", "Pa", Quantity::SectionStress),
            output("stress_peak", "Pa", Quantity::PeakStress),
        ],
        actuation: Some(ActuationCase {
            name: "actuation_force",
            case: 0,
            stiffness: FeOutputId(2),
        }),
        modal: None,
    }
}

fn spec() -> PartSpec {
    let strip = |name: &str, sign: f64, solid: usize| HingeSite {
        name: name.into(),
        start: [sign * C, 0.0],
        end: [sign * (C + L), 0.0],
        thickness: T,
        root: T,
        fillet: 0.0,
        kind: "strip",
        profile: vec![[0.0, 0.5 * T, 0.0], [L, 0.5 * T, 0.0]],
        solid,
    };
    let (top, bottom, end) = (0.5 * T, -0.5 * T, C + L);
    PartSpec {
        width: W,
        actuation: Some(Actuation {
            nominal_stroke: STROKE,
            preload: 0.0,
            stiffness: None,
            payload_mass: 0.0,
        }),
        analysis: Some(analysis()),
        solids: vec![
            Solid {
                name: "pad".into(),
                points: rect(-C, bottom, C, top),
            },
            Solid {
                name: "right strip".into(),
                points: rect(C, bottom, end, top),
            },
            Solid {
                name: "left strip".into(),
                points: rect(-end, bottom, -C, top),
            },
        ],
        joints: vec![(0, 1), (0, 2)],
        hinges: vec![strip("right strip", 1.0, 1), strip("left strip", -1.0, 2)],
        faces: vec![
            face("pad", [C, top], [-C, top]),
            face("upper_right", [end, top], [0.0, top]),
            face("upper_left", [0.0, top], [-end, top]),
            face("ends", [end, bottom], [end, top]),
            face("ends", [-end, top], [-end, bottom]),
        ],
        annotations: Vec::new(),
        caption: String::new(),
        min_slot: 0.2e-3,
        actuator: None,
        warnings: Vec::new(),
    }
}

fn checked() -> Verification {
    let settings = VerifySettings {
        tolerance: 0.002,
        max_levels: 4,
        modal: false,
        ..VerifySettings::default()
    };
    verify(&spec(), &STEEL, &settings).expect("the part verifies")
}

fn values<'a>(v: &'a Verification, idealization: Idealization, name: &str) -> &'a [f64] {
    let r = v
        .results
        .iter()
        .find(|r| r.idealization == idealization)
        .unwrap();
    &r.outputs.iter().find(|o| o.name == name).unwrap().values
}

/// The finest plane-stress value of `name` and its mesh error: the largest change over the
/// last two refinements, relative. (The clamped faces' corners are singular points that
/// leave the outputs wandering by about 1e-4 as the mesh refines, too irregular for the
/// verifier's Richardson estimate to call converging, and far below the comparisons'
/// tolerances.)
fn estimate(v: &Verification, name: &str) -> (f64, f64) {
    let values = values(v, Idealization::PlaneStress, name);
    let last = values[values.len() - 1];
    let change = values[values.len() - 3..]
        .windows(2)
        .map(|w| ((w[1] - w[0]) / last).abs())
        .fold(0.0, f64::max);
    (last, change)
}

#[test]
fn a_strip_clamped_at_both_ends_verifies_against_timoshenko() {
    let v = checked();
    assert_eq!(v.levels.len(), 4, "the most meshes");
    let (e, nu) = (STEEL.youngs_modulus, STEEL.poisson_ratio);
    let g = e / (2.0 * (1.0 + nu));
    // Cowper's shear coefficient of a rectangle
    let kappa = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
    let (i, area, span) = (W * T.powi(3) / 12.0, W * T, 2.0 * (C + L));
    let k_beam = 1.0 / (span.powi(3) / (192.0 * e * i) + span / (4.0 * kappa * g * area));
    let (k_fe, k_error) = estimate(&v, "stiffness");
    // the mesh's own error is far below the comparison's tolerance, which is the beam
    // theory's: the clamped faces held whole (their warping and Poisson contraction too)
    // and the load on a pad rather than at a point, effects of the order of the shear term
    // itself (4 (t / S)^2 E / (kappa G) = 0.7 % of the bending here) and of (c / S)^2
    // (0.06 %)
    assert!(k_error < 0.001, "the FE stiffness's mesh error {k_error}");
    let deviation = k_fe / k_beam - 1.0;
    eprintln!(
        "stiffness: FE {k_fe:e}, Timoshenko {k_beam:e}, {:+.3} %",
        100.0 * deviation
    );
    assert!(
        deviation.abs() < 0.01,
        "FE {k_fe:e} against beam theory {k_beam:e}"
    );

    let (ratio, r_error) = estimate(&v, "side_per_pad");
    assert!(r_error < 0.001, "the ratio's mesh error {r_error}");
    eprintln!("mean deflection of the upper side / the pad's: {ratio}");
    assert!(
        (ratio - 0.5).abs() < 0.005,
        "mean deflection / pad's {ratio}"
    );

    // the stress under the stroke, at the clamped ends
    let p = k_fe * STROKE;
    let moment = p * (span / 8.0 - C * C / (6.0 * span));
    let sigma = 6.0 * moment / (W * T * T);
    let (s_fe, s_error) = estimate(&v, "stress_section");
    assert!(
        s_error < 0.001,
        "the FE section stress's mesh error {s_error}"
    );
    let deviation = s_fe / sigma - 1.0;
    eprintln!(
        "section stress: FE {s_fe:e}, beam {sigma:e}, {:+.3} %",
        100.0 * deviation
    );
    assert!(
        deviation.abs() < 0.01,
        "FE {s_fe:e} against beam theory {sigma:e}"
    );
    assert!((v.actuation_force[0] - STROKE * k_fe).abs() <= 1e-12 * v.actuation_force[0]);
}

#[test]
fn outputs_are_their_measures_exactly_and_the_whole_part_agrees_with_the_half() {
    let v = checked();
    for idealization in Idealization::BOTH {
        let pad = values(&v, idealization, "pad");
        let side = values(&v, idealization, "upper_side");
        let stiffness = values(&v, idealization, "stiffness");
        let ratio = values(&v, idealization, "side_per_pad");
        for l in 0..pad.len() {
            assert_eq!(stiffness[l], v.test_force / pad[l]);
            assert_eq!(ratio[l], side[l] / pad[l]);
        }
    }
    // the whole part, its mirror half stated as the part states it, solved by flexopt on
    // the first mesh: the same measures as the half with the symmetry held
    let whole = v.full_model(0).unwrap();
    assert_eq!(whole.cases.len(), 1);
    assert_eq!(whole.sets.len(), 4, "every named face, each once");
    for (k, idealization) in Idealization::BOTH.into_iter().enumerate() {
        let u = whole.solve(&v.material, v.width, idealization).unwrap();
        let m = whole.measures(&u);
        let half = &v.results[k].outputs;
        for (j, name) in ["pad", "upper_side"].iter().enumerate() {
            let h = half.iter().find(|o| o.name == *name).unwrap().values[0];
            assert!(
                (m[j] / h - 1.0).abs() < 1e-7,
                "{name}: whole {} half {h}",
                m[j]
            );
        }
    }
}

#[test]
fn a_load_case_that_is_not_symmetric_is_refused() {
    let mut s = spec();
    let a = s.analysis.as_mut().unwrap();
    a.cases[0].loads = vec![Load {
        face: "upper_left".into(),
        direction: [0.0, -1.0],
        share: 1.0,
    }];
    let err = verify(&s, &STEEL, &VerifySettings::default()).unwrap_err();
    assert!(err.to_string().contains("not symmetric"), "{err}");
}

#[test]
fn a_statement_that_points_nowhere_is_refused() {
    let mut s = spec();
    s.analysis.as_mut().unwrap().measures[1].case = 3;
    let err = verify(&s, &STEEL, &VerifySettings::default()).unwrap_err();
    assert!(err.to_string().contains("load case 3, of 1"), "{err}");
    let mut s = spec();
    s.analysis
        .as_mut()
        .unwrap()
        .actuation
        .as_mut()
        .unwrap()
        .stiffness = FeOutputId(0);
    let err = verify(&s, &STEEL, &VerifySettings::default()).unwrap_err();
    assert!(err.to_string().contains("no stiffness"), "{err}");
}
