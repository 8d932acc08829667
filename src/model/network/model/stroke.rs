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

use super::super::structure::{beam_compliance, Body, Dof as NetDof, Flexure};
use super::{LinearAt, NetworkModel};
use crate::model::hinge::profile::integrate_over;
use crate::model::hinge::{Compliance, HingeKind};
use crate::model::large::{Dof, LocalOf, Section, SpringOf, StructureOf};
use crate::model::material::Material;
use crate::model::scalar::Scalar;

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
pub(crate) struct PortNode<D> {
    pub node: usize,
    pub direction: [D; 2],
    pub read: f64,
    pub share: f64,
}

/// A flexure's last element (at its end on `to`) and what its stress needs.
#[derive(Debug, Clone)]
pub(crate) struct FlexureEnd<D> {
    pub beam: usize,
    pub axis: [D; 2],
    pub kind: HingeKind,
    pub dims: Vec<D>,
}

/// The structure at a design: the mechanism driven, and the mechanism alone (the same
/// nodes, the drive's anchor held), whose tangent gives the stiffnesses. Over a scalar
/// `D`: real to be solved, dual to carry the design's derivatives
/// ([`crate::model::large::sensitivity`]).
#[derive(Debug, Clone)]
pub(crate) struct Built<D> {
    pub driven: StructureOf<D>,
    pub alone: StructureOf<D>,
    pub ports: Vec<PortNode<D>>,
    pub flexures: Vec<FlexureEnd<D>>,
    pub width: f64,
    /// Each body's master node.
    pub masters: Vec<usize>,
}

impl<D: Scalar> Built<D> {
    /// Every flexure's stiffness times `factor`, the factor on the material's moduli (E and
    /// G alike, as the linear model's [`crate::model::mechanism::ModulusScaling`]): the
    /// stack's spring and the rigid bodies stay as they are.
    pub(crate) fn scale_modulus(&mut self, factor: D) {
        for s in [&mut self.driven, &mut self.alone] {
            for local in s.beams.iter_mut().filter_map(|b| b.local.as_mut()) {
                local.axial = local.axial * factor;
                for v in local.bending.iter_mut().flatten() {
                    *v = *v * factor;
                }
            }
        }
    }
}

/// The distance of the stack's anchor behind the input port (m): long, so that the
/// stack's force keeps the port's direction as the port moves across it.
const ANCHOR: f64 = 1.0;

/// An axis-aligned unit direction's degree of freedom and sign.
fn axis_dof<D: Scalar>(n: [D; 2]) -> Option<(Dof, f64)> {
    match n.map(|v| v.re()) {
        [x, y] if y == 0.0 && x.abs() == 1.0 => Some((Dof::X, x)),
        [x, y] if x == 0.0 && y.abs() == 1.0 => Some((Dof::Y, y)),
        _ => None,
    }
}

