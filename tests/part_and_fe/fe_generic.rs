//! A part that is not the bridge, with a finite-element check of its own, stated from
//! outside the library with the part layer's types ([`flexopt::part::analysis`]): the
//! verifier knows no model's faces or outputs, so any part that names its faces can be
//! checked. The same part then comes as a model of its own from a problem file (physics, no
//! pictures, a part that states its check), and `verify` compares its output with the FE.
//!
//! The part: a straight strip clamped at both ends, pushed down at its middle by the test
//! force on a short pad of its upper side. Timoshenko's beam clamped at both ends under a
//! central load `P`, span `S`: `delta = P S^3 / (192 E I) + P S / (4 kappa G A)`; the end
//! moment of the load spread over the pad (`2 c` long), `P (S / 8 - c^2 / (6 S))`, which
//! shear leaves as it is for a symmetric load; the mean deflection along each half of the
//! span half the middle's (the bending shape and the shear's straight line alike).

use std::path::Path;
use std::sync::Arc;

use flexopt::fe::verify::{verify, verify_design, Verification, VerifySettings};
use flexopt::fe::{Elastic, Fidelity, Idealization};
use flexopt::model::entry::{no_sections, ModelEntry};
use flexopt::model::material::Material;
use flexopt::model::{
    Depiction, Dimension, Mechanism, Model, OutputInfo, ParameterInfo, PartMaker,
};
use flexopt::part::analysis::{
    ActuationCase, Analysis, FeCounterpart, FeOutput, FeOutputId, Load, LoadCase, Measure,
    Quantity, Term,
};
use flexopt::part::{Actuation, Face, HingeSite, PartSpec, Solid};
use flexopt::problem::Problem;
use flexopt::report::verify::VerifyReport;

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

pub(crate) fn output(name: &'static str, dimension: Dimension, quantity: Quantity) -> FeOutput {
    FeOutput {
        name,
        dimension,
        meaning: "",
        quantity,
        converges: quantity != Quantity::PeakStress,
        display: None,
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
            output("pad", Dimension::Length, Quantity::Displacement(0)),
            output("upper_side", Dimension::Length, Quantity::Displacement(1)),
            output("stiffness", Dimension::Stiffness, Quantity::Stiffness(0)),
            output(
                "side_per_pad",
                Dimension::Ratio,
                Quantity::Ratio {
                    numerator: 1,
                    denominator: 0,
                },
            ),
            output("stress_section", Dimension::Stress, Quantity::SectionStress),
            output("stress_peak", Dimension::Stress, Quantity::PeakStress),
        ],
        actuation: Some(ActuationCase {
            name: "actuation_force",
            case: 0,
            stiffness: FeOutputId(2),
        }),
        modal: None,
    }
}

/// The actuation of both test parts: [`STROKE`], no preload, a stiff actuator.
fn stroke() -> Actuation {
    Actuation {
        nominal_stroke: STROKE,
        preload: 0.0,
        stiffness: None,
        payload_mass: 0.0,
        stack_mass: 0.0,
    }
}

fn spec() -> PartSpec {
    spec_with(L, T)
}

