//! The network's outputs at its working stroke ([`LargeDeflection`]): the structure of
//! [`super::stroke`] followed from the unloaded part to the full stroke by Newton with load
//! continuation ([`crate::model::large::solve::continuation`]), each point measured as the
//! linear model measures its design, and the linear solution of the same load beside it.
//!
//! The stiffnesses are tangent: the compliance among the ports from the tangent stiffness
//! of the mechanism alone (the actuator taken away, its force on the input left as a load
//! of fixed direction at the input's master node, where it has no offset and so no share
//! in the tangent), `W_ij = read_i C_ij share_j` as the linear model's. A hinge's stress is
//! the hinge library's from the loads at its end on `to` (its last element's end forces in
//! the frame of that end, turned with it), as the linear model states it from its loads.

use super::stroke::{build, Built, Drive, FlexureEnd};
use super::stroke_modes::frequencies_at;
use super::NetworkModel;
use crate::model::hinge::HingeLoads;
use crate::model::large::assemble::{System, SystemOf};
use crate::model::large::critical::by_design::critical_by_design;
use crate::model::large::critical::critical_load_factor;
use crate::model::large::element::{beam, length};
use crate::model::large::report::{
    LargeDeflection, ParasiticOf, StrokeOptions, StrokePoint, StrokePointOf, StrokeReport,
};
use crate::model::large::sensitivity::{equilibrium_by_design, Factored};
use crate::model::large::solve::{continuation, solve_each, Options};
use crate::model::large::LargeError;
use crate::model::scalar::{max, Scalar};

impl LargeDeflection for NetworkModel {
    fn at_stroke(&self, x: &[f64], options: &StrokeOptions) -> Result<StrokeReport, String> {
        let drive = options.force.map_or(Drive::Stack, Drive::Force);
        solve_stroke(self, x, options, drive)
    }
}

fn large(err: LargeError) -> String {
    format!("the large-deflection solve: {err}")
}

/// The network `model` at the design `x` over the stroke `drive` gives.
pub fn solve_stroke(
    model: &NetworkModel,
    x: &[f64],
    options: &StrokeOptions,
    drive: Drive,
) -> Result<StrokeReport, String> {
    let d = model.description();
    // the natural frequencies at each point: the linear model's count, with the stack
    let count = match drive {
        Drive::Stack => model.frequency_count(),
        Drive::Force(_) => 0,
    };
    let solve = |elements: usize, steps: usize| -> Result<(Built<f64>, Vec<StrokePoint>), String> {
        let built = build(model, x, elements, drive)?;
        let opts = Options {
            steps,
            ..Options::default()
        };
        let path = continuation(&built.driven, 1.0, &opts).map_err(large)?;
        let curve = path
            .points
            .iter()
            .map(|p| {
                let mut point = measure(&built, &p.displacement, p.lambda, None)?;
                point.frequencies =
                    frequencies_or_nan(model, x, &built, &p.displacement, p.lambda, count);
                Ok(point)
            })
            .collect::<Result<Vec<_>, String>>()?;
        Ok((built, curve))
    };
    let (built, curve) = solve(options.elements, options.steps)?;
    let mut linear = linear(&built)?;
    let zero = vec![0.0; 3 * built.driven.nodes.len()];
    linear.frequencies = frequencies_or_nan(model, x, &built, &zero, 0.0, count);
    let finer = solve(2 * options.elements, options.steps)?
        .1
        .pop()
        .expect("a path has its end");
    let critical = if options.critical_up_to > 1.0 {
        let opts = critical_options(options.critical_up_to);
        match critical_load_factor(&built.driven, options.critical_up_to, &opts) {
            Ok(c) => Some(c.lambda),
            Err(LargeError::NoCriticalPoint { .. }) => None,
            // no equilibrium from there, and none past it to find the point on
            Err(LargeError::NotConverged { lambda, .. }) => Some(lambda),
            Err(e) => return Err(large(e)),
        }
    } else {
        None
    };
    Ok(StrokeReport {
        elements: options.elements,
        flexures: d
            .hinges
            .iter()
            .map(|h| h.name.clone())
            .chain(d.beams.iter().map(|b| b.name.clone()))
            .collect(),
        outputs: d.outputs.iter().map(|o| o.name.clone()).collect(),
        curve,
        linear,
        critical_load_factor: critical,
        finer: Some(finer),
    })
}

