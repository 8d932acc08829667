//! Properties of the general bridge model over Table 1's bounds: the paper's special
//! closed forms, an independent linear-system formulation, reciprocity, signs, gradients.

use crate::common;

use common::*;
use flexopt::model::bridge::{BridgeOutput, QuarterBridge, OUTPUTS};
use flexopt::model::hinge::{Compliance, HingeKind};
use flexopt::model::material::Material;
use flexopt::model::reference::bridge_matrix;
use flexopt::model::reference::closed_forms;
use flexopt::model::Model;

const W: f64 = 10.0 * MM;

fn hinge(l: f64, t: f64) -> Compliance<f64> {
    HingeKind::Strip.compliance(&[l, t], W, &Material::al7075_t6())
}

fn amplification(q: &QuarterBridge<f64>) -> f64 {
    q.a21() / q.a11()
}

#[test]
fn general_equations_reduce_to_the_parallel_closed_form_eq23() {
    let mut r = rng(23);
    let mut worst = 0.0f64;
    for _ in 0..2000 {
        let x = random_design(&mut r);
        let (l, t, l3, d3) = (x[0], x[2], x[3], x[4]);
        let h = hinge(l, t);
        let q = QuarterBridge::from_compliances(h, h, 0.0, l3, d3, 0.0);
        let expect = closed_forms::parallel(&h, l3, d3);
        worst = worst.max(rel(amplification(&q), expect, 1e-300));
    }
    eprintln!("special closed form, worst relative difference: {worst:e}");
    assert!(worst < 1e-12, "worst relative difference {worst:e}");
}

#[test]
fn general_equations_reduce_to_the_aligned_closed_form_eq27() {
    let mut r = rng(27);
    let mut worst = 0.0f64;
    for _ in 0..2000 {
        let x = random_design(&mut r);
        let (l, t, l3, d) = (x[0], x[2], x[3], x[4]);
        let h = hinge(l, t);
        let q = QuarterBridge::from_compliances(h, h, d, l3, d, d);
        worst = worst.max(rel(
            amplification(&q),
            closed_forms::aligned(&h, l3, d),
            1e-300,
        ));
    }
    eprintln!("special closed form, worst relative difference: {worst:e}");
    assert!(worst < 1e-12, "worst relative difference {worst:e}");
}

#[test]
fn general_equations_reduce_to_the_rhombic_closed_form_eq25() {
    let mut r = rng(25);
    let (mut worst_printed, mut worst_general) = (0.0f64, 0.0f64);
    let nothing = Compliance {
        c11: 0.0,
        c22: 0.0,
        c23: 0.0,
        c33: 0.0,
    };
    for _ in 0..2000 {
        let x = random_design(&mut r);
        let (l, t, d) = (x[5], x[7], x[6]);
        // Eq. 25 as printed assumes Euler-Bernoulli hinges (no shear term in c22)
        let mut bending_only = hinge(l, t);
        bending_only.c22 = 4.0 * l.powi(3) / (72e9 * W * t.powi(3));
        let q = QuarterBridge::from_compliances(nothing, bending_only, 0.0, 0.0, 0.0, d);
        let expect = closed_forms::rhombic(&bending_only, d);
        worst_printed = worst_printed.max(rel(amplification(&q), expect, 1e-300));
        // and the shear-inclusive limit holds for the full strip hinge
        let h = hinge(l, t);
        let q = QuarterBridge::from_compliances(nothing, h, 0.0, 0.0, 0.0, d);
        let expect = closed_forms::rhombic_general(&h, d);
        worst_general = worst_general.max(rel(amplification(&q), expect, 1e-300));
    }
    assert!(worst_printed < 1e-12, "Eq. 25: {worst_printed:e}");
    assert!(
        worst_general < 1e-12,
        "general rhombic limit: {worst_general:e}"
    );
}

