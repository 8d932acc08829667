//! The part of a flexure network, drawn from the same description as its model, and the
//! finite-element check it states through the ports (issue 25).
//!
//! What is cut (metres, the description's points evaluated at the design):
//!
//! - each body as the file draws it: its outline (split into triangles where it is not
//!   convex, as the part's solids are convex), or its link, a band of its width around the
//!   segment; a body drawn by neither is the convex hull of its hinges' and beams' pads;
//! - each hinge's thin section from `start` along `angle` for the kind's length, the model's
//!   hinge, with the true profile of its kind ([`crate::model::hinge::HingeKind::outline`]);
//!   its solid runs the fillet radius beyond both ends (a strip's; a notch meets its bodies
//!   smoothly and has none) to a face across it, and behind each face a pad `pad` deep and
//!   `root/2 + fillet + pad_margin` to each side: the pad is joined to the hinge and to the
//!   body, so that a body drawn up to the hinge's end meets it through a face the fillets
//!   land on;
//! - each flexible beam from `start` to `end`, cut as the strip hinge of its length and
//!   thickness is: a flexure to the checks and the finite elements as a hinge is
//!   ([`flexures`] says why);
//! - the ground is its hinges' and beams' pads, each held on its far side (the faces
//!   `clamp`), and its outline where the file draws one.
//!
//! A port's face lies where the line through the port along its direction leaves the body
//! on the side the port's force comes from (the actuator's side): every point of that line
//! moves alike along the direction under a rigid motion of the body, so the face's mean
//! displacement along it reads the port's. The face is `face` long, shorter where the edge
//! it lies on is.
//!
//! The check ([`crate::part::analysis`]): the clamped faces held; the test force on the input
//! face along the input's direction (the actuation case), the input's and the first output's
//! motions read under it; then on the first output's face, the input free. So `fe_k_in`,
//! `fe_amplification`, `fe_k_out` and the hinges' and beams' section and peak stresses
//! under the actuation, each beside the model's output of the same meaning.
//!
//! Mirror axes: the whole part is the described one and its images about each axis (and
//! both). A body across an axis is drawn with its image about it as one solid (the convex
//! hull of the two), so its halves join; each port's face has its images, which share the
//! port's force where they lie on the port's own body (as the model's described half of such
//! a body carries its share). A port across an axis reads its face and its image's face
//! across it: the change of their distance. A part with no ground is held on the first
//! output's image across its axis, as the bridge's lower output block is. The part is
//! symmetric about the y axis where the description is, so the check solves its right half.
//!
//! Under the stack (a spring of its stiffness on the input's face, driven by its free stroke,
//! [`crate::part::analysis::Ports`]): `stroke_in`, `stroke_out`, `k_out_actuated`,
//! `k_out_blocked` and `blocked_force`, the first output's.
//!
//! The natural modes, where the model has them (the actuator's stiffness given): `fe_f1`,
//! the part's lowest mode, the payload on the first output's face ([`modes_check`]). Without
//! mirror axes it is solved whole, the stack a spring from the input's face to the clamped
//! faces; with them on the right half, the lowest of the modes symmetric about the y axis
//! (the stack a spring between the input faces) and antisymmetric about it.

use super::description::{Axis, Description};
use crate::model::hinge::HingeKind;
use crate::model::part_rules::{PartRule, Witness};
use crate::model::{Dimension, PartMaker};
use crate::part::analysis::{
    Actuated, Analysis, FeCounterpart, FeOutput, Modal, Quantity, Spring as FeSpring,
};
use crate::part::mm::length as mm;
use crate::part::{convex_hull, Actuation, Annotation, Face, HingeSite, PartSpec, Solid};

mod drawing;
mod faces;
mod flexures;
mod images;
mod plane;
mod rules;
mod settings;
mod values;

pub use drawing::Drawing;
use faces::{port_face, ports_check, FaceProblem, PlacedPort};
use faces::{FE_ACTUATED, FE_AMPLIFICATION, FE_F1, FE_K_IN, FE_K_OUT, FE_STRESS_SECTION};
use flexures::{CutHinge, Named};
use images::Image;
use plane::{band, convex_pieces, exposed, scale, sub, P};
pub use settings::{PartSettings, RawNetworkPart};
use std::sync::Arc;
use values::Values;

