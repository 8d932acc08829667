//! The ports' faces on a network's part and the finite-element check stated through them.

use super::super::description::Axis;
use super::images::Image;
use super::plane::{add, covered, exit, same_face, scale, P};
use crate::model::Dimension;
use crate::part::analysis::{
    actuated_outputs, ActuationCase, Analysis, FeOutput, Load, LoadCase, Measure, Ports, Quantity,
    Term,
};
use crate::part::{Face, Solid};

use crate::part::analysis::FeOutputId;

pub(super) const FE_K_IN: FeOutputId = FeOutputId(0);
pub(super) const FE_AMPLIFICATION: FeOutputId = FeOutputId(1);
pub(super) const FE_K_OUT: FeOutputId = FeOutputId(2);
pub(super) const FE_STRESS_SECTION: FeOutputId = FeOutputId(3);
/// After `fe_stress_max` ([`analysis`]): the outputs under the stack.
pub(super) const FE_ACTUATED: FeOutputId = FeOutputId(5);
/// After those under the stack, where the part has its modes checked.
pub(super) const FE_F1: FeOutputId = FeOutputId(10);

/// A port's face on the described part: its name, ends, the port's direction and axis.
pub(super) struct PlacedPort<'a> {
    pub(super) name: String,
    pub(super) face: (P, P),
    pub(super) direction: P,
    pub(super) across: Option<Axis>,
    /// The axes its body lies across.
    pub(super) own: &'a [Axis],
}

pub(super) enum FaceProblem {
    Outside,
    Corner,
    /// Where the face would be, and the solid it lies on.
    Covered(P, usize),
}

/// The face of the port at `at` along `dir` on the body whose solids are `mine`: where the
/// line leaves the body on the side the force comes from, `length` long or shorter where the
/// edge is, and off every other solid.
pub(super) fn port_face(
    solids: &[Solid],
    mine: &[usize],
    at: P,
    dir: P,
    length: f64,
) -> Result<(P, P), FaceProblem> {
    let back = [-dir[0], -dir[1]];
    // through the body's convex pieces (its triangles, its pads) until the line leaves them
    // all: a piece's exit inside another piece goes on through that one
    let leave = |p: P| {
        mine.iter()
            .filter_map(|&k| exit(&solids[k].points, p, back).map(|(t, e)| (t, k, e)))
            .max_by(|x, y| x.0.total_cmp(&y.0))
    };
    let (t, mut k, mut e) = leave(at).ok_or(FaceProblem::Outside)?;
    let mut q = add(at, scale(back, t));
    let mut stepped = false;
    for _ in 0..mine.len() {
        match leave(q) {
            Some((t, k2, e2)) if t > 1e-12 => {
                (k, e, stepped) = (k2, e2, true);
                q = add(q, scale(back, t));
            }
            _ => break,
        }
    }
    let poly = &solids[k].points;
    let (a, b) = (poly[e], poly[(e + 1) % poly.len()]);
    let len = (b[0] - a[0]).hypot(b[1] - a[1]);
    let along = ((q[0] - a[0]) * (b[0] - a[0]) + (q[1] - a[1]) * (b[1] - a[1])) / len;
    let half = (0.5 * length).min(along).min(len - along);
    if half < 1e-6 {
        return Err(FaceProblem::Corner);
    }
    let e_u = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
    // on the side itself, whatever the steps through the pieces rounded
    let q = if stepped {
        add(a, scale(e_u, along))
    } else {
        q
    };
    // the face keeps off every solid of another body or hinge, whose material stands on
    // that edge there and leaves it no outline
    let (mut lo, mut hi) = (-half, half);
    for (j, other) in solids.iter().enumerate() {
        if mine.contains(&j) {
            continue;
        }
        if let Some((c0, c1)) = covered(&other.points, q, e_u, -half, half) {
            if c0 <= 0.0 && c1 >= 0.0 {
                return Err(FaceProblem::Covered(q, j));
            } else if c1 < 0.0 {
                lo = lo.max(c1);
            } else {
                hi = hi.min(c0);
            }
        }
    }
    if hi <= lo {
        return Err(FaceProblem::Covered(q, k));
    }
    Ok((add(q, scale(e_u, lo)), add(q, scale(e_u, hi))))
}

/// A port's faces on the whole part: the described one and its distinct images, each with
/// its direction, and the share of the port's force each carries (the images on one body
/// share it, as the model's port on a body across an axis does).
pub(super) struct PortFaces {
    faces: Vec<(String, P, Image)>,
    share: f64,
}

