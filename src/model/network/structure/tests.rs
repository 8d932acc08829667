//! The structure's tests: the closed forms it must meet (a cantilever at any angle, a
//! parallelogram guide, paper 004's quarter rhombus), a symmetric and reciprocal stiffness,
//! exact derivatives, the free body and the self-joined flexure named, and buffers kept
//! across structures. A child file, so that `structure.rs` holds the analysis alone.

use super::*;
use crate::model::hinge::HingeKind;
use crate::model::material::Material;
use crate::model::scalar::Jet;

fn strip<D: Scalar>(length: D, thickness: D) -> Compliance<D> {
    HingeKind::Strip.compliance(&[length, thickness], 0.01, &Material::al7075_t6())
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs())
}

/// One flexure from the ground: its free end moves by its compliance, turned into the
/// flexure's frame and back, at every orientation.
#[test]
fn a_cantilever_moves_by_its_compliance_at_any_angle() {
    let c = strip(0.004, 0.0005);
    for k in 0..12 {
        let phi = -3.0 + 0.5 * k as f64;
        let (s, co) = phi.sin_cos();
        let start = [0.003, -0.002];
        let f = Flexure::new(Body::Ground, Body::Rigid(0), start, [co, s], 0.004, c);
        let end = f.end;
        let net = Network {
            references: vec![end],
            flexures: vec![f],
            springs: vec![],
            guides: vec![],
            held: vec![],
        };
        let (fx, fy, m) = (3.0, -2.0, 0.01);
        let u = net
            .solve(&[Load {
                body: 0,
                point: end,
                force: [fx, fy],
                moment: m,
            }])
            .unwrap();
        let (n, v) = (co * fx + s * fy, -s * fx + co * fy);
        let (dx, dy, th) = (c.c11 * n, c.c22 * v + c.c23 * m, c.c23 * v + c.c33 * m);
        let expected = [co * dx - s * dy, s * dx + co * dy, th];
        for (got, want) in u.bodies[0].iter().zip(expected) {
            assert!(close(*got, want, 1e-9), "{phi}: {got} against {want}");
        }
        // the flexure carries the load, turned into its frame
        let loads = net.flexure_loads(0, &u);
        for (got, want) in [(loads.axial, n), (loads.shear, v), (loads.moment, m)] {
            assert!(close(got, want, 1e-9), "{phi}: {got} against {want}");
        }
    }
}

/// Two parallel strips from the ground to a stage (a parallelogram guide), loaded
/// sideways at the middle of their ends: the matrix method against the guide's closed
/// form, with the strips' axial compliance letting the stage tilt,
/// `F / v = 2 (a - b^2 / (c + k_a h^2 / 4))`, `[a b; b c]` the strips' bending block
/// inverted and `k_a` their axial stiffness; and against beam theory's guided beams,
/// `24 E I / l^3`, which leaves out the strips' shear and axial give.
#[test]
fn a_parallelogram_guide_has_the_guided_beams_stiffness() {
    let (l, t, h) = (0.01, 0.0003, 0.02);
    let c = strip(l, t);
    let leaf = |y: f64| Flexure::new(Body::Ground, Body::Rigid(0), [0.0, y], [1.0, 0.0], l, c);
    let net = Network {
        references: vec![[l, 0.0]],
        flexures: vec![leaf(-h / 2.0), leaf(h / 2.0)],
        springs: vec![],
        guides: vec![],
        held: vec![],
    };
    let force = 1.0;
    let u = net
        .solve(&[Load {
            body: 0,
            point: [l, 0.0],
            force: [0.0, force],
            moment: 0.0,
        }])
        .unwrap();
    let det = c.c22 * c.c33 - c.c23 * c.c23;
    let (a, b, cc) = (c.c33 / det, -c.c23 / det, c.c22 / det);
    let ka = 1.0 / c.c11;
    let closed = 2.0 * (a - b * b / (cc + ka * h * h / 4.0));
    let k = force / u.bodies[0][1];
    assert!(close(k, closed, 1e-10), "{k} against {closed}");
    // the shears carry the load; about the stage's reference point, the strips' end
    // moments and the couple of their axial forces across the guide balance
    let theta = u.bodies[0][2];
    for (i, y) in [(0, -h / 2.0), (1, h / 2.0)] {
        let loads = net.flexure_loads(i, &u);
        let axial = -ka * theta * y;
        assert!(close(loads.axial, axial, 1e-6), "{} {axial}", loads.axial);
        let (v, th) = (u.bodies[0][1], theta);
        assert!(close(loads.shear, a * v + b * th, 1e-9));
        assert!(close(loads.moment, b * v + cc * th, 1e-9));
    }
    let (l0, l1) = (net.flexure_loads(0, &u), net.flexure_loads(1, &u));
    assert!(
        close(l0.shear + l1.shear, force, 1e-9),
        "the shears carry the load"
    );
    let arm = l0.moment + l1.moment + (l0.axial - l1.axial) * h / 2.0;
    assert!(arm.abs() < 1e-9 * force * l, "the moments balance: {arm}");
    assert!(
        u.bodies[0][0].abs() < 1e-12 * u.bodies[0][1].abs(),
        "no axial motion"
    );
    // beam theory: Euler-Bernoulli, 24 E I / l^3; with the strips' shear (the strip's
    // c22 takes the shear deflection l / (G w t)), 2 / (l^3 / (12 E I) + l / (G w t));
    // the stage's tilt on the strips' axial give is left, 3 (t/h)^2 / 4 of the bending
    // block's coupling (2e-4 here)
    let m = Material::al7075_t6();
    let ei = m.youngs_modulus * (0.01 * t.powi(3) / 12.0);
    let beam = 24.0 * ei / l.powi(3);
    let shear = l / (m.shear_modulus() * 0.01 * t);
    let timoshenko = 2.0 / (l.powi(3) / (12.0 * ei) + shear);
    assert!(close(k, timoshenko, 3e-4), "{k} against {timoshenko}");
    assert!(k < timoshenko && k < beam, "{k} against {beam}");
}