/// The model's outputs the check measures, by their indices among the model's outputs.
#[derive(Debug, Clone, PartialEq)]
pub struct Counterparts {
    pub amplification: Option<usize>,
    pub k_in: Option<usize>,
    pub k_out: Option<usize>,
    pub stress_max: Option<usize>,
    /// The lowest natural frequency, `f1`.
    pub f1: Option<usize>,
    /// Those under the stack, named as [`ACTUATED_OUTPUTS`].
    pub actuated: [Option<usize>; 5],
    /// The sizes of the part as drawn ([`PartMaker::drawn`]).
    pub drawn: Vec<usize>,
}

/// The model's outputs the check measures under the stack, in the order of
/// [`crate::part::analysis::Actuated::ALL`].
pub const ACTUATED_OUTPUTS: [&str; 5] = [
    "stroke_in",
    "stroke_out",
    "k_out_actuated",
    "k_out_blocked",
    "blocked_force",
];

/// A network's part: its drawing (shared with the model, whose footprint outputs read it),
/// the actuator, and the model's outputs its check measures.
#[derive(Debug, Clone)]
pub struct NetworkPart {
    pub drawing: Arc<Drawing>,
    pub actuation: Actuation,
    pub counterparts: Counterparts,
}

impl PartMaker for NetworkPart {
    fn part(&self, x: &[f64]) -> Result<PartSpec, Vec<String>> {
        spec(self, x)
    }

    fn fe_counterpart(&self, output: usize) -> Option<FeCounterpart> {
        let c = &self.counterparts;
        let is = |o: Option<usize>| o == Some(output);
        if is(c.k_in) {
            Some(FeCounterpart::Output(FE_K_IN))
        } else if is(c.amplification) {
            Some(FeCounterpart::Output(FE_AMPLIFICATION))
        } else if is(c.k_out) {
            Some(FeCounterpart::Output(FE_K_OUT))
        } else if is(c.stress_max) {
            // the hinges' beam stress with each notch's concentration, and the beams' with
            // none: the section stress is its FE counterpart for strips and beams, whose
            // concentration is 1
            Some(FeCounterpart::Output(FE_STRESS_SECTION))
        } else if is(c.f1) {
            Some(FeCounterpart::Output(FE_F1))
        } else {
            let k = c.actuated.iter().position(|&a| is(a))?;
            Some(FeCounterpart::Output(Actuated::ALL[k].id(FE_ACTUATED.0)))
        }
    }

    fn drawn(&self, output: usize) -> bool {
        self.counterparts.drawn.contains(&output)
    }

    fn rules(&self) -> &[PartRule] {
        self.drawing.layout.rules()
    }

    fn first_rules(&self) -> usize {
        self.drawing.layout.first_rules()
    }

    fn enforces_rules(&self) -> bool {
        self.drawing.settings.enforce
    }

    fn rule_margins(&self, x: &[f64], out: &mut [f64]) {
        self.drawing.rules().margins(x, out);
    }

    fn rule_margins_with_gradient(&self, x: &[f64], out: &mut [f64], jacobian: &mut [f64]) {
        self.drawing.rules().margins_with_gradient(x, out, jacobian);
    }

    fn rule_hessians(&self) -> bool {
        true
    }

    fn rule_margins_with_hessian(
        &self,
        x: &[f64],
        out: &mut [f64],
        jacobian: &mut [f64],
        hessian: &mut [f64],
    ) {
        self.drawing
            .rules()
            .margins_with_hessian(x, out, jacobian, hessian);
    }

    fn rule_witnesses(&self, x: &[f64], out: &mut [Option<Witness>]) {
        self.drawing.rules().witnesses(x, out);
    }
}