#[test]
fn closed_form_agrees_with_the_linear_elastic_system() {
    let settings = wei2017_settings();
    let mut r = rng(10_000);
    let mut worst = 0.0f64;
    for _ in 0..20_000 {
        let x = random_design(&mut r);
        let g = geometry(x);
        let q = QuarterBridge::new(&g, settings.width, &settings.material);
        let a = [[q.a11(), q.a12()], [q.a21(), q.a22()]];
        let m = bridge_matrix::coefficients(&g, settings.width, &settings.material);
        // each coefficient relative to its own size; a12 and a21 may pass through zero, so
        // they are measured against sqrt(a11 |a22|), their Cauchy-Schwarz bound
        let cross = (a[0][0] * a[1][1].abs()).sqrt();
        for (i, j) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            let scale = if i == j { m[(i, j)].abs() } else { cross };
            worst = worst.max((a[i][j] - m[(i, j)]).abs() / scale);
        }
    }
    eprintln!("closed form vs linear system, worst relative difference: {worst:e}");
    assert!(worst < 1e-10, "worst relative difference {worst:e}");
}

#[test]
fn maxwell_betti_reciprocity_and_signs_over_the_bounds_box() {
    let settings = wei2017_settings();
    let mut r = rng(42);
    let corners = (0..256u32).map(|bits| {
        let b = table1_bounds();
        std::array::from_fn(|i| if bits >> i & 1 == 1 { b[i].1 } else { b[i].0 })
    });
    let randoms: Vec<[f64; 8]> = (0..10_000).map(|_| random_design(&mut r)).collect();
    for x in corners.chain(randoms) {
        let q = QuarterBridge::new(&geometry(x), settings.width, &settings.material);
        let (a12, a21) = (q.a12(), q.a21());
        let cross = (q.a11() * q.a22().abs()).sqrt();
        assert!(
            (a12 + a21).abs() <= 1e-13 * cross,
            "a12 = {a12:e}, a21 = {a21:e} at {x:?}"
        );
        assert!(q.a11() > 0.0, "a11 = {:e} at {x:?}", q.a11());
        assert!(q.a22() < 0.0, "a22 = {:e} at {x:?}", q.a22());
        // a positive-definite compliance: a11 |a22| > a12 a21
        assert!(q.a11() * q.a22().abs() > a12 * a12);
    }
}

#[test]
fn exact_gradients_agree_with_finite_differences() {
    let model = wei2017();
    let all: Vec<usize> = (0..BridgeOutput::ALL.len()).collect();
    let parameters = flexopt::model::Model::parameters(&wei2017()).to_vec();
    let n = parameters.len();
    let ranges = table1_bounds().map(|(lo, hi)| hi - lo);
    let mut r = rng(7);
    let mut worst = (0.0f64, "", "");
    let (mut checks, mut kinks) = (0usize, 0usize);
    for _ in 0..1000 {
        let x = random_design(&mut r);
        let mut value = vec![0.0; all.len()];
        let mut jac = vec![0.0; all.len() * n];
        model.evaluate_with_gradient(&x, &all, &mut value, &mut jac);
        let mut plain = vec![0.0; all.len()];
        Model::evaluate(&model, &x, &all, &mut plain);
        for (v, p) in value.iter().zip(&plain) {
            assert!(rel(*v, *p, 1e-300) < 1e-11, "dual {v:e} vs real {p:e}");
        }
        for j in 0..n {
            let h = 1e-5 * ranges[j];
            // the five-point stencil, fourth order in h
            let at = |k: f64| {
                let mut y = x;
                y[j] += k * h;
                let mut f = vec![0.0; all.len()];
                Model::evaluate(&model, &y, &all, &mut f);
                f
            };
            let (f2, f1, f0, fm1, fm2) = (at(2.0), at(1.0), at(0.0), at(-1.0), at(-2.0));
            let (fh, fmh) = (at(0.5), at(-0.5));
            for i in 0..all.len() {
                // derivatives scaled by the bound ranges, measured against the largest
                // scaled derivative of the same output
                let scale = (0..n)
                    .map(|k| (jac[i * n + k] * ranges[k]).abs())
                    .fold(0.0, f64::max);
                if scale == 0.0 {
                    continue;
                }
                // the stresses take a max and absolute values: where a kink lies inside the
                // stencil no derivative exists to compare. The jump between the one-sided
                // slopes is h f'' for a smooth function, halving with h; at a kink it stays.
                let jump = |r: f64, l: f64| ((r - f0[i]) - (f0[i] - l)).abs();
                let (wide, narrow) = (jump(f1[i], fm1[i]) / h, jump(fh[i], fmh[i]) / (0.5 * h));
                checks += 1;
                if narrow > 0.75 * wide && wide * ranges[j] > 1e-9 * scale {
                    kinks += 1;
                    continue;
                }
                let fd_grad = (8.0 * (f1[i] - fm1[i]) - (f2[i] - fm2[i])) / (12.0 * h);
                let err = (fd_grad - jac[i * n + j]).abs() * ranges[j] / scale;
                if err > worst.0 {
                    worst = (err, OUTPUTS[i].name.as_ref(), parameters[j].name.as_ref());
                }
            }
        }
    }
    eprintln!(
        "gradients vs finite differences, worst {:e}: d {} / d {}; {kinks} of {checks} stencils straddled a kink",
        worst.0, worst.1, worst.2
    );
    assert!(kinks * 1000 < checks, "{kinks} kinks in {checks} checks");
    assert!(
        worst.0 < 1e-6,
        "worst {:e}: d {} / d {}",
        worst.0,
        worst.1,
        worst.2
    );
}

