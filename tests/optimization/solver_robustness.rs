//! The solvers at the edges: non-finite values, starts on and outside the bounds,
//! inconsistent linearisations, redundant and degenerate constraints, iteration limits, no
//! feasible point. Nothing panics, and no NaN or infeasible point is reported as converged.

use crate::common;

use common::hs::{hs10, hs14, hs15, hs21, hs35, hs6, hs7, hs71, Hs};
use flexopt::model::scalar::Jet;
use flexopt::optim::nelder_mead::{self, NelderMeadSettings};
use flexopt::optim::sqp::{self, SqpSettings};
use flexopt::optim::{Problem, Solution, Status};

/// What every solution must honour, whatever its status.
fn sound(p: &dyn Problem, s: &Solution) {
    let (lo, hi) = p.bounds();
    assert!(
        s.x.iter().all(|v| v.is_finite()),
        "non-finite design {:?}",
        s.x
    );
    for j in 0..s.x.len() {
        assert!(
            s.x[j] >= lo[j] && s.x[j] <= hi[j],
            "x{j} = {} outside [{}, {}]",
            s.x[j],
            lo[j],
            hi[j]
        );
    }
    if s.status == Status::Converged {
        assert!(
            s.objective.is_finite(),
            "converged with objective {}",
            s.objective
        );
        assert!(
            s.max_violation <= 1e-8,
            "converged with violation {:e}",
            s.max_violation
        );
    }
}

fn both(p: &dyn Problem, x0: &[f64]) -> [Solution; 2] {
    let a = sqp::solve(p, x0, &SqpSettings::default());
    let b = nelder_mead::solve(p, x0, &NelderMeadSettings::default());
    sound(p, &a);
    sound(p, &b);
    [a, b]
}

/// minimize -x on [0, 1], where the model has no value beyond x = 0.7
fn nan_beyond() -> Hs<1> {
    Hs {
        name: "nan beyond 0.7",
        lower: [0.0],
        upper: [1.0],
        start: [0.2],
        equalities: 0,
        constraints: 0,
        f: |x| {
            if x[0].re > 0.7 {
                Jet::from(f64::NAN)
            } else {
                -x[0]
            }
        },
        c: |_, _| {},
        x_opt: [0.7],
        f_opt: -0.7,
    }
}

#[test]
fn a_nan_region_is_never_entered() {
    let p = nan_beyond();
    for s in both(&p, &p.start) {
        assert!(s.objective.is_finite() && s.x[0] <= 0.7, "{s:?}");
        // 0.7 is no KKT point: the SQP must not claim convergence there
    }
    let s = sqp::solve(&p, &p.start, &SqpSettings::default());
    assert_ne!(s.status, Status::Converged, "{s:?}");
}

#[test]
fn a_nan_start_is_a_clear_failure() {
    let p = nan_beyond();
    for s in both(&p, &[0.9]) {
        assert!(
            matches!(&s.status, Status::Failed(r) if r.contains("start point")),
            "{s:?}"
        );
    }
}

#[test]
fn starts_on_and_outside_the_bounds() {
    let p = hs35();
    for x0 in [[0.0, 0.0, 0.0], [-1.0, 5.0, -2.0], [1e6, 0.0, 1e6]] {
        for s in both(&p, &x0) {
            assert_eq!(s.status, Status::Converged, "from {x0:?}: {s:?}");
            assert!(
                (s.objective - 1.0 / 9.0).abs() < 1e-6,
                "from {x0:?}: {}",
                s.objective
            );
        }
    }
    let p = hs21();
    let s = sqp::solve(&p, &[50.0, 50.0], &SqpSettings::default());
    assert_eq!(s.status, Status::Converged);
    assert!((s.objective + 99.96).abs() < 1e-8);
}

/// x <= 1 and x^2 >= 4: from x = 0.5 the linearisations d <= 0.5 and d >= 3.75 have no
/// common point; the feasible set is x <= -2, where x^2 is least at -2.
fn inconsistent() -> Hs<1> {
    Hs {
        name: "inconsistent linearisation",
        lower: [-10.0],
        upper: [10.0],
        start: [0.5],
        equalities: 0,
        constraints: 2,
        f: |x| x[0] * x[0],
        c: |x, c| {
            c[0] = -x[0] + 1.0;
            c[1] = x[0] * x[0] - 4.0;
        },
        x_opt: [-2.0],
        f_opt: 4.0,
    }
}

#[test]
fn inconsistent_linearisations_end_feasible_or_say_infeasible() {
    let p = inconsistent();
    for x0 in [[0.5], [0.9], [-0.5], [5.0]] {
        let s = sqp::solve(&p, &x0, &SqpSettings::default());
        sound(&p, &s);
        match s.status {
            Status::Converged => assert!((s.x[0] + 2.0).abs() < 1e-8, "from {x0:?}: {s:?}"),
            Status::Infeasible => assert!(s.max_violation > 1e-8, "from {x0:?}: {s:?}"),
            _ => panic!("from {x0:?}: {s:?}"),
        }
    }
    // from the left the feasible set is in reach
    let s = sqp::solve(&p, &[-0.5], &SqpSettings::default());
    assert_eq!(s.status, Status::Converged, "{s:?}");
}

