//! The part's statement of its check ([`Analysis`]) turned into what a mesh is loaded and
//! read with: on the whole part as stated, or on its right half, where the symmetry
//! condition on the cut stands for everything at `x < 0`. The half is solved where the part
//! and every load case, measure and actuator of its statement are symmetric about the y
//! axis ([`half`] states them); elsewhere the whole part is.
//!
//! On the half, a face wholly at `x < 0` is its mirror image's business: a measure reads
//! the mirror face with the x components negated (the symmetric field there is the mirror
//! of the field here), a load on it is dropped (the mirror load, which a symmetric case
//! has, makes it), and an actuator between it and its mirror becomes a grounded spring of
//! twice the stiffness on the right face (the gap between them closes twice as fast as the
//! right face moves). A face across the axis keeps half of its load and half of its mass.

use crate::fe::geometry::Domain;
use crate::fe::loads;
use crate::fe::mesh::{EdgeNodes, Mesh};
use crate::fe::FeError;
use crate::part::analysis::{Analysis, Measure, Quantity};
use crate::part::{Actuation, Face};

/// A load as applied: its face, its total force (N).
#[derive(Debug, Clone)]
pub(super) struct Applied {
    pub(super) face: String,
    pub(super) total: [f64; 2],
}

/// A term as read: its face, direction and weight.
#[derive(Debug, Clone)]
pub(super) struct Read {
    pub(super) face: String,
    pub(super) direction: [f64; 2],
    pub(super) weight: f64,
}

/// The actuator on the half: the right face and the direction it acts along, and the
/// multiple of the actuator's stiffness its grounded spring has.
#[derive(Debug, Clone)]
pub(super) struct HalfSpring {
    pub(super) face: String,
    pub(super) direction: [f64; 2],
    pub(super) factor: f64,
}

/// The statement on the mesh it is solved on.
#[derive(Debug, Clone)]
pub(super) struct Stated {
    pub(super) clamped: Vec<String>,
    /// Each case's loads, in the statement's order.
    pub(super) cases: Vec<Vec<Applied>>,
    /// Each measure's case and terms.
    pub(super) measures: Vec<(usize, Vec<Read>)>,
    /// The payload face and the share of the payload it carries.
    pub(super) payload: Option<(String, f64)>,
    pub(super) spring: Option<HalfSpring>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Side {
    Right,
    Left,
    Across,
}

fn segments<'a>(faces: &'a [Face], name: &str) -> Vec<&'a Face> {
    faces.iter().filter(|f| f.name == name).collect()
}

fn side(faces: &[Face], name: &str) -> Result<Side, FeError> {
    let segs = segments(faces, name);
    if segs.is_empty() {
        return Err(FeError::Setup(format!("the part has no face `{name}`")));
    }
    let xs = segs.iter().flat_map(|f| [f.a[0], f.b[0]]);
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
        (l.min(x), h.max(x))
    });
    Ok(if lo >= 0.0 && hi > 0.0 {
        Side::Right
    } else if hi <= 0.0 && lo < 0.0 {
        Side::Left
    } else {
        Side::Across
    })
}

/// The name of the faces that mirror those called `name` about the y axis.
fn mirror<'a>(faces: &'a [Face], name: &str) -> Result<&'a str, FeError> {
    let tol = 1e-12;
    let near = |p: [f64; 2], q: [f64; 2]| (p[0] + q[0]).abs() <= tol && (p[1] - q[1]).abs() <= tol;
    let mirrors = |f: &Face, g: &Face| {
        (near(f.a, g.a) && near(f.b, g.b)) || (near(f.a, g.b) && near(f.b, g.a))
    };
    let segs = segments(faces, name);
    faces
        .iter()
        .map(|g| g.name.as_str())
        .find(|&other| {
            let theirs = segments(faces, other);
            theirs.len() == segs.len() && segs.iter().all(|f| theirs.iter().any(|g| mirrors(f, g)))
        })
        .ok_or_else(|| {
            FeError::Setup(format!(
                "the face `{name}` has no mirror image about the y axis among the part's faces"
            ))
        })
}

/// The statement on the whole part, at the test force `force`.
pub(super) fn whole(analysis: &Analysis, force: f64) -> Stated {
    Stated {
        clamped: analysis.clamped.clone(),
        cases: analysis
            .cases
            .iter()
            .map(|c| {
                c.loads
                    .iter()
                    .map(|l| {
                        let f = force * l.share;
                        Applied {
                            face: l.face.clone(),
                            total: [l.direction[0] * f, l.direction[1] * f],
                        }
                    })
                    .collect()
            })
            .collect(),
        measures: analysis
            .measures
            .iter()
            .map(|m| {
                let terms = m
                    .terms
                    .iter()
                    .map(|t| Read {
                        face: t.face.clone(),
                        direction: t.direction,
                        weight: t.weight,
                    })
                    .collect();
                (m.case, terms)
            })
            .collect(),
        payload: analysis.modal.as_ref().map(|m| (m.payload.clone(), 1.0)),
        // an actuator whose far face is held stands on the ground: a spring on its near face
        spring: analysis
            .modal
            .as_ref()
            .and_then(|m| m.actuator.as_ref())
            .filter(|s| analysis.clamped.contains(&s.faces[1]))
            .map(|s| HalfSpring {
                face: s.faces[0].clone(),
                direction: s.direction,
                factor: 1.0,
            }),
    }
}