#[test]
fn spans_match_the_node_coordinates() {
    let mut r = rng(3);
    for _ in 0..100 {
        let g = geometry(random_design(&mut r));
        let node5 = g.nodes()[3];
        assert!((node5[0] - g.span_x()).abs() < 1e-15);
        assert!((node5[1] - g.span_y()).abs() < 1e-15);
    }
}

#[test]
fn jet_and_num_dual_give_the_same_gradients() {
    use flexopt::model::bridge::Geometry;
    use flexopt::model::scalar::Jet;
    use num_dual::DualSVec64;
    let model = wei2017();
    let all: Vec<usize> = (0..BridgeOutput::ALL.len()).collect();
    let mut r = rng(11);
    // the dynamic outputs pass through the serial chain of bridge_dynamics, whose
    // condensation costs a digit or so (see bridge_matrix): they get their own, looser bound
    let (mut worst, mut worst_dynamic) = (0.0f64, 0.0f64);
    for _ in 0..1000 {
        let x = random_design(&mut r);
        let mut jet = vec![Jet::<8>::from(0.0); all.len()];
        model.evaluate(&model.layout().seeded::<8>(&x), &all, &mut jet);
        let xd: [DualSVec64<8>; 8] =
            std::array::from_fn(|i| DualSVec64::from_re(x[i]).derivative(i));
        let mut nd = vec![DualSVec64::<8>::from_re(0.0); all.len()];
        model.evaluate(&Geometry::from_array(xd), &all, &mut nd);
        for (k, (j, d)) in jet.iter().zip(&nd).enumerate() {
            let worst = if k >= BridgeOutput::KOutActuated as usize {
                &mut worst_dynamic
            } else {
                &mut worst
            };
            // num-dual stores no gradient for a constant (stroke_in of a rigid actuator)
            let g: Vec<f64> = d
                .eps
                .0
                .as_ref()
                .map_or(vec![0.0; 8], |g| g.iter().copied().collect());
            let scale = g.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (a, b) in j.grad.iter().zip(&g) {
                let diff = (a - b).abs();
                *worst = worst.max(if scale > 0.0 { diff / scale } else { diff });
            }
        }
    }
    eprintln!("Jet vs num-dual gradients, worst relative difference: {worst:e}, dynamic outputs {worst_dynamic:e}");
    assert!(worst < 1e-12, "{worst:e}");
    assert!(worst_dynamic < 1e-11, "{worst_dynamic:e}");
}