/// The natural modes beside the static check, as the model's `f1` has them
/// ([`super::model`]): the first output's face carries the payload. Without mirror axes the
/// actuator is a spring from the input's face to the ground (the part's clamped faces,
/// where the stack's far end sits on the base), and the modes are the whole part's. With
/// them the check solves the right half, the modes symmetric about the y axis with the
/// actuator a spring between the input's face and its image, and those antisymmetric about
/// it without (the two faces move alike): the lowest of both is the whole part's, as the
/// model's families give it. Stated for a grounded part and for a part standing on its
/// first output's image across the x axis, the input across the y axis; only with the
/// actuator's stiffness; `None` where the check cannot hold the model's modes, which are
/// then left without an FE counterpart.
fn modes_check(check: &mut Analysis, d: &Description, grounded: bool) -> Option<()> {
    let input = &check.cases[0].loads[0];
    let (face, direction) = (input.face.clone(), input.direction);
    let payload = check.cases[1].loads[0].face.clone();
    let (far, start) = if d.mirror.is_empty() {
        ("clamp".to_string(), 0)
    } else {
        let holds = grounded || d.outputs[0].across == Some(Axis::X);
        if d.input.across != Some(Axis::Y) || !holds {
            return None;
        }
        let image = format!("{face}{}", Image::across(Axis::Y).suffix());
        check.cases[0].loads.iter().find(|l| l.face == image)?;
        // the output's load bends the part much as its symmetric mode does
        (image, 1)
    };
    check.modal = Some(Modal {
        payload,
        actuator: Some(FeSpring {
            faces: [face, far],
            direction,
        }),
        start,
    });
    debug_assert_eq!(check.outputs.len(), FE_F1.0);
    check.outputs.push(FeOutput {
        name: "fe_f1",
        dimension: Dimension::Frequency,
        meaning: if d.mirror.is_empty() {
            "the part's lowest natural frequency, the actuator a spring from the input face to \
             the ground, the payload on the first output's face"
        } else {
            "the part's lowest natural frequency, of its modes symmetric about the y axis (the \
             actuator a spring between the input faces) and antisymmetric (the actuator not \
             stretched), the payload on the first output's face"
        },
        quantity: Quantity::LowestFrequency,
        converges: true,
        display: None,
        analytic: None,
    });
    Some(())
}

/// A physical body of the whole part: its slot (0 the ground) and which of its images.
type BodyKey = (usize, Image);