/// The structure of `model` at the design `x` (SI) in `elements` beams a flexure.
pub(crate) fn build<D: Scalar>(
    model: &NetworkModel,
    x: &[D],
    elements: usize,
    drive: Drive,
) -> Result<Built<D>, String> {
    let lin = model.linear_at(x)?;
    let d = model.description();
    let (material, actuator) = model.material_and_actuator();
    let net = &lin.network;
    let (mut s, masters) = bodies(&lin, model)?;
    let mut flexures = Vec::new();
    for (h, f) in net.flexures.iter().enumerate() {
        let kind = d.hinges.get(h).map(|h| h.kind);
        let segments = segments(kind, &lin.dims[h], f, elements.max(1), d.width, material);
        let end = |s: &mut StructureOf<D>, body: Body, p: [D; 2]| {
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
            beam.local = Some(LocalOf::from_compliance(l0, c.c11, c.c22, c.c23, c.c33));
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
        s.node(p[0] - n[0] * ANCHOR, p[1] - n[1] * ANCHOR)
    };
    s.fix(anchor);
    let alone = s.clone();
    let port = ports[0];
    match (drive, actuator.stiffness) {
        (Drive::Force(force), _) => {
            let f = force * port.share;
            s.load(
                port.node,
                [port.direction[0] * f, port.direction[1] * f, D::from(0.0)],
            );
        }
        (Drive::Stack, Some(k_a)) => s.springs.push(SpringOf {
            a: anchor,
            b: port.node,
            stiffness: D::from(port.share * port.read * k_a),
            free_stroke: D::from(actuator.nominal_stroke / port.read),
            preload: D::from(port.share * actuator.preload),
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
            s.prescribe(
                port.node,
                dof,
                D::from(sign * actuator.nominal_stroke / port.read),
            );
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
fn bodies<D: Scalar>(
    lin: &LinearAt<D>,
    model: &NetworkModel,
) -> Result<(StructureOf<D>, Vec<usize>), String> {
    let (net, d) = (&lin.network, model.description());
    let mut at: Vec<Option<[D; 2]>> = vec![None; net.references.len()];
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
            Some(p) if p.map(|v| v.re()) != g.point.map(|v| v.re()) => {
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
    let mut s = StructureOf::default();
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
fn port_nodes<D: Scalar>(
    s: &mut StructureOf<D>,
    lin: &LinearAt<D>,
    masters: &[usize],
) -> Vec<PortNode<D>> {
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
/// other end clamped, in the flexure's frame; in series they make the flexure's own. Segment
/// `i`'s integrals are taken over its own fraction `tau` in (0, 1), `s = (i + tau) step`, so
/// that the quadrature's points are fixed fractions of the profile and a dual number's
/// derivatives by the dimensions and the length come from the same rule.
fn segments<D: Scalar>(
    kind: Option<HingeKind>,
    dims: &[D],
    f: &Flexure<D>,
    n: usize,
    width: f64,
    material: &Material,
) -> Vec<Compliance<D>> {
    let length = f.length;
    let step = length / n as f64;
    let mut out: Vec<Compliance<D>> = (0..n)
        .map(|i| match kind {
            None => beam_compliance(step, dims[1], width, material),
            Some(kind) => {
                let t = |tau: f64| kind.thickness_at(dims, (i as f64 + tau) / n as f64);
                let ew = material.youngs_modulus * width;
                let i0 = integrate_over(&|tau| t(tau).recip(), 0.0, 1.0) * step;
                // int (hi - s)^k / t^3 ds = step^(k+1) int (1 - tau)^k / t^3 dtau
                let i3: Vec<D> = (0..3)
                    .map(|k| {
                        let f = |tau: f64| t(tau).powi(3).recip() * (1.0 - tau).powi(k);
                        integrate_over(&f, 0.0, 1.0) * step.powi(k + 1)
                    })
                    .collect();
                // E / G = 2 (1 + nu): paper 004's shear factor 1, as the hinges' integrals
                let shear = 2.0 * (1.0 + material.poisson_ratio);
                Compliance {
                    c11: i0 / ew,
                    c22: (i3[2] * 12.0 + i0 * shear) / ew,
                    c23: i3[1] * 12.0 / ew,
                    c33: i3[0] * 12.0 / ew,
                }
            }
        })
        .collect();
    // the segments in series at the flexure's end: each carried over the distance `a`
    // from its end to the flexure's by the rigid transfer (the last with `a = 0`)
    let zero = D::from(0.0);
    let mut sum = [zero; 4];
    for (i, c) in out.iter().enumerate() {
        let a = length - step * (i + 1) as f64;
        sum[0] = sum[0] + c.c11;
        sum[1] = sum[1] + c.c22 + a * c.c23 * 2.0 + a * a * c.c33;
        sum[2] = sum[2] + c.c23 + a * c.c33;
        sum[3] = sum[3] + c.c33;
    }
    let whole = f.compliance;
    let last = out.last_mut().expect("one segment at least");
    last.c11 = last.c11 + whole.c11 - sum[0];
    last.c22 = last.c22 + whole.c22 - sum[1];
    last.c23 = last.c23 + whole.c23 - sum[2];
    last.c33 = last.c33 + whole.c33 - sum[3];
    out
}
