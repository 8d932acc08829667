//! A limit point located on a path under displacement control (Batoz and Dhatt,
//! "Incremental displacement algorithms for nonlinear problems", International Journal for
//! Numerical Methods in Engineering 14 (1979) 1262-1267): one free displacement `u_j` is
//! prescribed and the load factor solved for beside the others, Newton on the bordered
//! system `[K, -q; e_j^T, 0] [du; dlambda] = -[r; u_j - c]`. The load factor has its
//! maximum on such a path where the tangent is singular, and the path passes it smoothly, so
//! the lowest eigenvalue of the scaled tangent changes sign there as a smooth function of
//! `c`: the Illinois bracket closes on `c` as it does on the load factor at a bifurcation.
//! The controlled displacement is the one the path's rate `K^{-1} q` moves most, near the
//! limit the null vector's largest component.

use faer::prelude::Solve;
use faer::Mat;

use super::eigen::{illinois_keeps, lowest};
use crate::model::large::assemble::System;
use crate::model::large::solve::{solve_each, Options, State};
use crate::model::large::LargeError;

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The bordered matrix `[K, -q; e_j^T, 0]` at `state`, and the residual and load there.
fn bordered(system: &System, state: &State, j: usize) -> (Mat<f64>, Vec<f64>, Vec<f64>) {
    let a = system.at(state);
    let n = a.load.len();
    let m = Mat::from_fn(n + 1, n + 1, |r, c| match (r < n, c < n) {
        (true, true) => a.tangent[(r, c)],
        (true, false) => -a.load[r],
        (false, true) => f64::from(u8::from(c == j)),
        (false, false) => 0.0,
    });
    (m, a.residual, a.load)
}

/// The equilibrium with `u_j = c`, from `start` by the path's tangent and Newton on the
/// bordered system; `None` if Newton does not converge.
fn controlled(system: &System, start: &State, j: usize, c: f64, opts: &Options) -> Option<State> {
    let (m, _, _) = bordered(system, start, j);
    let n = start.free.len();
    let mut rhs = Mat::zeros(n + 1, 1);
    rhs[(n, 0)] = 1.0;
    let rate = m.partial_piv_lu().solve(&rhs);
    let dc = c - start.free[j];
    let mut state = State {
        free: (0..n).map(|i| start.free[i] + dc * rate[(i, 0)]).collect(),
        lambda: start.lambda + dc * rate[(n, 0)],
    };
    for _ in 0..opts.iterations {
        let (m, r, q) = bordered(system, &state, j);
        let mut rhs = Mat::zeros(n + 1, 1);
        for (i, v) in r.iter().enumerate() {
            rhs[(i, 0)] = -v;
        }
        rhs[(n, 0)] = c - state.free[j];
        let step = m.partial_piv_lu().solve(&rhs);
        if (0..=n).any(|i| !step[(i, 0)].is_finite()) {
            return None;
        }
        for (i, u) in state.free.iter_mut().enumerate() {
            *u += step[(i, 0)];
        }
        state.lambda += step[(n, 0)];
        let correction = norm(&(0..n).map(|i| step[(i, 0)]).collect::<Vec<_>>());
        if norm(&r) <= opts.tolerance * norm(&q) || correction <= opts.tolerance * norm(&state.free)
        {
            state.free[j] = c;
            return Some(state);
        }
    }
    None
}

/// The limit point past the stable state `below` (its lowest scaled eigenvalue positive),
/// where the load factor `beyond` has no equilibrium: the path followed from `below` by
/// displacement control in steps that grow while the eigenvalue stays positive, then the
/// bracket closed on the controlled displacement to a relative width of `1e-12` (at most
/// 200 trial points). The result is the bracket's stable end.
pub(super) fn locate(
    system: &System,
    scale: &[f64],
    below: (State, f64),
    beyond: f64,
    opts: &Options,
) -> Result<State, LargeError> {
    let singular = LargeError::Singular {
        lambda: below.0.lambda,
    };
    let a = system.at(&below.0);
    let rate = solve_each(&a.tangent, &[&a.load])
        .ok_or(singular.clone())?
        .remove(0);
    let j = (0..rate.len())
        .max_by(|&x, &y| rate[x].abs().total_cmp(&rate[y].abs()))
        .ok_or(singular)?;
    let (mut sa, mut fa) = below;
    let mut dc = 0.5 * rate[j] * (beyond - sa.lambda);
    let not_found = |sa: &State| LargeError::NotConverged {
        lambda: sa.lambda,
        residual: norm(&system.at(sa).residual),
        cuts: opts.cuts,
    };
    let (mut cb, mut fb) = (0.0, 0.0);
    let mut bracketed = false;
    let mut cuts = 0;
    for _ in 0..4 * opts.max_steps.min(100) {
        let c = sa.free[j] + dc;
        match controlled(system, &sa, j, c, opts) {
            Some(s) => {
                let f = lowest(system, &s, scale)?;
                if f > 0.0 {
                    (sa, fa) = (s, f);
                    dc *= 1.5;
                } else {
                    (cb, fb, bracketed) = (c, f, true);
                    break;
                }
            }
            None if cuts < opts.cuts => {
                cuts += 1;
                dc *= 0.5;
            }
            None => return Err(not_found(&sa)),
        }
    }
    if !bracketed {
        return Err(not_found(&sa));
    }
    let mut side: i8 = 0;
    for _ in 0..200 {
        let ca = sa.free[j];
        if (cb - ca).abs() <= 1e-12 * cb.abs().max(ca.abs()) {
            break;
        }
        let cc = (ca * fb - cb * fa) / (fb - fa);
        let sc = controlled(system, &sa, j, cc, opts).ok_or_else(|| not_found(&sa))?;
        let fc = lowest(system, &sc, scale)?;
        if illinois_keeps(fc, &mut fa, &mut fb, &mut side) {
            sa = sc;
        } else {
            cb = cc;
        }
    }
    Ok(sa)
}
