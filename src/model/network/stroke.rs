//! The network as a geometrically nonlinear structure ([`crate::model::large`]) at a design:
//! each body a master node with its flexures' ends as slaves, each flexure a chain of `n`
//! corotational beam elements, the mirror axes' and the supports' holds, and the actuator
//! at the input port.
//!
//! Each element's local linear stiffness is the exact inverse of its segment's compliance,
//! computed as the hinge library computes a hinge's (Castigliano's integrals of the profile,
//! [`crate::model::hinge::integrals`], here by adaptive quadrature over the segment; a beam's
//! Timoshenko segment in closed form), and the last segment takes the rounding and quadrature
//! remainder between the segments in series and the flexure's own compliance. So the
//! unloaded structure's stiffness is the linear network's, for any `n`, to rounding; as `n`
//! grows the chain tends to the elastica of the flexure's profile.
//!
//! A mirror axis is the linear network's: the described part with its bodies on an axis
//! held across it and in rotation, a port across an axis read twice (the change of distance
//! to its image) and a body on `k` axes carrying `1 / 2^k` of a load there. So the whole
//! mechanism's stack of stiffness `k_a`, free stroke `X` and preload `P` is, on the
//! described part, a spring of stiffness `share read k_a` with the free stroke `X / read`
//! and the preload `share P` at the input port; an actuator without a stiffness (much
//! stiffer than the mechanism) prescribes the input's motion, `X / read`.

use super::model::{LinearAt, NetworkModel};
use super::structure::{beam_compliance, Body, Dof as NetDof, Flexure};
use crate::model::hinge::profile::integrate;
use crate::model::hinge::{Compliance, HingeKind};
use crate::model::large::{Dof, Local, Section, Spring, Structure};
use crate::model::material::Material;

/// How the input is driven.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Drive {
    /// The problem's actuator: its stack at full free stroke and preload.
    Stack,
    /// A force of fixed direction at the input (N, the whole mechanism's), without the
    /// actuator.
    Force(f64),
}

/// A port as a node of the structure.
#[derive(Debug, Clone, Copy)]
pub(super) struct PortNode {
    pub node: usize,
    pub direction: [f64; 2],
    pub read: f64,
    pub share: f64,
}

/// A flexure's last element (at its end on `to`) and what its stress needs.
#[derive(Debug, Clone)]
pub(super) struct FlexureEnd {
    pub beam: usize,
    pub axis: [f64; 2],
    pub kind: HingeKind,
    pub dims: Vec<f64>,
}

/// The structure at a design: the mechanism driven, and the mechanism alone (the same
/// nodes, the drive's anchor held), whose tangent gives the stiffnesses.
#[derive(Debug, Clone)]
pub(super) struct Built {
    pub driven: Structure,
    pub alone: Structure,
    pub ports: Vec<PortNode>,
    pub flexures: Vec<FlexureEnd>,
    pub width: f64,
    /// Each body's master node.
    pub masters: Vec<usize>,
}

/// The distance of the stack's anchor behind the input port (m): long, so that the
/// stack's force keeps the port's direction as the port moves across it.
const ANCHOR: f64 = 1.0;

/// An axis-aligned unit direction's degree of freedom and sign.
fn axis_dof(n: [f64; 2]) -> Option<(Dof, f64)> {
    match n {
        [x, y] if y == 0.0 && x.abs() == 1.0 => Some((Dof::X, x)),
        [x, y] if x == 0.0 && y.abs() == 1.0 => Some((Dof::Y, y)),
        _ => None,
    }
}

/// The structure of `model` at the design `x` (SI) in `elements` beams a flexure.
pub(super) fn build(
    model: &NetworkModel,
    x: &[f64],
    elements: usize,
    drive: Drive,
) -> Result<Built, String> {
    let lin = model.linear_at(x)?;
    let d = model.description();
    let (material, actuator) = model.material_and_actuator();
    let net = &lin.network;
    let (mut s, masters) = bodies(&lin, model)?;
    let mut flexures = Vec::new();
    for (h, f) in net.flexures.iter().enumerate() {
        let kind = d.hinges.get(h).map(|h| h.kind);
        let segments = segments(kind, &lin.dims[h], f, elements.max(1), d.width, material);
        let end = |s: &mut Structure, body: Body, p: [f64; 2]| {
            let node = s.node(p[0], p[1]);
            match body {
                Body::Ground => s.fix(node),
                Body::Rigid(b) => s.attach(node, masters[b]),
            }
            node
        };
        let a = end(&mut s, f.from, f.start);
        let b = end(&mut s, f.to, f.end);
        let first = s.beams.len();
        let chain = s.flexure(a, b, segments.len(), |_| Section { ea: 1.0, ei: 1.0 });
        let l0 = f.length / segments.len() as f64;
        for (beam, c) in s.beams[first..].iter_mut().zip(&segments) {
            beam.local = Some(Local::from_compliance(l0, c.c11, c.c22, c.c23, c.c33));
        }
        debug_assert_eq!(chain.len(), segments.len() + 1);
        flexures.push(FlexureEnd {
            beam: s.beams.len() - 1,
            axis: f.axis,
            kind: kind.unwrap_or(HingeKind::Strip),
            dims: lin.dims[h].clone(),
        });
    }
    let ports = port_nodes(&mut s, &lin, &masters);
    let anchor = {
        let (p, n) = (lin.ports[0].point, lin.ports[0].force);
        s.node(p[0] - ANCHOR * n[0], p[1] - ANCHOR * n[1])
    };
    s.fix(anchor);
    let alone = s.clone();
    let port = ports[0];
    match (drive, actuator.stiffness) {
        (Drive::Force(force), _) => {
            let f = force * port.share;
            s.load(
                port.node,
                [f * port.direction[0], f * port.direction[1], 0.0],
            );
        }
        (Drive::Stack, Some(k_a)) => s.springs.push(Spring {
            a: anchor,
            b: port.node,
            stiffness: port.share * port.read * k_a,
            free_stroke: actuator.nominal_stroke / port.read,
            preload: port.share * actuator.preload,
        }),
        (Drive::Stack, None) => {
            let (dof, sign) = axis_dof(port.direction).ok_or_else(|| {
                "[actuator] stiffness: an actuator without a stiffness prescribes the input's \
                 motion, which the large-deflection model does along x or y only; give the \
                 actuator its stiffness"
                    .to_string()
            })?;
            if s.held.iter().any(|&(n, h, _)| n == port.node && h == dof) {
                return Err("the input port's motion is held by a mirror axis or a support".into());
            }
            s.prescribe(port.node, dof, sign * actuator.nominal_stroke / port.read);
        }
    }
    Ok(Built {
        driven: s,
        alone,
        ports,
        flexures,
        width: d.width,
        masters,
    })
}

