//! Evaluation cost of the general bridge model (issue goal: <= 60 ns for the values of
//! wei2017's objective and constraints, <= 400 ns with their gradients).

use std::hint::black_box;
use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use flexopt::model::bridge::{BridgeOutput, Geometry};
use flexopt::model::scalar::Jet;
use flexopt::problem::bind::Evaluator;
use flexopt::problem::{ModelSpec, Problem};
use num_dual::DualSVec64;

fn bench(c: &mut Criterion) {
    let problem = Problem::load(Path::new("problems/wei2017.toml")).unwrap();
    let model = problem.model();
    let deg = std::f64::consts::PI / 180.0;
    let x = [
        1.96e-3,
        4.07 * deg,
        0.4e-3,
        8.1e-3,
        4.01 * deg,
        1.96e-3,
        4.07 * deg,
        0.4e-3,
    ];
    // the closed-form outputs of paper 004, before the dynamic ones
    let static_outputs: Vec<usize> = (0..BridgeOutput::KOutActuated as usize).collect();
    let mut out = vec![0.0; static_outputs.len()];
    c.bench_function("bridge/all_static_outputs", |b| {
        b.iter(|| model.evaluate(black_box(&x), &static_outputs, &mut out))
    });

    let ev = Evaluator::new(&problem);
    let n = ev.dimension();
    let m = problem.constraints.len();
    let (mut f, mut g, mut cons, mut jac) = (0.0, vec![0.0; n], vec![0.0; m], vec![0.0; m * n]);
    c.bench_function("wei2017/objective_and_constraints", |b| {
        b.iter(|| ev.evaluate(black_box(&x), &mut f, &mut cons))
    });
    c.bench_function("wei2017/objective_and_constraints_with_gradients", |b| {
        b.iter(|| ev.evaluate_with_gradient(black_box(&x), &mut f, &mut g, &mut cons, &mut jac))
    });

    // the same with the frequency floor of wei2017_dynamic: the serial chain and the mass
    let dynamic = Problem::load(Path::new("problems/wei2017_dynamic.toml")).unwrap();
    let ev = Evaluator::new(&dynamic);
    let m = dynamic.constraints.len();
    let (mut cons, mut jac) = (vec![0.0; m], vec![0.0; m * n]);
    c.bench_function("wei2017_dynamic/objective_and_constraints", |b| {
        b.iter(|| ev.evaluate(black_box(&x), &mut f, &mut cons))
    });
    c.bench_function(
        "wei2017_dynamic/objective_and_constraints_with_gradients",
        |b| {
            b.iter(|| ev.evaluate_with_gradient(black_box(&x), &mut f, &mut g, &mut cons, &mut jac))
        },
    );
}

/// The same model differentiated two ways, side by side: flexopt's `Jet<8>` and num-dual's
/// `DualSVec64<8>`.
fn gradient_backends(c: &mut Criterion) {
    let problem = Problem::load(Path::new("problems/wei2017.toml")).unwrap();
    let ModelSpec::Bridge(bridge) = &problem.model else {
        unreachable!("wei2017 is a bridge problem")
    };
    let ev = Evaluator::new(&problem);
    let wanted = ev.wanted().to_vec();
    let deg = std::f64::consts::PI / 180.0;
    let x = [
        1.96e-3,
        4.07 * deg,
        0.4e-3,
        8.1e-3,
        4.01 * deg,
        1.96e-3,
        4.07 * deg,
        0.4e-3,
    ];
    let mut out_jet = vec![Jet::<8>::from(0.0); wanted.len()];
    c.bench_function("gradient_backend/jet", |b| {
        b.iter(|| bridge.evaluate(&Geometry::seeded(black_box(&x)), &wanted, &mut out_jet))
    });
    let mut out_nd = vec![DualSVec64::<8>::from_re(0.0); wanted.len()];
    c.bench_function("gradient_backend/num_dual", |b| {
        b.iter(|| {
            let xd: [DualSVec64<8>; 8] =
                std::array::from_fn(|i| DualSVec64::from_re(black_box(x[i])).derivative(i));
            bridge.evaluate(&Geometry::from_array(xd), &wanted, &mut out_nd)
        })
    });
}

criterion_group!(benches, bench, gradient_backends);
criterion_main!(benches);
