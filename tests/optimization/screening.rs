//! The SQP's constraint screening and the study's shared hand-overs between stages: the
//! same solutions as without them.

use std::sync::atomic::{AtomicUsize, Ordering};

use crate::common::hs::Hs;
use flexopt::model::scalar::Jet;
use flexopt::optim::sqp::{self, SqpSettings};
use flexopt::optim::staged::{HandOvers, GRID};
use flexopt::optim::{Solution, Status};

const SIDES: usize = 60;

/// The point of a 60-sided polygon around the unit circle nearest (2, 1): sixty
/// inequalities, of which two at most are active and most far from their bounds, what
/// screening leaves out of the QP.
fn polygon() -> Hs<2> {
    fn f(x: &[Jet<2>; 2]) -> Jet<2> {
        let dx = x[0] - 2.0;
        let dy = x[1] - 1.0;
        dx * dx + dy * dy
    }
    fn c(x: &[Jet<2>; 2], out: &mut [Jet<2>]) {
        for (k, o) in out.iter_mut().enumerate() {
            let angle = 2.0 * std::f64::consts::PI * (k as f64 + 0.5) / SIDES as f64;
            *o = Jet::from(1.0) - x[0] * angle.cos() - x[1] * angle.sin();
        }
    }
    Hs {
        name: "polygon",
        lower: [-3.0, -3.0],
        upper: [3.0, 3.0],
        start: [-0.5, -0.2],
        equalities: 0,
        constraints: SIDES,
        f,
        c,
        x_opt: [0.0, 0.0],
        f_opt: 0.0,
    }
}

#[test]
fn screening_steps_as_the_whole_qp_does() {
    let p = polygon();
    let plain = sqp::solve(&p, &p.start, &SqpSettings::default());
    let screened = sqp::solve(
        &p,
        &p.start,
        &SqpSettings {
            screening: true,
            ..SqpSettings::default()
        },
    );
    for s in [&plain, &screened] {
        assert_eq!(s.status, Status::Converged, "{s:?}");
        assert!(s.max_violation <= 1e-10, "{s:?}");
        // on the side whose normal is nearest (2, 1)'s direction: one row active, at 1
        // from the centre along its normal
        let active = s.constraints.iter().filter(|c| c.abs() <= 1e-10).count();
        let r = (s.x[0] * s.x[0] + s.x[1] * s.x[1]).sqrt();
        let corner = 1.0 / (std::f64::consts::PI / SIDES as f64).cos();
        assert!(active == 1 && r > 0.99 && r < corner, "{s:?}");
    }
    // the first QP, from a start inside, holds no row and its step breaks a dozen: they are
    // let in, and the steps are the whole QP's
    assert_eq!(plain.iterations, screened.iterations);
    for (a, b) in plain.x.iter().zip(&screened.x) {
        assert!(
            (a - b).abs() <= 1e-12,
            "{:?} against {:?}",
            plain.x,
            screened.x
        );
    }
    assert!((plain.objective - screened.objective).abs() <= 1e-12);
}

fn solution(x: &[f64]) -> Solution {
    Solution {
        status: Status::Converged,
        x: x.to_vec(),
        objective: x.iter().sum(),
        constraints: vec![],
        max_violation: 0.0,
        kkt_residual: Some(0.0),
        iterations: 7,
        evaluations: 11,
    }
}

#[test]
fn ends_that_round_alike_share_one_hand_over() {
    let hand_overs = HandOvers::new();
    let calls = AtomicUsize::new(0);
    let (lower, upper) = ([0.0, 0.0, f64::NEG_INFINITY], [1.0, 2.0, f64::INFINITY]);
    let solve = |y: &[f64]| {
        calls.fetch_add(1, Ordering::Relaxed);
        solution(y)
    };
    // two ends of one optimum, 1e-9 apart, and an end elsewhere
    let a = [0.3, 1.7, 12.5];
    let b = [0.3 + 1e-9, 1.7 - 1e-9, 12.5 + 1e-9];
    let c = [0.3 + 1e-3, 1.7, 12.5];
    let sa = hand_overs.solve(&a, &lower, &upper, solve);
    let sb = hand_overs.solve(&b, &lower, &upper, solve);
    assert_eq!(
        calls.load(Ordering::Relaxed),
        1,
        "the second end was solved again"
    );
    assert_eq!(sa.x, sb.x);
    assert_eq!((sb.iterations, sb.evaluations), (7, 11));
    // solved from a grid point near the end: spacing GRID of the range (bounded), of the
    // power of two below the size (unbounded)
    for (j, spacing) in [GRID, 2.0 * GRID, 8.0 * GRID].into_iter().enumerate() {
        assert!((sa.x[j] - a[j]).abs() <= 0.5 * spacing, "{:?}", sa.x);
        assert_eq!((sa.x[j] / spacing).fract(), 0.0, "{:?}", sa.x);
    }
    let sc = hand_overs.solve(&c, &lower, &upper, solve);
    assert_eq!(calls.load(Ordering::Relaxed), 2);
    assert!((sc.x[0] - c[0]).abs() <= 0.5 * GRID);
    // the grid keeps to the bounds
    let edge = hand_overs.solve(&[1.0, 0.0, -3.0], &lower, &upper, solve);
    assert_eq!(&edge.x[..2], &[1.0, 0.0]);
}
