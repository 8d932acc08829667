//! Evaluation cost of the general bridge model (issue goal: <= 60 ns for the values of
//! wei2017's objective and constraints, <= 400 ns with their gradients), and of the same
//! through the solvers' view of the problem (scaled variables, constraint rows).

use std::hint::black_box;
use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use flexopt::model::bridge::{Actuator, Bridge, BridgeOutput, BridgeSettings, Geometry};
use flexopt::model::hinge::HingeKind;
use flexopt::model::material::Material;
use flexopt::model::scalar::Jet;
use flexopt::optim::Problem as _;
use flexopt::problem::nlp::DesignNlp;
use flexopt::problem::Problem;
use num_dual::DualSVec64;

#[path = "support/table1.rs"]
mod table1;
use table1::table1_design;

fn bench(c: &mut Criterion) {
    let problem = Problem::load(Path::new("problems/wei2017.toml")).unwrap();
    let model = problem.model();
    let x = table1_design();
    // the closed-form outputs of paper 004, before the dynamic ones
    let static_outputs: Vec<usize> = (0..BridgeOutput::KOutActuated as usize).collect();
    let mut out = vec![0.0; static_outputs.len()];
    c.bench_function("bridge/all_static_outputs", |b| {
        b.iter(|| model.evaluate(black_box(&x), &static_outputs, &mut out))
    });

    // the objective and every constraint row as the solver sees them, at Table 1's design
    for (name, file) in [
        ("wei2017", "problems/wei2017.toml"),
        // the frequency floor of wei2017_dynamic: the serial chain and the mass as well
        ("wei2017_dynamic", "problems/wei2017_dynamic.toml"),
    ] {
        let p = Problem::load(Path::new(file)).unwrap();
        let nlp = DesignNlp::new(&p);
        let u = nlp.scale(&x);
        let (n, m) = (nlp.dimension(), nlp.constraint_count());
        let (mut g, mut cons, mut jac) = (vec![0.0; n], vec![0.0; m], vec![0.0; m * n]);
        c.bench_function(&format!("{name}/objective_and_constraints"), |b| {
            b.iter(|| nlp.evaluate(black_box(&u), &mut cons))
        });
        c.bench_function(
            &format!("{name}/objective_and_constraints_with_gradients"),
            |b| b.iter(|| nlp.evaluate_with_gradient(black_box(&u), &mut cons, &mut g, &mut jac)),
        );
    }
}

/// The same model differentiated two ways, side by side: flexopt's `Jet<8>` and num-dual's
/// `DualSVec64<8>`.
fn gradient_backends(c: &mut Criterion) {
    let problem = Problem::load(Path::new("problems/wei2017.toml")).unwrap();
    let wanted = DesignNlp::new(&problem).wanted().to_vec();
    // problems/wei2017.toml's bridge
    let bridge = Bridge::new(BridgeSettings {
        hinge_b: HingeKind::Strip,
        hinge_d: HingeKind::Strip,
        width: 10e-3,
        material: Material::al7075_t6(),
        actuator: Actuator {
            nominal_stroke: 17.4e-6,
            preload: 40.0,
            stiffness: None,
            mass: None,
        },
        dynamics: None,
        part: flexopt::model::bridge::part::PartSettings::default(),
    });
    let x = table1_design();
    let mut out_jet = vec![Jet::<8>::from(0.0); wanted.len()];
    c.bench_function("gradient_backend/jet", |b| {
        b.iter(|| {
            bridge.evaluate(
                &bridge.layout().seeded::<8>(black_box(&x)),
                &wanted,
                &mut out_jet,
            )
        })
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
