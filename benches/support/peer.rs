//! The `slsqp` crate (Kraft's SLSQP) as a peer solver for the benchmarks, driven on the same
//! scaled design problem with the same exact gradients. Its objective and constraint
//! callbacks are separate; they share one cached evaluation per point, so that the peer
//! pays one model evaluation per point, as flexopt does.

use std::cell::RefCell;

use flexopt::optim::Problem as _;
use flexopt::problem::nlp::DesignNlp;

/// The last evaluation of the problem, so that the peer's separate objective and
/// constraint callbacks cost one model evaluation per point, as flexopt's do.
#[derive(Default)]
struct Cache {
    x: Vec<f64>,
    f: f64,
    c: Vec<f64>,
    g: Vec<f64>,
    jac: Vec<f64>,
    evaluations: usize,
}

fn cached<'a>(
    nlp: &'a DesignNlp,
    cache: &'a RefCell<Cache>,
    x: &[f64],
) -> std::cell::RefMut<'a, Cache> {
    let mut c = cache.borrow_mut();
    if c.x != x {
        let (n, m) = (nlp.dimension(), nlp.constraint_count());
        c.c.resize(m, 0.0);
        c.g.resize(n, 0.0);
        c.jac.resize(m * n, 0.0);
        let Cache { c: cv, g, jac, .. } = &mut *c;
        let f = nlp.evaluate_with_gradient(x, cv, g, jac);
        c.f = f;
        c.x = x.to_vec();
        c.evaluations += 1;
    }
    c
}

/// A callback of the peer: value, and gradient when asked.
type PeerCallback<'a> = dyn Fn(&[f64], Option<&mut [f64]>, &mut ()) -> f64 + 'a;

/// One SLSQP solve with relative function tolerance `ftol`; returns the objective, the
/// largest constraint violation and the number of model evaluations.
pub fn slsqp_solve(nlp: &DesignNlp, x0: &[f64], ftol: f64) -> (f64, f64, usize) {
    let n = nlp.dimension();
    let m = nlp.constraint_count();
    let cache = RefCell::new(Cache::default());
    let objective = |x: &[f64], grad: Option<&mut [f64]>, _: &mut ()| {
        let c = cached(nlp, &cache, x);
        if let Some(g) = grad {
            g.copy_from_slice(&c.g);
        }
        c.f
    };
    // flexopt's constraints are c >= 0; the peer's are c <= 0
    let constraints: Vec<Box<PeerCallback>> = (0..m)
        .map(|i| {
            let cache = &cache;
            Box::new(move |x: &[f64], grad: Option<&mut [f64]>, _: &mut ()| {
                let c = cached(nlp, cache, x);
                if let Some(g) = grad {
                    for (gj, jac) in g.iter_mut().zip(&c.jac[i * n..(i + 1) * n]) {
                        *gj = -jac;
                    }
                }
                -c.c[i]
            }) as Box<PeerCallback>
        })
        .collect();
    let refs: Vec<&PeerCallback> = constraints.iter().map(|c| c.as_ref()).collect();
    let tol = slsqp::StopTols {
        ftol_rel: ftol,
        ..slsqp::StopTols::default()
    };
    let (x, f) = match slsqp::minimize(
        objective,
        x0,
        &vec![(0.0, 1.0); n],
        &refs,
        (),
        2000,
        Some(tol),
    ) {
        Ok((_, x, f)) | Err((_, x, f)) => (x, f),
    };
    let mut c = vec![0.0; m];
    let f_check = nlp.evaluate(&x, &mut c);
    let violation = c.iter().fold(0.0f64, |v, ci| v.max(-ci));
    let evaluations = cache.borrow().evaluations;
    (
        if f.is_finite() { f_check } else { f64::NAN },
        violation,
        evaluations,
    )
}