fn reads(
    m: &Measure,
    at: impl Fn(&crate::part::analysis::Term) -> Result<(String, [f64; 2]), FeError>,
) -> Result<Vec<Read>, FeError> {
    m.terms
        .iter()
        .map(|t| {
            let (face, direction) = at(t)?;
            Ok(Read {
                face,
                direction,
                weight: t.weight,
            })
        })
        .collect()
}

/// That every face the statement names is a face of the part.
pub(super) fn faces_exist(analysis: &Analysis, faces: &[Face]) -> Result<(), FeError> {
    for name in analysis.faces() {
        side(faces, name)?;
    }
    Ok(())
}

/// The statement on the right half of the part whose faces are `faces` (metres), at the
/// test force `force`: for the symmetric response, which every load case must be (an error
/// says which is not).
pub(super) fn half(analysis: &Analysis, faces: &[Face], force: f64) -> Result<Stated, FeError> {
    let right = |name: &str| -> Result<String, FeError> {
        Ok(match side(faces, name)? {
            Side::Left => mirror(faces, name)?.to_string(),
            _ => name.to_string(),
        })
    };
    let mut clamped = Vec::new();
    for name in &analysis.clamped {
        let r = right(name)?;
        if !clamped.contains(&r) {
            clamped.push(r);
        }
    }
    let mut cases = Vec::new();
    for c in &analysis.cases {
        let mut applied = Vec::new();
        for l in &c.loads {
            let k = match side(faces, &l.face)? {
                Side::Right => 1.0,
                Side::Across => 0.5,
                Side::Left => {
                    // a symmetric case has the mirror load, which the symmetry makes
                    let image = mirror(faces, &l.face)?;
                    let mirrored = c.loads.iter().any(|o| {
                        o.face == image
                            && o.share == l.share
                            && o.direction == [-l.direction[0], l.direction[1]]
                    });
                    if !mirrored {
                        return Err(FeError::Setup(format!(
                            "the load case `{}` is not symmetric about the y axis: the load on \
                             `{}` has no mirror image",
                            c.name, l.face
                        )));
                    }
                    continue;
                }
            };
            let f = force * l.share * k;
            applied.push(Applied {
                face: l.face.clone(),
                total: [l.direction[0] * f, l.direction[1] * f],
            });
        }
        cases.push(applied);
    }
    let mut measures = Vec::new();
    for m in &analysis.measures {
        let terms = reads(m, |t| {
            Ok(match side(faces, &t.face)? {
                Side::Left => (
                    mirror(faces, &t.face)?.to_string(),
                    [-t.direction[0], t.direction[1]],
                ),
                _ => (t.face.clone(), t.direction),
            })
        })?;
        measures.push((m.case, terms));
    }
    let (mut payload, mut spring) = (None, None);
    if let Some(modal) = &analysis.modal {
        let share = match side(faces, &modal.payload)? {
            Side::Across => 0.5,
            _ => 1.0,
        };
        payload = Some((right(&modal.payload)?, share));
        if let Some(s) = &modal.actuator {
            let [a, b] = &s.faces;
            let (sa, sb) = (side(faces, a)?, side(faces, b)?);
            let face = match (sa, sb) {
                (Side::Right, Side::Left) if mirror(faces, b)? == a => a,
                (Side::Left, Side::Right) if mirror(faces, a)? == b => b,
                _ => {
                    return Err(FeError::Setup(format!(
                        "the actuator between `{a}` and `{b}` is not between a face and its \
                         mirror image"
                    )))
                }
            };
            let d = s.direction;
            spring = Some(HalfSpring {
                face: face.clone(),
                direction: if d[0] < 0.0 { [-d[0], -d[1]] } else { d },
                factor: 2.0,
            });
        }
    }
    Ok(Stated {
        clamped,
        cases,
        measures,
        payload,
        spring,
    })
}

/// The edges of every face a statement names, found once a mesh.
pub(super) struct Edges(Vec<(String, Vec<EdgeNodes>)>);

impl Edges {
    pub(super) fn of(m: &Mesh, domain: &Domain, names: &[&str]) -> Result<Self, FeError> {
        names
            .iter()
            .map(|&name| Ok((name.to_string(), super::level::face_edges(m, domain, name)?)))
            .collect::<Result<_, FeError>>()
            .map(Edges)
    }

    pub(super) fn get(&self, name: &str) -> &[EdgeNodes] {
        self.0
            .iter()
            .find(|(n, _)| n == name)
            .map_or(&[], |(_, e)| e.as_slice())
    }
}