/// The `count` lowest natural frequencies about the equilibrium `u` at `lambda` of the
/// network `model` at the design `x` ([`frequencies_at`]), not-a-number where they cannot
/// be found there (the curve goes on without them).
fn frequencies_or_nan(
    model: &NetworkModel,
    x: &[f64],
    built: &Built<f64>,
    u: &[f64],
    lambda: f64,
    count: usize,
) -> Vec<f64> {
    frequencies_at(model, x, built, u, lambda, count).unwrap_or_else(|_| vec![f64::NAN; count])
}

/// The outputs at the full stroke of the problem's actuator at the design `x`, over the
/// scalar of `x`, with the `frequencies` lowest natural frequencies about its equilibrium:
/// the path solved in real numbers, then the equilibrium's derivatives by the design
/// through the implicit function theorem ([`crate::model::large::sensitivity`]), so a dual
/// `x` gives every output its exact gradient at stroke (to the path's tolerance); the
/// frequencies' by the eigenvalue's derivative at the equilibrium ([`frequencies_at`]).
/// With `modulus` the flexures' moduli are that factor times the material's, and its
/// derivative is carried as the design's.
pub(crate) fn end_by_design<D: Scalar>(
    model: &NetworkModel,
    x: &[D],
    modulus: Option<D>,
    elements: usize,
    steps: usize,
    frequencies: usize,
) -> Result<StrokePointOf<D>, String> {
    let real_x: Vec<f64> = x.iter().map(|v| v.re()).collect();
    let real = stack_driven(model, &real_x, modulus.map(|m| m.re()), elements)?;
    let opts = Options {
        steps,
        ..Options::default()
    };
    let path = continuation(&real.driven, 1.0, &opts).map_err(large)?;
    let end = path.end();
    let system = System::new(&real.driven).map_err(large)?;
    let free: Vec<f64> = system.free.iter().map(|&i| end.displacement[i]).collect();
    let free = system.polish(free, end.lambda);
    let dual = stack_driven(model, x, modulus, elements)?;
    let dual_system = SystemOf::new(&dual.driven).map_err(large)?;
    let u = equilibrium_by_design(&system, &dual_system, &free, end.lambda).map_err(large)?;
    let mut point = measure(&dual, &u, end.lambda, None)?;
    if frequencies > 0 {
        point.frequencies = frequencies_at(model, x, &dual, &u, end.lambda, frequencies)?;
    }
    Ok(point)
}

/// How the critical load factor is looked for up to `up_to`: two load steps a unit of
/// the load factor before the bracket is closed.
fn critical_options(up_to: f64) -> Options {
    Options {
        steps: (2.0 * up_to).ceil() as usize,
        ..Options::default()
    }
}

/// The critical load factor of the problem's actuator on the structure at the design `x`
/// (the load factor by which its free stroke and preload grow until the tangent stiffness
/// stops being positive definite), looked for up to `up_to`, over the scalar of `x`: found
/// in real numbers ([`critical_load_factor`]), its derivatives at the critical point by the
/// design ([`critical_by_design`]). Without a critical point up to `up_to`, `up_to` itself,
/// constant.
pub(crate) fn critical_of<D: Scalar>(
    model: &NetworkModel,
    x: &[D],
    modulus: Option<D>,
    elements: usize,
    up_to: f64,
) -> Result<D, String> {
    let real_x: Vec<f64> = x.iter().map(|v| v.re()).collect();
    let real = stack_driven(model, &real_x, modulus.map(|m| m.re()), elements)?;
    let critical = match critical_load_factor(&real.driven, up_to, &critical_options(up_to)) {
        Ok(c) => c,
        Err(LargeError::NoCriticalPoint { .. }) => return Ok(D::from(up_to)),
        Err(e) => return Err(large(e)),
    };
    let dual = stack_driven(model, x, modulus, elements)?;
    critical_by_design(&real.driven, &dual.driven, &critical).map_err(large)
}

