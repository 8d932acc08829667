//! The local solvers on Hock-Schittkowski problems from their standard start points.

use crate::common;

use common::hs::*;
use flexopt::optim::nelder_mead::{self, NelderMeadSettings};
use flexopt::optim::sqp::{self, SqpSettings};
use flexopt::optim::{Problem, Solution, Status};

fn check<const N: usize>(p: &Hs<N>, s: &Solution, solver: &str) {
    assert_eq!(
        s.status,
        Status::Converged,
        "{solver} on {}: {:?}",
        p.name,
        s
    );
    let err = (s.objective - p.f_opt).abs() / p.f_opt.abs().max(1.0);
    assert!(
        err <= 1e-6,
        "{solver} on {}: f = {} vs {} ({err:e})",
        p.name,
        s.objective,
        p.f_opt
    );
    assert!(
        s.max_violation <= 1e-8,
        "{solver} on {}: violation {:e}",
        p.name,
        s.max_violation
    );
    let (lo, hi) = p.bounds();
    for j in 0..N {
        assert!(
            s.x[j] >= lo[j] && s.x[j] <= hi[j],
            "{solver} on {}: x{j} = {} out of bounds",
            p.name,
            s.x[j]
        );
        assert!(
            (s.x[j] - p.x_opt[j]).abs() <= 1e-4 * (1.0 + p.x_opt[j].abs()),
            "{solver} on {}: x = {:?}",
            p.name,
            s.x
        );
    }
    eprintln!(
        "{solver} {}: f = {:.12} ({err:.1e}), {} iterations, {} evaluations, KKT {:?}",
        p.name, s.objective, s.iterations, s.evaluations, s.kkt_residual
    );
}

/// SQP with its default Hessian refresh, with BFGS alone, and with constraint screening.
fn sqp_on<const N: usize>(p: Hs<N>) {
    let s = sqp::solve(&p, &p.start, &SqpSettings::default());
    check(&p, &s, "SQP");
    let bfgs = SqpSettings {
        hessian_refresh: 0,
        ..SqpSettings::default()
    };
    let s = sqp::solve(&p, &p.start, &bfgs);
    check(&p, &s, "SQP (BFGS only)");
    let screened = SqpSettings {
        screening: true,
        ..SqpSettings::default()
    };
    let s = sqp::solve(&p, &p.start, &screened);
    check(&p, &s, "SQP (screening)");
}

#[test]
fn sqp_hs6() {
    sqp_on(hs6());
}
#[test]
fn sqp_hs7() {
    sqp_on(hs7());
}
#[test]
fn sqp_hs10() {
    sqp_on(hs10());
}
#[test]
fn sqp_hs14() {
    sqp_on(hs14());
}
#[test]
fn sqp_hs15() {
    sqp_on(hs15());
}
#[test]
fn sqp_hs21_from_a_start_outside_the_bounds() {
    sqp_on(hs21());
}
#[test]
fn sqp_hs35() {
    sqp_on(hs35());
}
#[test]
fn sqp_hs71() {
    sqp_on(hs71());
}

fn nm_on<const N: usize>(p: Hs<N>) {
    let s = nelder_mead::solve(&p, &p.start, &NelderMeadSettings::default());
    check(&p, &s, "Nelder-Mead");
}

#[test]
fn nelder_mead_hs10() {
    nm_on(hs10());
}
#[test]
fn nelder_mead_hs15() {
    nm_on(hs15());
}
#[test]
fn nelder_mead_hs21_from_a_start_outside_the_bounds() {
    nm_on(hs21());
}
#[test]
fn nelder_mead_hs35() {
    nm_on(hs35());
}