impl Stated {
    /// Every face it names, each once.
    pub(super) fn faces(&self) -> Vec<&str> {
        let mut names: Vec<&str> = Vec::new();
        let all = self
            .clamped
            .iter()
            .chain(self.cases.iter().flatten().map(|a| &a.face))
            .chain(
                self.measures
                    .iter()
                    .flat_map(|(_, t)| t.iter().map(|r| &r.face)),
            )
            .chain(self.payload.iter().map(|p| &p.0))
            .chain(self.spring.iter().map(|s| &s.face));
        for name in all {
            if !names.contains(&name.as_str()) {
                names.push(name);
            }
        }
        names
    }
}

/// A measure's value: its terms summed in their order, the first one as it is.
pub(super) fn measure(m: &Mesh, edges: &Edges, terms: &[Read], u: &[f64]) -> f64 {
    terms
        .iter()
        .map(|t| {
            let d = loads::mean_displacement(m, edges.get(&t.face), u);
            t.weight * (d[0] * t.direction[0] + d[1] * t.direction[1])
        })
        .reduce(|a, b| a + b)
        .unwrap_or(0.0)
}

/// A measure's value from a 3D field on `ext` (three a node): the faces' mean
/// displacements over their area through the half-width.
pub(super) fn measure_solid(
    ext: &crate::fe::solid::Extruded,
    edges: &Edges,
    terms: &[Read],
    u: &[f64],
) -> f64 {
    terms
        .iter()
        .map(|t| {
            let faces = ext.side_faces(edges.get(&t.face));
            let d = crate::fe::solid::mean_displacement(ext, &faces, u);
            t.weight * (d[0] * t.direction[0] + d[1] * t.direction[1])
        })
        .reduce(|a, b| a + b)
        .unwrap_or(0.0)
}

/// Every output's value (in the analysis's order): the static ones from the measures at the
/// test force `force` (and the actuator `a`), the others as `other` gives them.
pub(super) fn output_values(
    analysis: &Analysis,
    measured: &[f64],
    force: f64,
    a: &Actuation,
    other: impl Fn(Quantity) -> f64,
) -> Vec<f64> {
    analysis
        .outputs
        .iter()
        .map(|o| static_value(o.quantity, measured, force, a).unwrap_or_else(|| other(o.quantity)))
        .collect()
}

/// The static outputs (those read from the measures alone, with the actuator `a`) at the
/// test force `force`; `None` for the others.
pub(super) fn static_value(q: Quantity, values: &[f64], force: f64, a: &Actuation) -> Option<f64> {
    match q {
        Quantity::Actuated { ports, what } => {
            Some(ports.value(what, values, force, a.nominal_stroke, a.stiffness))
        }
        Quantity::Displacement(i) => Some(values[i]),
        Quantity::Stiffness(i) => Some(force / values[i]),
        Quantity::Ratio {
            numerator,
            denominator,
        } => Some(values[numerator] / values[denominator]),
        _ => None,
    }
}

/// The nodal forces of a case's loads (full vector): the first load's as they are, the
/// others added in order.
pub(super) fn case_forces(m: &Mesh, edges: &Edges, width: f64, applied: &[Applied]) -> Vec<f64> {
    applied
        .iter()
        .map(|a| loads::uniform_force(m, edges.get(&a.face), width, a.total))
        .reduce(|mut sum, f| {
            for (s, v) in sum.iter_mut().zip(f) {
                *s += v;
            }
            sum
        })
        .unwrap_or_else(|| vec![0.0; 2 * m.nodes.len()])
}

/// That every index of the statement points into its lists: a statement that points
/// nowhere is the model's mistake, and is said as such rather than found by a solve.
pub(super) fn check(a: &Analysis) -> Result<(), FeError> {
    let fail = |what: String| Err(FeError::Setup(format!("the part's check is wrong: {what}")));
    let (cases, measures) = (a.cases.len(), a.measures.len());
    for (k, m) in a.measures.iter().enumerate() {
        if m.case >= cases {
            return fail(format!(
                "measure {k} is read under load case {}, of {cases}",
                m.case
            ));
        }
    }
    for o in &a.outputs {
        let read = match o.quantity {
            Quantity::Displacement(i) | Quantity::Stiffness(i) => vec![i],
            Quantity::Ratio {
                numerator,
                denominator,
            } => vec![numerator, denominator],
            Quantity::Actuated { ports, .. } => ports.measures().to_vec(),
            _ => Vec::new(),
        };
        if let Some(i) = read.into_iter().find(|&i| i >= measures) {
            return fail(format!("{} reads measure {i}, of {measures}", o.name));
        }
    }
    if let Some(act) = &a.actuation {
        if act.case >= cases {
            return fail(format!(
                "the actuation is load case {}, of {cases}",
                act.case
            ));
        }
        let stiffness = a.outputs.get(act.stiffness.0).map(|o| o.quantity);
        if !matches!(stiffness, Some(Quantity::Stiffness(_))) {
            return fail(format!(
                "the actuation is scaled by output {}, which is no stiffness",
                act.stiffness.0
            ));
        }
    }
    if let Some(m) = &a.modal {
        if m.start >= cases {
            return fail(format!(
                "the modes start from load case {}, of {cases}",
                m.start
            ));
        }
    }
    Ok(())
}