/// The stiffness is symmetric and positive definite; by Maxwell-Betti, the motion at
/// one point along one direction under a unit force at another equals the converse.
#[test]
fn the_stiffness_is_symmetric_and_reciprocal() {
    let net = two_stage(0.0004);
    let k = net.stiffness().unwrap();
    let n = 6;
    for i in 0..n {
        for j in 0..n {
            assert!(close(k[i * n + j], k[j * n + i], 1e-12) || k[i * n + j].abs() < 1e-6);
        }
    }
    let (p, q) = ([0.012, 0.003], [0.02, -0.004]);
    let (dp, dq) = ([0.6, 0.8], [0.0, 1.0]);
    let unit = |body, point: [f64; 2], dir: [f64; 2]| Load {
        body,
        point,
        force: dir,
        moment: 0.0,
    };
    let a = net
        .solve(&[unit(0, p, dp)])
        .unwrap()
        .along(Body::Rigid(1), q, dq);
    let b = net
        .solve(&[unit(1, q, dq)])
        .unwrap()
        .along(Body::Rigid(0), p, dp);
    assert!(close(a, b, 1e-9), "{a} {b}");
}

/// Two bodies: the first held by two strips from the ground, the second joined to it
/// and to the ground by one strip each, with an actuator's spring on the first.
fn two_stage<D: Scalar>(t: D) -> Network<D> {
    let c = |l: f64| strip(D::from(l), t);
    let flexure = |from, to, start: [f64; 2], axis: [f64; 2], l: f64| {
        Flexure::new(
            from,
            to,
            start.map(D::from),
            axis.map(D::from),
            D::from(l),
            c(l),
        )
    };
    Network {
        references: vec![[D::from(0.01), D::from(0.0)], [D::from(0.02), D::from(0.0)]],
        flexures: vec![
            flexure(
                Body::Ground,
                Body::Rigid(0),
                [0.0, 0.002],
                [1.0, 0.0],
                0.004,
            ),
            flexure(
                Body::Ground,
                Body::Rigid(0),
                [0.0, -0.002],
                [0.8, -0.6],
                0.003,
            ),
            flexure(
                Body::Rigid(0),
                Body::Rigid(1),
                [0.012, 0.0],
                [0.6, 0.8],
                0.002,
            ),
            flexure(
                Body::Ground,
                Body::Rigid(1),
                [0.03, 0.01],
                [-0.6, -0.8],
                0.005,
            ),
        ],
        springs: vec![Spring {
            body: 0,
            point: [D::from(0.01), D::from(0.001)],
            direction: [D::from(1.0), D::from(0.0)],
            stiffness: D::from(2e6),
        }],
        held: vec![],
        guides: vec![],
    }
}

/// Exact derivatives through the solve: a `Jet` over the hinges' thickness against
/// central differences.
#[test]
fn displacements_have_exact_derivatives() {
    let t = 0.0004;
    let load = |body| Load {
        body,
        point: [0.01, 0.001],
        force: [1.0, 0.5],
        moment: 0.0,
    };
    let motion = |t: f64| {
        let net = two_stage(t);
        let u = net.solve(&[load(0)]).unwrap();
        u.along(Body::Rigid(1), [0.02, 0.0], [0.0, 1.0])
    };
    let jet = {
        let net = two_stage(Jet::<1>::variable(t, 0));
        let loads = [Load {
            body: 0,
            point: [0.01, 0.001].map(Jet::from),
            force: [1.0, 0.5].map(Jet::from),
            moment: Jet::from(0.0),
        }];
        let u = net.solve(&loads).unwrap();
        u.along(
            Body::Rigid(1),
            [0.02, 0.0].map(Jet::from),
            [0.0, 1.0].map(Jet::from),
        )
    };
    let h = 1e-9;
    let fd = (motion(t + h) - motion(t - h)) / (2.0 * h);
    // the same solve, its operations grouped differently in the dual number
    assert!(close(jet.re, motion(t), 1e-12));
    assert!(close(jet.grad[0], fd, 1e-6), "{} against {fd}", jet.grad[0]);
}