/// The structure at the design `x` driven by the problem's stack, its flexures' moduli
/// `modulus` times the material's where given.
fn stack_driven<D: Scalar>(
    model: &NetworkModel,
    x: &[D],
    modulus: Option<D>,
    elements: usize,
) -> Result<Built<D>, String> {
    let mut built = build(model, x, elements, Drive::Stack)?;
    if let Some(m) = modulus {
        built.scale_modulus(m);
    }
    Ok(built)
}

/// The linear solution of the driven structure's full load: the unloaded tangent's, with
/// the slaves carried by the linear rigid transfer.
fn linear(built: &Built<f64>) -> Result<StrokePoint, String> {
    let system = System::new(&built.driven).map_err(large)?;
    let zero = vec![0.0; 3 * built.driven.nodes.len()];
    let a = system.assemble(&zero, 0.0);
    let du = solve_each(&a.tangent, &[&a.load])
        .ok_or_else(|| large(LargeError::Singular { lambda: 0.0 }))?
        .remove(0);
    let mut u = zero.clone();
    for (&i, &v) in system.free.iter().zip(&du) {
        u[i] = v;
    }
    for &(i, v) in &system.held {
        u[i] = v;
    }
    for (p, m) in system.master.iter().enumerate() {
        if let Some(b) = *m {
            let (xp, xb) = (built.driven.nodes[p], built.driven.nodes[b]);
            let theta = u[3 * b + 2];
            u[3 * p] = u[3 * b] - theta * (xp[1] - xb[1]);
            u[3 * p + 1] = u[3 * b + 1] + theta * (xp[0] - xb[0]);
            u[3 * p + 2] = theta;
        }
    }
    measure(built, &u, 1.0, Some(&zero))
}

/// The outputs at the displacement `u` (every node's) at load factor `lambda`; with
/// `linear_about` the elements' forces are their unloaded stiffness times `u` (the linear
/// solution's) and the stiffnesses the unloaded ones. Over any scalar: with `u` carrying
/// its derivatives by the design ([`end_by_design`]), every output carries its own.
fn measure<D: Scalar>(
    built: &Built<D>,
    u: &[D],
    lambda: f64,
    linear_about: Option<&[D]>,
) -> Result<StrokePointOf<D>, String> {
    let at = linear_about.unwrap_or(u);
    let along = |i: usize| {
        let p = &built.ports[i];
        (u[3 * p.node] * p.direction[0] + u[3 * p.node + 1] * p.direction[1]) * p.read
    };
    let (stroke_in, stroke_out) = (along(0), along(1));
    let w = port_compliance(built, at)?;
    let amplification_tangent = w[1][0] / w[0][0];
    let amplification = if lambda == 0.0 {
        amplification_tangent
    } else {
        stroke_out / stroke_in
    };
    let stresses: Vec<D> = built
        .flexures
        .iter()
        .map(|f| end_stress(built, f, u, linear_about))
        .collect();
    let parasitic = built.ports[1..]
        .iter()
        .map(|p| ParasiticOf {
            across: -(u[3 * p.node] * p.direction[1]) + u[3 * p.node + 1] * p.direction[0],
            rotation: u[3 * p.node + 2],
        })
        .collect();
    Ok(StrokePointOf {
        fraction: lambda,
        stroke_in,
        stroke_out,
        amplification,
        amplification_tangent,
        k_in: w[0][0].recip(),
        k_out: w[1][1].recip(),
        stress_max: stresses.iter().copied().fold(D::from(0.0), max),
        stresses,
        parasitic,
        frequencies: Vec::new(),
    })
}