/// The quarter as a flexure network (issue 25's structural analysis): input link, middle
/// link and output link as rigid bodies, hinges b and d as flexures, the input and output
/// links held on the mirror axes; its compliances under FX and FY are Appendix A's
/// coefficients, which share no formula with it, at 2,000 designs of Table 1, to 1e-10.
#[test]
fn the_quarter_as_a_flexure_network_has_appendix_as_coefficients() {
    use flexopt::model::network::structure::{Body, Dof, Flexure, Load, Network};
    let mut r = rng(2025);
    let mut worst = 0.0f64;
    for _ in 0..2000 {
        let x = random_design(&mut r);
        let g = geometry(x);
        let q = QuarterBridge::new(&g, W, &Material::al7075_t6());
        let [n2, _, n4, n5] = g.nodes();
        let axis = |d: f64| [d.cos(), d.sin()];
        let net = Network {
            references: vec![n2, g.nodes()[1], n5],
            flexures: vec![
                Flexure::new(
                    Body::Rigid(0),
                    Body::Rigid(1),
                    n2,
                    axis(g.delta2),
                    x[0],
                    hinge(x[0], x[2]),
                ),
                Flexure::new(
                    Body::Rigid(1),
                    Body::Rigid(2),
                    n4,
                    axis(g.delta4),
                    x[5],
                    hinge(x[5], x[7]),
                ),
            ],
            springs: vec![],
            held: vec![
                (0, Dof::Y),
                (0, Dof::Rotation),
                (2, Dof::X),
                (2, Dof::Rotation),
            ],
            guides: Vec::new(),
        };
        let solve = |body: usize, force: [f64; 2]| {
            let u = net
                .solve(&[Load {
                    body,
                    point: net.references[body],
                    force,
                    moment: 0.0,
                }])
                .unwrap();
            (u.bodies[0][0], u.bodies[2][1])
        };
        // FX pushes the input link towards the centre; FY is counted against the output
        let (a11, a21) = solve(0, [1.0, 0.0]);
        let (a12, a22) = solve(2, [0.0, -1.0]);
        let scale = q.a11().abs().max(q.a22().abs());
        for (got, want) in [
            (a11, q.a11()),
            (a21, q.a21()),
            (a12, q.a12()),
            (a22, q.a22()),
        ] {
            worst = worst.max(rel(got, want, scale));
        }
    }
    eprintln!("quarter as a network, worst relative difference: {worst:e}");
    // 2.4e-12 measured: round-off of the 9 x 9 solve and of the closed form's sums
    assert!(worst < 1e-10, "worst relative difference {worst:e}");
}

/// The Hessians a robust study's spreads use (`ModulusScaling::evaluate_with_hessian`, by
/// flexopt's `Jet2`) against num-dual's second-order numbers through the same generic code,
/// over the parameters and the moduli's factor.
#[test]
fn jet2_and_num_dual_give_the_same_hessians() {
    use flexopt::model::bridge::Geometry;
    use flexopt::model::mechanism::ModulusScaling;
    use nalgebra::{Const, U1};
    use num_dual::Dual2SVec64;
    const N: usize = 9;
    let model = wei2017();
    let all: Vec<usize> = (0..BridgeOutput::ALL.len()).collect();
    let m = all.len();
    let mut r = rng(12);
    let mut worst = 0.0f64;
    for _ in 0..200 {
        let x = random_design(&mut r);
        let (mut out, mut jac, mut hess) = (vec![0.0; m], vec![0.0; m * N], vec![0.0; m * N * N]);
        model.evaluate_with_hessian(&x, &all, &mut out, &mut jac, &mut hess);
        let xd: [Dual2SVec64<N>; 8] =
            std::array::from_fn(|i| Dual2SVec64::from_re(x[i]).derivative(i));
        let modulus = Dual2SVec64::<N>::from_re(1.0).derivative(N - 1);
        let mut nd = vec![Dual2SVec64::<N>::from_re(0.0); m];
        model.evaluate_with_modulus(&Geometry::from_array(xd), Some(modulus), &all, &mut nd);
        for (k, d) in nd.iter().enumerate() {
            // the dynamic outputs' condensation costs a digit (see the gradients' test)
            if k >= BridgeOutput::KOutActuated as usize {
                continue;
            }
            let g = d.v1.unwrap_generic(U1, Const::<N>);
            let h = d.v2.unwrap_generic(Const::<N>, Const::<N>);
            let g_scale = g.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            let h_scale = h.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            let relative = |a: f64, b: f64, scale: f64| {
                if scale > 0.0 {
                    (a - b).abs() / scale
                } else {
                    (a - b).abs()
                }
            };
            worst = worst.max(relative(out[k], d.re, d.re.abs()));
            for i in 0..N {
                worst = worst.max(relative(jac[k * N + i], g[i], g_scale));
                for l in 0..N {
                    worst = worst.max(relative(hess[(k * N + i) * N + l], h[(i, l)], h_scale));
                }
            }
        }
    }
    eprintln!("Jet2 vs num-dual Hessians, worst relative difference: {worst:e}");
    assert!(worst < 1e-12, "{worst:e}");
}