#[test]
fn a_free_body_and_a_self_joined_flexure_are_named() {
    let mut net = two_stage(0.0004);
    net.references.push([0.05, 0.0]);
    assert_eq!(
        net.stiffness().map(|_| ()),
        Ok(()),
        "the matrix is built; the solve finds the free body"
    );
    let err = net.solve(&[]).unwrap_err();
    assert_eq!(
        err,
        NetworkError::Free {
            body: 2,
            direction: "x"
        }
    );
    assert!(err.to_string().contains("body 2 is free to move (x)"));
    // a body held by one strip along its axis only, hinged at the ground: it turns
    let mut hinged = two_stage(0.0004);
    hinged.flexures.truncate(1);
    hinged.flexures[0].compliance.c33 = 1e12;
    hinged.flexures[0].compliance.c23 = 0.0;
    hinged.flexures[0].compliance.c22 = 1e12;
    hinged.springs.clear();
    hinged.references.truncate(1);
    let err = hinged.solve(&[]).unwrap_err();
    assert!(matches!(err, NetworkError::Free { body: 0, .. }), "{err:?}");
    let mut joined = two_stage(0.0004);
    joined.flexures[2].to = Body::Rigid(0);
    assert_eq!(
        joined.stiffness().map(|_| ()),
        Err(NetworkError::SelfJoined { flexure: 2 })
    );
}

/// The solve's buffers, kept from one network to the next (a thread evaluates several
/// models with them), form their plan of the assembly again when the structure changes:
/// the same flexures with a degree of freedom held, or the flexures joining other
/// bodies, solve as with fresh buffers, in any order.
#[test]
fn buffers_kept_across_structures_solve_as_fresh_ones() {
    let free = two_stage(0.0004);
    let mut held = two_stage(0.0004);
    held.held = vec![(1, Dof::Rotation)];
    let mut rejoined = two_stage(0.0004);
    rejoined.flexures[1].to = Body::Rigid(1);
    let loads = [Load {
        body: 1,
        point: [0.02, 0.001],
        force: [0.3, -1.0],
        moment: 0.002,
    }];
    let cases = [Case {
        loads: &loads,
        read: None,
    }];
    let mut buffers = SolveBuffers::default();
    let mut solutions = Vec::new();
    for net in [&free, &held, &rejoined, &free, &rejoined, &held, &held] {
        let fresh = net.solve(&loads).unwrap();
        let solved = net.solve_cases_in(&cases, &mut buffers).unwrap();
        let kept = solved.case(0);
        assert_eq!(&*kept.bodies, &*fresh.bodies);
        for i in 0..net.flexures.len() {
            assert_eq!(net.flexure_loads(i, &kept), net.flexure_loads(i, &fresh));
        }
        solutions.push(fresh.bodies[1]);
    }
    // the three structures differ, so a stale plan would show
    assert_eq!(solutions[1][2], 0.0, "held");
    assert!(solutions[0][2] != 0.0);
    assert!(solutions[0][0] != solutions[2][0]);
}

/// A quarter of a rhombic bridge: one hinge from the input block (held on the output's
/// mirror axis: no vertical motion, no rotation) to the output block (on the input's
/// axis: no horizontal motion, no rotation). Its amplification is paper 004's rhombic
/// limit of Eq. 9 for any hinge, and Eq. 25 as printed for a hinge without shear
/// compliance ([`crate::model::reference::closed_forms`]).
#[test]
fn a_quarter_rhombus_amplifies_as_paper_004s_closed_form() {
    use crate::model::reference::closed_forms::{rhombic, rhombic_general};
    let mut worst = [0.0f64; 2];
    for k in 0..40 {
        let delta = 0.01 + 0.02 * k as f64;
        let (length, t) = (0.004 + 0.0002 * k as f64, 0.0003 + 0.00001 * k as f64);
        let mut bending_only = strip(length, t);
        for (i, c) in [strip(length, t), {
            bending_only.c22 = 4.0 * length.powi(3) / (72e9 * 0.01 * t.powi(3));
            bending_only
        }]
        .into_iter()
        .enumerate()
        {
            let (s, co) = delta.sin_cos();
            let end = [length * co, length * s];
            let net = Network {
                references: vec![[0.0, 0.0], end],
                flexures: vec![Flexure::new(
                    Body::Rigid(0),
                    Body::Rigid(1),
                    [0.0, 0.0],
                    [co, s],
                    length,
                    c,
                )],
                springs: vec![],
                guides: vec![],
                held: vec![
                    (0, Dof::Y),
                    (0, Dof::Rotation),
                    (1, Dof::X),
                    (1, Dof::Rotation),
                ],
            };
            let u = net
                .solve(&[Load {
                    body: 0,
                    point: [0.0, 0.0],
                    force: [1.0, 0.0],
                    moment: 0.0,
                }])
                .unwrap();
            let da = u.bodies[1][1] / u.bodies[0][0];
            let expected = if i == 0 {
                rhombic_general(&c, delta)
            } else {
                rhombic(&c, delta)
            };
            worst[i] = worst[i].max((da - expected).abs() / expected.abs());
        }
    }
    assert!(worst[0] < 1e-12 && worst[1] < 1e-12, "{worst:?}");
}