/// A flexure's largest stress at its end on `to` from its last element's end forces there
/// (in the frame of that end, turned with it), as the linear model states it from its loads.
fn end_stress<D: Scalar>(
    built: &Built<D>,
    f: &FlexureEnd<D>,
    u: &[D],
    linear_about: Option<&[D]>,
) -> D {
    let st = &built.driven;
    let b = &st.beams[f.beam];
    let (xa, xb) = (st.nodes[b.a], st.nodes[b.b]);
    let idx = [
        3 * b.a,
        3 * b.a + 1,
        3 * b.a + 2,
        3 * b.b,
        3 * b.b + 1,
        3 * b.b + 2,
    ];
    let local = b.local(length(xa, xb));
    let force = match linear_about {
        None => beam(xa, xb, local, &idx.map(|i| u[i])).force,
        Some(zero) => {
            let k = beam(xa, xb, local, &idx.map(|i| zero[i])).stiffness;
            std::array::from_fn(|r| {
                (1..6).fold(k[r][0] * u[idx[0]], |sum, c| sum + k[r][c] * u[idx[c]])
            })
        }
    };
    // the frame of the flexure's end on `to`, turned with it
    let (s, c) = if linear_about.is_some() {
        (D::from(0.0), D::from(1.0))
    } else {
        u[idx[5]].sin_cos()
    };
    let e = [c * f.axis[0] - s * f.axis[1], s * f.axis[0] + c * f.axis[1]];
    let loads = HingeLoads {
        axial: force[3] * e[0] + force[4] * e[1],
        shear: -(force[3] * e[1]) + force[4] * e[0],
        moment: force[5],
    };
    let (to, from) = f.kind.end_stresses(&f.dims, built.width, &loads);
    max(to, from)
}

/// `W_ij = read_i C_ij share_j` for the input and the first output, `C` from the tangent of
/// the mechanism alone at `u`.
fn port_compliance<D: Scalar>(built: &Built<D>, u: &[D]) -> Result<[[D; 2]; 2], String> {
    let system = SystemOf::new(&built.alone).map_err(large)?;
    let k = system.tangent(u);
    let column = |i: usize| -> Vec<D> {
        let p = &built.ports[i];
        // the unit force at the port carried to its master at the current offset
        let (node, n) = (p.node, p.direction);
        let master = system.master[node].unwrap_or(node);
        let theta = u[3 * master + 2];
        let (xp, xb) = (built.alone.nodes[node], built.alone.nodes[master]);
        let r0 = [xp[0] - xb[0], xp[1] - xb[1]];
        let (s, c) = theta.sin_cos();
        let r = [c * r0[0] - s * r0[1], s * r0[0] + c * r0[1]];
        let full = [n[0], n[1], -(r[1] * n[0]) + r[0] * n[1]];
        system
            .free
            .iter()
            .map(|&i| {
                if i / 3 == master {
                    full[i % 3]
                } else {
                    D::from(0.0)
                }
            })
            .collect()
    };
    let e = [column(0), column(1)];
    let factored = Factored::of_real_parts(&k, system.free.len());
    if !factored.is_regular() {
        return Err(large(LargeError::Singular { lambda: 0.0 }));
    }
    let x = [
        factored.solve_dual(&k, &e[0]),
        factored.solve_dual(&k, &e[1]),
    ];
    let dot = |a: &[D], b: &[D]| a.iter().zip(b).fold(D::from(0.0), |s, (&x, &y)| s + x * y);
    let p = &built.ports;
    Ok(std::array::from_fn(|i| {
        std::array::from_fn(|j| dot(&e[i], &x[j]) * (p[i].read * p[j].share))
    }))
}