/// HS35 with its constraint twice and a third copy scaled by 2 (dependent normals), and a
/// constraint through the optimum with a zero multiplier (degenerate).
fn hs35_redundant() -> Hs<3> {
    let mut p = hs35();
    p.name = "HS35 with redundant and degenerate constraints";
    p.constraints = 4;
    p.c = |x, c| {
        let g = -x[0] - x[1] - x[2] * 2.0 + 3.0;
        c[0] = g;
        c[1] = g;
        c[2] = g * 2.0;
        // x1 <= 4/3 + (x2 - 7/9): active at the optimum, not binding
        c[3] = -x[0] + x[1] + (4.0 / 3.0 - 7.0 / 9.0);
    };
    p
}

#[test]
fn redundant_and_degenerate_constraints() {
    let p = hs35_redundant();
    for s in both(&p, &p.start) {
        assert_eq!(s.status, Status::Converged, "{s:?}");
        assert!((s.objective - 1.0 / 9.0).abs() < 1e-6, "{}", s.objective);
    }
}

#[test]
fn iteration_limits_report_a_sound_point() {
    let p = hs35();
    let s = sqp::solve(
        &p,
        &p.start,
        &SqpSettings {
            tolerance: 1e-10,
            max_iterations: 2,
            ..SqpSettings::default()
        },
    );
    sound(&p, &s);
    assert_eq!(s.status, Status::IterationLimit);
    let s = nelder_mead::solve(
        &p,
        &p.start,
        &NelderMeadSettings {
            max_iterations: 1,
            ..NelderMeadSettings::default()
        },
    );
    sound(&p, &s);
    assert_ne!(s.status, Status::Converged);
}

/// x >= 2 and x <= 1: no feasible point.
fn no_feasible_point() -> Hs<1> {
    Hs {
        name: "no feasible point",
        lower: [-5.0],
        upper: [5.0],
        start: [0.0],
        equalities: 0,
        constraints: 2,
        f: |x| x[0] * x[0],
        c: |x, c| {
            c[0] = x[0] - 2.0;
            c[1] = -x[0] + 1.0;
        },
        x_opt: [1.5],
        f_opt: 2.25,
    }
}

#[test]
fn no_feasible_point_is_reported_as_such() {
    let p = no_feasible_point();
    for s in both(&p, &p.start) {
        assert_eq!(s.status, Status::Infeasible, "{s:?}");
        // the least violating point lies between the two
        assert!(
            s.max_violation >= 0.5 - 1e-6 && s.x[0] > 0.9 && s.x[0] < 2.1,
            "{s:?}"
        );
    }
}

/// `problem` with its objective multiplied by `factor`: a stress in pascals beside the
/// same stress in units of its own size.
struct Rescaled<'p> {
    problem: &'p dyn Problem,
    factor: f64,
}

impl Problem for Rescaled<'_> {
    fn dimension(&self) -> usize {
        self.problem.dimension()
    }
    fn bounds(&self) -> (&[f64], &[f64]) {
        self.problem.bounds()
    }
    fn equality_count(&self) -> usize {
        self.problem.equality_count()
    }
    fn constraint_count(&self) -> usize {
        self.problem.constraint_count()
    }
    fn evaluate(&self, x: &[f64], c: &mut [f64]) -> f64 {
        self.factor * self.problem.evaluate(x, c)
    }
    fn evaluate_with_gradient(
        &self,
        x: &[f64],
        c: &mut [f64],
        g: &mut [f64],
        jac: &mut [f64],
    ) -> f64 {
        let f = self.problem.evaluate_with_gradient(x, c, g, jac);
        g.iter_mut().for_each(|v| *v *= self.factor);
        self.factor * f
    }
}

/// The SQP on `p` with its objective multiplied by each factor: the same optimum.
fn same_optimum_whatever_the_objectives_unit<const N: usize>(p: Hs<N>) {
    for factor in [1e-3, 1.0, 3e7, 1e12] {
        let scaled = Rescaled {
            problem: &p,
            factor,
        };
        let s = sqp::solve(&scaled, &p.start, &SqpSettings::default());
        sound(&scaled, &s);
        assert_eq!(s.status, Status::Converged, "{} x {factor}: {s:?}", p.name);
        let err = (s.objective / factor - p.f_opt).abs() / p.f_opt.abs().max(1.0);
        assert!(
            err <= 1e-8,
            "{} x {factor}: f = {} ({err:e})",
            p.name,
            s.objective
        );
        for (x, x_opt) in s.x.iter().zip(&p.x_opt) {
            assert!(
                (x - x_opt).abs() <= 1e-4 * (1.0 + x_opt.abs()),
                "{} x {factor}: {:?}",
                p.name,
                s.x
            );
        }
    }
}

#[test]
fn an_objective_of_any_size_reaches_the_same_optimum() {
    // the SQP's first model is the identity and its elastic QP prices the violation at a
    // multiple of the gradient: neither may make the result depend on the objective's unit
    same_optimum_whatever_the_objectives_unit(hs71());
    same_optimum_whatever_the_objectives_unit(hs35());
    same_optimum_whatever_the_objectives_unit(hs21());
    same_optimum_whatever_the_objectives_unit(hs10());
    same_optimum_whatever_the_objectives_unit(hs14());
    same_optimum_whatever_the_objectives_unit(hs15());
    same_optimum_whatever_the_objectives_unit(hs6());
    same_optimum_whatever_the_objectives_unit(hs7());
}