/// The part of design `x`: the described part, then its images about the mirror axes.
fn spec(part: &NetworkPart, x: &[f64]) -> Result<PartSpec, Vec<String>> {
    let d = &part.drawing.description;
    let s = &part.drawing.settings;
    let v = Values::new(d, x);
    let one = |r: Result<P, String>| r.map_err(|e| vec![e]);
    let slot = |b: Option<usize>| b.map_or(0, |b| b + 1);
    // the axes each body (by slot) lies across: a body's images about them are itself
    let own: Vec<&[Axis]> = std::iter::once(&[][..])
        .chain(d.bodies.iter().map(|b| b.on_axis.as_slice()))
        .collect();

    // each hinge and each beam: its solid and its two pads
    let mut cut: Vec<CutHinge> = Vec::new();
    for h in &d.hinges {
        let mut dims = Vec::with_capacity(h.dimensions.len());
        for (e, info) in h.dimensions.iter().zip(h.kind.dimensions()) {
            let value = if info.dimension == Dimension::Length {
                v.length(e)
            } else {
                v.eval(e)
            };
            dims.push(value.map_err(|e| vec![e])?);
        }
        let start = one(v.point(&h.start))?;
        let angle = v.eval(&h.angle).map_err(|e| vec![e])?;
        let named = Named {
            what: "hinge",
            name: &h.name,
        };
        let u = [angle.cos(), angle.sin()];
        let bodies = (slot(h.from), slot(h.to));
        cut.push(flexures::cut(named, h.kind, &dims, start, u, bodies, s));
    }
    for b in &d.beams {
        let (start, end) = (one(v.point(&b.start))?, one(v.point(&b.end))?);
        let thickness = v.length(&b.thickness).map_err(|e| vec![e])?;
        let along = sub(end, start);
        let length = along[0].hypot(along[1]);
        // the model refuses these at the design's middle; elsewhere they leave its domain
        if !(length > 0.0 && thickness > 0.0) {
            return Err(vec![format!(
                "beam \"{}\" ({}): its length {length:e} m and thickness {thickness:e} m \
                 must be positive",
                b.name, b.key
            )]);
        }
        let named = Named {
            what: "beam",
            name: &b.name,
        };
        let u = scale(along, 1.0 / length);
        let bodies = (slot(b.from), slot(b.to));
        // the model's beam is the strip of its length and thickness with Cowper's shear
        // coefficient: the part cuts the strip
        let dims = [length, thickness];
        cut.push(flexures::cut(
            named,
            HingeKind::Strip,
            &dims,
            start,
            u,
            bodies,
            s,
        ));
    }

    // the bodies as drawn, or the hull of their pads; a body across an axis with its image
    // about it, so that its two halves are one solid
    let mut shapes: Vec<(usize, Solid)> = Vec::new();
    let mut named = |slot: usize, name: String, drawn: Vec<Vec<P>>| {
        for (i, points) in drawn.into_iter().enumerate() {
            let name = if i == 0 {
                name.clone()
            } else {
                format!("{name} ({})", i + 1)
            };
            shapes.push((slot, Solid { name, points }));
        }
    };
    if d.ground.len() >= 3 {
        let points = v.points(&d.ground).map_err(|e| vec![e])?;
        named(0, "the ground".into(), convex_pieces(points));
    }
    for (b, body) in d.bodies.iter().enumerate() {
        let points = v.points(&body.points).map_err(|e| vec![e])?;
        let mut drawn: Vec<Vec<P>> = match (&body.link_width, points.len()) {
            (Some(w), 2) => {
                let width = v.length(w).map_err(|e| vec![e])?;
                vec![band(points[0], points[1], 0.5 * width)]
            }
            (_, 0) => {
                let all: Vec<P> = cut
                    .iter()
                    .flat_map(|c| {
                        [(c.from, &c.pads[0].0), (c.to, &c.pads[1].0)]
                            .into_iter()
                            .filter(|(o, _)| *o == b + 1)
                            .flat_map(|(_, p)| p.points.iter().copied())
                    })
                    .collect();
                vec![convex_hull(&all)]
            }
            _ => convex_pieces(points),
        };
        if !body.on_axis.is_empty() {
            let selves: Vec<Image> = Image::all(&body.on_axis);
            for shape in &mut drawn {
                let all: Vec<P> = selves
                    .iter()
                    .flat_map(|t| shape.iter().map(|&p| t.point(p)))
                    .collect();
                *shape = convex_hull(&all);
            }
        }
        named(b + 1, format!("body {}", body.name), drawn);
    }

    // the whole: each image of the described part
    let images = Image::all(&d.mirror);
    let mut solids: Vec<Solid> = Vec::new();
    let mut hinges: Vec<HingeSite> = Vec::new();
    let mut joints: Vec<(usize, usize)> = Vec::new();
    let mut faces: Vec<Face> = Vec::new();
    let mut owners: Vec<(BodyKey, usize)> = Vec::new();
    let key = |b: usize, t: Image| -> BodyKey {
        if b == 0 {
            (0, Image::IDENTITY)
        } else {
            (b, t.of_body(own[b]))
        }
    };
    // the sides the ground may be held on: (its solid, its ends)
    let mut held: Vec<(usize, P, P)> = Vec::new();
    // each hinge image's solid and the bodies it meets
    let mut meets: Vec<(usize, BodyKey, BodyKey)> = Vec::new();
    for &t in &images {
        for c in &cut {
            let k = solids.len();
            solids.push(Solid {
                name: format!("{}{}", c.solid.name, t.suffix()),
                points: t.polygon(&c.solid.points),
            });
            hinges.push(HingeSite {
                name: format!("{}{}", c.site.name, t.suffix()),
                start: t.point(c.site.start),
                end: t.point(c.site.end),
                solid: k,
                ..c.site.clone()
            });
            let (from, to) = (key(c.from, t), key(c.to, t));
            meets.push((k, from, to));
            for ((pad, clamp), body) in c.pads.iter().zip([from, to]) {
                let p = solids.len();
                solids.push(Solid {
                    name: format!("{}{}", pad.name, t.suffix()),
                    points: t.polygon(&pad.points),
                });
                joints.push((k, p));
                owners.push((body, p));
                if let Some((a, b)) = clamp {
                    held.push((p, t.point(*a), t.point(*b)));
                }
            }
        }
        for (b, shape) in &shapes {
            let body = key(*b, t);
            if t.of_body(own[*b]) != t {
                // the image of a body across an axis about that axis: the body itself
                continue;
            }
            let k = solids.len();
            let points = t.polygon(&shape.points);
            if *b == 0 {
                let n = points.len();
                held.extend((0..n).map(|i| (k, points[i], points[(i + 1) % n])));
            }
            solids.push(Solid {
                name: format!("{}{}", shape.name, t.suffix()),
                points,
            });
            owners.push((body, k));
        }
    }
    // the ground is held wherever its outline and its pads' far sides are the part's
    faces.extend(held.iter().flat_map(|&(k, a, b)| {
        exposed(&solids, k, a, b).into_iter().map(|(a, b)| Face {
            name: "clamp".into(),
            a,
            b,
        })
    }));
    let of = |body: BodyKey| -> Vec<usize> {
        owners
            .iter()
            .filter(|(o, _)| *o == body)
            .map(|&(_, k)| k)
            .collect()
    };
    // a hinge meets its two bodies through its faces, and every solid of a body is joined
    // to every other of it
    for &(own, from, to) in &meets {
        for k in of(from).into_iter().chain(of(to)) {
            if !joints.contains(&(own, k)) {
                joints.push((own, k));
            }
        }
    }
    let mut bodies: Vec<BodyKey> = owners.iter().map(|(o, _)| *o).collect();
    bodies.sort_by_key(|&(b, t)| (b, t.flip_x, t.flip_y));
    bodies.dedup();
    for &body in &bodies {
        let list = of(body);
        for (i, &a) in list.iter().enumerate() {
            for &c in &list[i + 1..] {
                joints.push((a, c));
            }
        }
    }

    // the ports' faces, on the side the force comes from, and their images
    let mut problems = Vec::new();
    let ports = std::iter::once(("input".to_string(), &d.input))
        .chain(d.outputs.iter().map(|o| (format!("output_{}", o.name), o)));
    let mut placed: Vec<PlacedPort> = Vec::new();
    for (name, port) in ports {
        let at = one(v.point(&port.at))?;
        let dir = one(v.point(&port.direction))?;
        let norm = dir[0].hypot(dir[1]);
        let dir = [dir[0] / norm, dir[1] / norm];
        let body = key(port.body + 1, Image::IDENTITY);
        let mine = of(body);
        let body_name = &d.bodies[port.body].name;
        match port_face(&solids, &mine, at, dir, s.face) {
            Err(FaceProblem::Outside) => problems.push(format!(
                "port {name} at ({:.3}, {:.3}) mm lies on no solid of body \"{body_name}\": put \
                 it on the body",
                at[0] * 1e3,
                at[1] * 1e3,
            )),
            Err(FaceProblem::Corner) => problems.push(format!(
                "port {name}: its face falls on a corner of body \"{body_name}\"; move the port \
                 along the body's edge"
            )),
            Err(FaceProblem::Covered(q, other)) => problems.push(format!(
                "port {name}: its face at ({:.3}, {:.3}) mm lies on {}; move the port clear of \
                 it",
                q[0] * 1e3,
                q[1] * 1e3,
                solids[other].name
            )),
            Ok(face) => placed.push(PlacedPort {
                name,
                face,
                direction: dir,
                across: port.across,
                own: &d.bodies[port.body].on_axis,
            }),
        }
    }
    if !problems.is_empty() {
        return Err(problems);
    }
    let grounded = faces.iter().any(|f| f.name == "clamp");
    let mut check = ports_check(&placed, &images, grounded, &mut faces).map_err(|e| vec![e])?;
    if part.actuation.stiffness.is_some() {
        modes_check(&mut check, d, grounded);
    }
    let annotations = hinge_notes(&hinges);
    Ok(PartSpec {
        width: d.width,
        actuation: Some(part.actuation),
        analysis: Some(check),
        solids,
        joints,
        hinges,
        faces,
        annotations,
        caption: format!(
            "flexure network: {}, {}{}{}",
            counted(d.bodies.len(), "body", "bodies"),
            counted(d.hinges.len(), "hinge", "hinges"),
            match d.beams.len() {
                0 => String::new(),
                n => format!(", {}", counted(n, "beam", "beams")),
            },
            if images.len() > 1 {
                format!(", {} images of the described part", images.len())
            } else {
                String::new()
            }
        ),
        min_slot: s.min_slot,
        actuator: None,
        warnings: Vec::new(),
    })
}

/// `n` and the noun in its number.
fn counted(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// The drawing's dimension of each hinge of the described part (its images are its mirror
/// copies): its name, least thickness and length in mm, labelled beside its middle on the
/// side its axis turns left to.
fn hinge_notes(hinges: &[HingeSite]) -> Vec<Annotation> {
    hinges
        .iter()
        .filter(|h| !h.name.ends_with(')'))
        .map(|h| {
            let d = [h.end[0] - h.start[0], h.end[1] - h.start[1]];
            let length = d[0].hypot(d[1]);
            let normal = [-d[1] / length, d[0] / length];
            let at = [0.5 * (h.start[0] + h.end[0]), 0.5 * (h.start[1] + h.end[1])];
            let off = h.root.max(h.thickness) + 2.5e-3;
            Annotation::Note {
                at,
                label_at: [at[0] + off * normal[0], at[1] + off * normal[1]],
                label: format!("{} t {}, l {}", h.name, mm(h.thickness), mm(length)),
            }
        })
        .collect()
}