/// The part with strips `l` long and `t` thick (m).
fn spec_with(l: f64, t: f64) -> PartSpec {
    let strip = |name: &str, sign: f64, solid: usize| HingeSite {
        name: name.into(),
        start: [sign * C, 0.0],
        end: [sign * (C + l), 0.0],
        thickness: t,
        root: t,
        fillet: 0.0,
        kind: "strip",
        profile: vec![[0.0, 0.5 * t, 0.0], [l, 0.5 * t, 0.0]],
        solid,
    };
    let (top, bottom, end) = (0.5 * t, -0.5 * t, C + l);
    PartSpec {
        width: W,
        actuation: Some(stroke()),
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
    // the estimate below reads the last three meshes' values
    assert!(v.levels.len() >= 3, "{} meshes", v.levels.len());
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

/// The strip's check with each upper half pushed down in a load case of its own: neither
/// case is symmetric, so the whole part is solved. Each case deflects the pad as the other
/// does (the part is symmetric, its whole mesh only nearly so), and the two together as the
/// half's symmetric solve of both halves pushed at once (another mesh, the same limit):
/// linear superposition, within the meshes' errors.
#[test]
fn a_load_case_that_is_not_symmetric_is_solved_on_the_whole_part() {
    let down = [0.0, -1.0];
    let push = |face: &str| Load {
        face: face.into(),
        direction: down,
        share: 1.0,
    };
    let pad = |case: usize| Measure {
        case,
        terms: vec![Term {
            weight: 1.0,
            face: "pad".into(),
            direction: down,
        }],
    };
    let case = |name: &str, loads: Vec<Load>| LoadCase {
        name: name.into(),
        loads,
    };
    let settings = VerifySettings {
        tolerance: 0.002,
        max_levels: 4,
        modal: false,
        solid: false,
        ..VerifySettings::default()
    };
    let mut one_sided = spec();
    let a = one_sided.analysis.as_mut().unwrap();
    a.cases = vec![
        case("left", vec![push("upper_left")]),
        case("right", vec![push("upper_right")]),
    ];
    a.measures = vec![pad(0), pad(1)];
    a.outputs = vec![
        output("pad_left", Dimension::Length, Quantity::Displacement(0)),
        output("pad_right", Dimension::Length, Quantity::Displacement(1)),
        output("k_left", Dimension::Stiffness, Quantity::Stiffness(0)),
    ];
    let actuated = |stiffness: usize| {
        Some(ActuationCase {
            name: "actuation_force",
            case: 0,
            stiffness: FeOutputId(stiffness),
        })
    };
    a.actuation = actuated(2);
    let whole = verify(&one_sided, &STEEL, &settings).expect("the whole part verifies");
    assert!(whole.whole_part);
    assert_eq!(whole.half.area, whole.part.area, "the whole part is solved");

    let mut both = one_sided.clone();
    let a = both.analysis.as_mut().unwrap();
    a.cases = vec![case("both", vec![push("upper_left"), push("upper_right")])];
    a.measures = vec![pad(0)];
    a.outputs = vec![
        output("pad_both", Dimension::Length, Quantity::Displacement(0)),
        output("k_both", Dimension::Stiffness, Quantity::Stiffness(0)),
    ];
    a.actuation = actuated(1);
    let half = verify(&both, &STEEL, &settings).expect("the half verifies");
    assert!(!half.whole_part);
    assert!(half.half.area < 0.51 * half.part.area);

    let (left, e_left) = estimate(&whole, "pad_left");
    let (right, e_right) = estimate(&whole, "pad_right");
    let (sum, e_sum) = estimate(&half, "pad_both");
    let error = e_left.max(e_right).max(e_sum);
    eprintln!(
        "whole: {left:e} + {right:e} = {:e}; half, both at once: {sum:e}; mesh errors {error:e}",
        left + right
    );
    assert!(error < 1e-3, "{error}");
    assert!(
        (left / right - 1.0).abs() < 2.0 * error,
        "{left:e} vs {right:e}"
    );
    assert!(
        ((left + right) / sum - 1.0).abs() < 2.0 * error,
        "{left:e} + {right:e} vs {sum:e}"
    );
}

/// A part with no symmetry at all: a strip `l` long and `t` thick clamped at its left end
/// (face `root`), its right end face (`tip`) pushed down by the test force; the outputs its
/// deflection (`tip`), the stiffness and the root's section stress.
pub fn cantilever(l: f64, t: f64) -> PartSpec {
    let down = [0.0, -1.0];
    PartSpec {
        width: W,
        actuation: Some(stroke()),
        analysis: Some(Analysis {
            clamped: vec!["root".into()],
            cases: vec![LoadCase {
                name: "down on the tip".into(),
                loads: vec![Load {
                    face: "tip".into(),
                    direction: down,
                    share: 1.0,
                }],
            }],
            measures: vec![Measure {
                case: 0,
                terms: vec![Term {
                    weight: 1.0,
                    face: "tip".into(),
                    direction: down,
                }],
            }],
            outputs: vec![
                output("tip", Dimension::Length, Quantity::Displacement(0)),
                output("stiffness", Dimension::Stiffness, Quantity::Stiffness(0)),
                output("stress_section", Dimension::Stress, Quantity::SectionStress),
            ],
            actuation: Some(ActuationCase {
                name: "actuation_force",
                case: 0,
                stiffness: FeOutputId(1),
            }),
            modal: None,
        }),
        solids: vec![Solid {
            name: "strip".into(),
            points: rect(0.0, -0.5 * t, l, 0.5 * t),
        }],
        joints: Vec::new(),
        hinges: vec![HingeSite {
            name: "strip".into(),
            start: [0.0, 0.0],
            end: [l, 0.0],
            thickness: t,
            root: t,
            fillet: 0.0,
            kind: "strip",
            profile: vec![[0.0, 0.5 * t, 0.0], [l, 0.5 * t, 0.0]],
            solid: 0,
        }],
        faces: vec![
            face("root", [0.0, 0.5 * t], [0.0, -0.5 * t]),
            face("tip", [l, -0.5 * t], [l, 0.5 * t]),
        ],
        annotations: Vec::new(),
        caption: String::new(),
        min_slot: 0.2e-3,
        actuator: None,
        warnings: Vec::new(),
    }
}

/// [`cantilever`] against Timoshenko's cantilever (Cowper's shear coefficient): `delta = P
/// L^3 / (3 E I) + P L / (kappa G A)`, the root moment `P L`, so the root's beam stress `6 P
/// L / (w t^2)` under the actuation force.
#[test]
fn a_part_without_symmetry_verifies_against_timoshenkos_cantilever() {
    let (l, t) = (20e-3, 1e-3);
    let spec = cantilever(l, t);
    let settings = VerifySettings {
        tolerance: 0.002,
        max_levels: 4,
        modal: false,
        ..VerifySettings::default()
    };
    let v = verify(&spec, &STEEL, &settings).expect("the cantilever verifies");
    assert!(v.whole_part);
    // the whole model for CalculiX is the mesh solved, not mirrored: the same measure
    let full = v.full_model(0).unwrap();
    assert_eq!(full.mesh.nodes.len(), v.meshes[0].nodes.len());
    let u = full
        .solve(&v.material, v.width, Idealization::PlaneStress)
        .unwrap();
    let first = values(&v, Idealization::PlaneStress, "tip")[0];
    assert!((full.measures(&u)[0] / first - 1.0).abs() < 1e-7);
    // the 3D plate, ten times as wide as the strip is thick, lies between the idealizations
    let k = |f: Fidelity| {
        let o = v.outputs(f).expect("the check made it");
        o.iter()
            .find(|o| o.name == "stiffness")
            .unwrap()
            .estimate
            .value
    };
    let (stress, solid, strain) = (
        k(Fidelity::PlaneStress),
        k(Fidelity::Solid),
        k(Fidelity::PlaneStrain),
    );
    eprintln!("cantilever: plane stress {stress:e} <= 3D {solid:e} <= plane strain {strain:e}");
    assert!(stress < solid && solid < strain);
    let (e, nu) = (STEEL.youngs_modulus, STEEL.poisson_ratio);
    let g = e / (2.0 * (1.0 + nu));
    let kappa = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
    let (i, area) = (W * t.powi(3) / 12.0, W * t);
    let k_beam = 1.0 / (l.powi(3) / (3.0 * e * i) + l / (kappa * g * area));
    let (k_fe, k_error) = estimate(&v, "stiffness");
    let deviation = k_fe / k_beam - 1.0;
    eprintln!(
        "cantilever stiffness: FE {k_fe:e} (mesh {k_error:e}), Timoshenko {k_beam:e}, {:+.3} %",
        100.0 * deviation
    );
    assert!(k_error < 0.001, "{k_error}");
    // the clamped face held whole (no warping, no Poisson contraction at the root) stiffens
    // the FE; measured +0.085 %, a small part of the shear term itself, 3 (t/L)^2 E /
    // (kappa G) = 2 % of the bending
    assert!(
        deviation.abs() < 0.005,
        "FE {k_fe:e} against beam theory {k_beam:e}"
    );
    let (s_fe, s_error) = estimate(&v, "stress_section");
    let sigma = 6.0 * (k_fe * STROKE) * l / (W * t * t);
    let deviation = s_fe / sigma - 1.0;
    eprintln!(
        "root stress: FE {s_fe:e} (mesh {s_error:e}), beam {sigma:e}, {:+.3} %",
        100.0 * deviation
    );
    assert!(
        s_error < 0.001 && deviation.abs() < 0.01,
        "{s_fe:e} vs {sigma:e}"
    );
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

/// Timoshenko's stiffness of the strip clamped at both ends under a central load, the
/// span the two strips and the pad (Cowper's shear coefficient of a rectangle).
fn timoshenko(l: f64, t: f64) -> f64 {
    let (e, nu) = (STEEL.youngs_modulus, STEEL.poisson_ratio);
    let g = e / (2.0 * (1.0 + nu));
    let kappa = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
    let (i, area, span) = (W * t.powi(3) / 12.0, W * t, 2.0 * (C + l));
    1.0 / (span.powi(3) / (192.0 * e * i) + span / (4.0 * kappa * g * area))
}

/// The same part as a model from outside the library, the way a mechanism with a part is
/// added inside it: its physics (`k_mid`, the beam theory's stiffness, with its exact
/// gradient), no pictures of its own, and a part that states its check, whose stiffness is
/// `k_mid`'s counterpart.
#[derive(Debug)]
struct ClampedStrip {
    material: Material,
}

static PARAMETERS: [ParameterInfo; 2] = [
    ParameterInfo::new("l", Dimension::Length, "length of each strip"),
    ParameterInfo::new("t", Dimension::Length, "thickness of the strips"),
];

static OUTPUTS: [OutputInfo; 1] = [OutputInfo::new(
    "k_mid",
    Dimension::Stiffness,
    "stiffness at the middle, Timoshenko's beam clamped at both ends",
)];

impl Model for ClampedStrip {
    fn name(&self) -> &'static str {
        "clamped_strip"
    }
    fn parameters(&self) -> &[ParameterInfo] {
        &PARAMETERS
    }
    fn outputs(&self) -> &[OutputInfo] {
        &OUTPUTS
    }
    fn evaluate(&self, x: &[f64], _: &[usize], out: &mut [f64]) {
        out[0] = timoshenko(x[0], x[1]);
    }
    fn evaluate_with_gradient(&self, x: &[f64], w: &[usize], out: &mut [f64], jac: &mut [f64]) {
        // central differences: the test needs values, the trait asks for gradients too
        self.evaluate(x, w, out);
        for j in 0..2 {
            let h = 1e-6 * x[j];
            let (mut a, mut b) = (x.to_vec(), x.to_vec());
            a[j] += h;
            b[j] -= h;
            jac[j] = (timoshenko(a[0], a[1]) - timoshenko(b[0], b[1])) / (2.0 * h);
        }
    }
    fn domain_error(&self, x: &[f64]) -> Option<String> {
        x.iter()
            .any(|&v| v <= 0.0)
            .then(|| "lengths must be positive".into())
    }
    fn box_error(&self, _: &[f64], _: &[f64]) -> Option<(usize, String)> {
        None
    }
    fn max_of(&self, _: usize) -> Option<&[usize]> {
        None
    }
    fn unavailable(&self, _: usize) -> Option<String> {
        None
    }
    fn material(&self) -> Option<&Material> {
        Some(&self.material)
    }
    fn angle_limit(&self) -> Option<f64> {
        None
    }
    fn mirror(&self, _: &mut [f64]) -> bool {
        false
    }

    fn fit_limits(&self) -> &[flexopt::model::fit::FitLimit] {
        &[]
    }
}

impl Depiction for ClampedStrip {}

impl PartMaker for ClampedStrip {
    fn part(&self, x: &[f64]) -> Result<PartSpec, Vec<String>> {
        Ok(spec_with(x[0], x[1]))
    }
    fn fe_counterpart(&self, output: usize) -> Option<FeCounterpart> {
        (output == 0).then_some(FeCounterpart::Output(FeOutputId(2)))
    }
}

const STRIP_ENTRY: ModelEntry = ModelEntry {
    name: "clamped_strip",
    sections: &[],
    hinge_layout: None,
    optional_outputs: None,
    build: |_| {
        Ok(Mechanism::complete(ClampedStrip {
            material: Material {
                name: "steel".into(),
                youngs_modulus: STEEL.youngs_modulus,
                poisson_ratio: STEEL.poisson_ratio,
                yield_strength: None,
                ultimate_strength: None,
                density: STEEL.density,
            },
        }))
    },
    schema: no_sections,
    template: "",
};

const STRIP_FILE: &str = r#"
name = "clamped_strip"
model = "clamped_strip"

[[variables]]
name = "l"
unit = "mm"
lower = 5
upper = 15

[[variables]]
name = "t"
unit = "mm"
lower = 0.3
upper = 0.8

[objective]
maximize = "k_mid"
"#;

#[test]
fn a_model_from_outside_with_a_part_is_checked_from_its_problem_file() {
    let problem = Problem::parse_with(&[STRIP_ENTRY], Path::new("strip.toml"), STRIP_FILE).unwrap();
    let x = [L, T];
    let settings = VerifySettings {
        tolerance: 0.002,
        modal: false,
        ..VerifySettings::default()
    };
    let v = verify_design(problem.mechanism(), &x, &settings).unwrap();
    // the report compares the FE stiffness with the model's own output, named by the part
    let report = VerifyReport::new(&problem, &x, &v);
    assert_eq!(report.design["l"], 10.0);
    let k = &report.outputs["plane_stress"]["stiffness"];
    assert_eq!(k.analytic, Some(timoshenko(L, T)));
    let deviation = k.deviation_percent.unwrap();
    eprintln!("k_mid against the FE stiffness: {deviation:+.3} %");
    // the same comparison as the statement's own test above: within beam theory's 1 %
    assert!(deviation.abs() < 1.0, "{deviation} %");
    assert_eq!(
        k.deviation_percent,
        Some(100.0 * (timoshenko(L, T) - k.estimate.value) / k.estimate.value)
    );
    // a refinement reads the same counterpart, a physics replaced keeps the part
    let corrected = problem.mechanism().with_physics(Arc::new(ClampedStrip {
        material: problem.model().material().unwrap().clone(),
    }));
    assert!(corrected.part_spec(&x).is_some_and(|s| s.is_ok()));
    assert_eq!(
        corrected.fe_counterpart(0),
        Some(FeCounterpart::Output(FeOutputId(2)))
    );
}