/// The bodies' master nodes with the mirror axes' and the supports' holds. Each master
/// stands at the input port for the input's body (the drive acts there without an offset),
/// at its support for a supported one (held there), else at its reference point.
fn bodies(lin: &LinearAt, model: &NetworkModel) -> Result<(Structure, Vec<usize>), String> {
    let (net, d) = (&lin.network, model.description());
    let mut at: Vec<Option<[f64; 2]>> = vec![None; net.references.len()];
    let input = &lin.ports[0];
    at[input.body] = Some(input.point);
    let mut holds = Vec::new();
    for (g, s) in net.guides.iter().zip(&d.supports) {
        let (dof, _) = axis_dof(g.direction).ok_or_else(|| {
            format!(
                "support ({}): the large-deflection model holds a support along x or y only",
                s.key
            )
        })?;
        match at[g.body] {
            Some(p) if p != g.point => {
                return Err(format!(
                    "support ({}): its body has the input port or another support elsewhere, \
                     which the large-deflection model cannot hold together",
                    s.key
                ))
            }
            _ => at[g.body] = Some(g.point),
        }
        holds.push((g.body, dof));
    }
    let mut s = Structure::default();
    let masters: Vec<usize> = (0..net.references.len())
        .map(|b| {
            let p = at[b].unwrap_or(net.references[b]);
            s.node(p[0], p[1])
        })
        .collect();
    for &(b, dof) in &net.held {
        let dof = match dof {
            NetDof::X => Dof::X,
            NetDof::Y => Dof::Y,
            NetDof::Rotation => Dof::Rotation,
        };
        s.hold(masters[b], dof);
    }
    for &(b, dof) in &holds {
        if !s.held.iter().any(|&(n, h, _)| n == masters[b] && h == dof) {
            s.hold(masters[b], dof);
        }
    }
    Ok((s, masters))
}

/// The ports as nodes: the input its body's master, each output a slave of its body.
fn port_nodes(s: &mut Structure, lin: &LinearAt, masters: &[usize]) -> Vec<PortNode> {
    lin.ports
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let node = if i == 0 {
                masters[p.body]
            } else {
                let node = s.node(p.point[0], p.point[1]);
                s.attach(node, masters[p.body]);
                node
            };
            PortNode {
                node,
                direction: p.force,
                read: lin.read[i],
                share: lin.share[i],
            }
        })
        .collect()
}

/// The compliances of a flexure's `n` equal segments, each at its end toward `to` with its
/// other end clamped, in the flexure's frame; in series they make the flexure's own.
fn segments(
    kind: Option<HingeKind>,
    dims: &[f64],
    f: &Flexure<f64>,
    n: usize,
    width: f64,
    material: &Material,
) -> Vec<Compliance<f64>> {
    let length = f.length;
    let step = length / n as f64;
    let mut out: Vec<Compliance<f64>> = (0..n)
        .map(|i| match kind {
            None => beam_compliance(step, dims[1], width, material),
            Some(kind) => {
                let (lo, hi) = (i as f64 * step, (i + 1) as f64 * step);
                let t = |s: f64| kind.thickness_at(dims, s / length);
                let ew = material.youngs_modulus * width;
                let i0 = integrate(&|s| 1.0 / t(s), lo, hi);
                let i3: Vec<f64> = (0..3)
                    .map(|k| integrate(&|s| (hi - s).powi(k) / t(s).powi(3), lo, hi))
                    .collect();
                // E / G = 2 (1 + nu): paper 004's shear factor 1, as the hinges' integrals
                let shear = 2.0 * (1.0 + material.poisson_ratio);
                Compliance {
                    c11: i0 / ew,
                    c22: (12.0 * i3[2] + shear * i0) / ew,
                    c23: 12.0 * i3[1] / ew,
                    c33: 12.0 * i3[0] / ew,
                }
            }
        })
        .collect();
    // the segments in series at the flexure's end: each carried over the distance `a`
    // from its end to the flexure's by the rigid transfer (the last with `a = 0`)
    let mut sum = [0.0; 4];
    for (i, c) in out.iter().enumerate() {
        let a = length - (i + 1) as f64 * step;
        sum[0] += c.c11;
        sum[1] += c.c22 + 2.0 * a * c.c23 + a * a * c.c33;
        sum[2] += c.c23 + a * c.c33;
        sum[3] += c.c33;
    }
    let whole = f.compliance;
    let last = out.last_mut().expect("one segment at least");
    last.c11 += whole.c11 - sum[0];
    last.c22 += whole.c22 - sum[1];
    last.c23 += whole.c23 - sum[2];
    last.c33 += whole.c33 - sum[3];
    out
}