/// The check through the ports on the whole part, its faces added to `faces`. A part
/// without ground is held on the first output's image across its axis (the input's where the
/// output is across none), as the bridge's lower output block is.
pub(super) fn ports_check(
    placed: &[PlacedPort<'_>],
    images: &[Image],
    grounded: bool,
    faces: &mut Vec<Face>,
) -> Result<Analysis, String> {
    let held = match (grounded, placed[1].across, placed[0].across) {
        (true, _, _) => None,
        (false, Some(_), _) => Some(1),
        (false, None, Some(_)) => Some(0),
        (false, None, None) => {
            return Err(
                "the network has no ground, and neither its input nor its first output \
                        is across a mirror axis: nothing holds its part for the check; join a \
                        hinge to the ground"
                    .into(),
            )
        }
    };
    let mut all = Vec::new();
    for (i, p) in placed.iter().take(2).enumerate() {
        let mut mine: Vec<(String, P, Image, (P, P))> = Vec::new();
        for &t in images {
            let f = (t.point(p.face.0), t.point(p.face.1));
            if mine.iter().any(|m| same_face(m.3, f)) {
                continue;
            }
            let d = t.point(p.direction);
            let name = format!("{}{}", p.name, t.suffix());
            mine.push((name, d, t, f));
        }
        // the images of the port on its own body (about the axes the body lies across)
        // share the port's force, as the model's described half of such a body carries its
        // share of it
        let on_body = mine
            .iter()
            .filter(|m| m.2.of_body(p.own) == Image::IDENTITY)
            .count();
        let held_image = held.filter(|&h| h == i).and(p.across).map(Image::across);
        let mut kept = Vec::new();
        for (name, d, t, f) in mine {
            if Some(t) == held_image {
                faces.push(Face {
                    name: "clamp".into(),
                    a: f.0,
                    b: f.1,
                });
                continue;
            }
            faces.push(Face {
                name: name.clone(),
                a: f.0,
                b: f.1,
            });
            kept.push((name, d, t));
        }
        all.push(PortFaces {
            faces: kept,
            share: 1.0 / on_body as f64,
        });
    }
    let (input, output) = (&all[0], &all[1]);
    let term = |face: &str, direction: P| Term {
        weight: 1.0,
        face: face.into(),
        direction,
    };
    let loads = |p: &PortFaces| -> Vec<Load> {
        p.faces
            .iter()
            .map(|(face, direction, _)| Load {
                face: face.clone(),
                direction: *direction,
                share: p.share,
            })
            .collect()
    };
    // what the model reads: the port's motion, or across an axis the change of its
    // distance from its image (the image's term where the image is not held)
    let reads = |p: &PortFaces, across: Option<Axis>| -> Vec<Term> {
        p.faces
            .iter()
            .filter(|(_, _, t)| {
                *t == Image::IDENTITY || across.is_some_and(|a| *t == Image::across(a))
            })
            .map(|(face, direction, _)| term(face, *direction))
            .collect()
    };
    Ok(analysis(
        loads(input),
        reads(input, placed[0].across),
        loads(output),
        reads(output, placed[1].across),
    ))
}

/// The check through the ports: the test force on the input's faces (the actuation case),
/// the input's and the first output's motions under it; then on the first output's faces,
/// the input free, the output's and the input's motions under it; and the outputs under the
/// stack from those four.
pub(super) fn analysis(
    input_loads: Vec<Load>,
    input_reads: Vec<Term>,
    output_loads: Vec<Load>,
    output_reads: Vec<Term>,
) -> Analysis {
    let out = |name: &'static str, dimension, meaning: &'static str, quantity| FeOutput {
        name,
        dimension,
        meaning,
        quantity,
        converges: quantity != Quantity::PeakStress,
        display: None,
        analytic: None,
    };
    let ports = Ports {
        input: 0,
        output: 1,
        output_loaded: 2,
        input_by_output: 3,
    };
    Analysis {
        clamped: vec!["clamp".into()],
        cases: vec![
            LoadCase {
                name: "on the input face".into(),
                loads: input_loads,
            },
            LoadCase {
                name: "on the first output's face".into(),
                loads: output_loads,
            },
        ],
        measures: vec![
            Measure {
                case: 0,
                terms: input_reads.clone(),
            },
            Measure {
                case: 0,
                terms: output_reads.clone(),
            },
            Measure {
                case: 1,
                terms: output_reads,
            },
            // the input under the output's load: the stack and the output as two ports
            Measure {
                case: 1,
                terms: input_reads,
            },
        ],
        outputs: vec![
            out(
                "fe_k_in",
                Dimension::Stiffness,
                "the test force over the input face's motion along the input",
                Quantity::Stiffness(0),
            ),
            out(
                "fe_amplification",
                Dimension::Ratio,
                "the first output face's motion over the input face's, the force on the input",
                Quantity::Ratio {
                    numerator: 1,
                    denominator: 0,
                },
            ),
            out(
                "fe_k_out",
                Dimension::Stiffness,
                "the test force on the first output over its face's motion, the input free",
                Quantity::Stiffness(2),
            ),
            out(
                "fe_stress_section",
                Dimension::Stress,
                "the largest beam stress at the hinges' sections under the actuation",
                Quantity::SectionStress,
            ),
            out(
                "fe_stress_max",
                Dimension::Stress,
                "the largest von Mises stress under the actuation",
                Quantity::PeakStress,
            ),
        ]
        .into_iter()
        .chain(actuated_outputs(ports, None))
        .collect(),
        actuation: Some(ActuationCase {
            name: "actuation_force",
            case: 0,
            stiffness: FE_K_IN,
        }),
        modal: None,
    }
}
