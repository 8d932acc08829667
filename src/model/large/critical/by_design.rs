//! The critical load factor's derivatives by the design, at the critical point found in
//! real numbers ([`super::critical_load_factor`]), over the dual scalar `D` that the
//! structure rebuilt over the design carries (as [`crate::model::large::sensitivity`] does
//! for an equilibrium). `K` is the tangent on the free degrees of freedom, `q = -dr/dlambda`
//! the load per unit load factor, `phi` the null vector of `K` at the point (of the tangent
//! itself: the scaling under which it is found is a congruence, which moves neither the
//! point nor the null space, [`super::eigen::lowest_pair`]).
//!
//! - A limit point (`phi^T q != 0`): the critical points `r(u, lambda_c, p) = 0` with `K`
//!   singular form a curve in the design; differentiating the equilibrium along it and
//!   multiplying by `phi^T` (`phi^T K = 0`) leaves `-phi^T q dlambda_c + phi^T dr/dp = 0`,
//!   so `dlambda_c/dp = phi^T (dr/dp|_u) / (phi^T q)`, no solve needed (Haftka and Gurdal,
//!   *Elements of Structural Optimization*, 3rd ed., Kluwer 1992, section 7.4, the
//!   sensitivity of a limit load; Wriggers, *Nonlinear Finite Element Methods*, Springer
//!   2008, section 7.2, the limit points' extended system).
//! - A bifurcation (`phi^T q = 0`, a perfect path: Euler's column): the lowest eigenvalue
//!   `mu(p, lambda)` of the tangent on the fundamental path vanishes at `lambda_c`, so
//!   `dlambda_c/dp = -(dmu/dp) / (dmu/dlambda)`, each derivative of the simple eigenvalue
//!   `phi^T (dK) phi / phi^T phi` (Haftka and Gurdal 1992, section 7.3, the sensitivity of
//!   a buckling load, and its extension to a nonlinear prebuckling path; Wriggers 2008,
//!   section 7.2). `dK/dp` at fixed `lambda` moves with the path, `du/dp = -K^{-1} dr/dp`,
//!   and `dK/dlambda` along it with `du/dlambda = K^{-1} q`, both solved with the singular
//!   `K` bordered by its null vector, `[K, phi; phi^T, 0] [w; s] = [b; 0]`: the bordered
//!   matrix is regular when `phi` spans `K`'s null space (a simple eigenvalue), and its
//!   solution is the one orthogonal to `phi`, with `s = phi^T b / phi^T phi` (zero at a
//!   bifurcation, where the fundamental path's forces do no work on the buckling mode).
//!   The component of `w` along `phi` that the bordering leaves out adds `c phi^T
//!   (dK/du[phi]) phi` to `dmu`, the third derivative of the energy along the mode, which
//!   vanishes at a symmetric bifurcation (the mode's energy even in its amplitude): the
//!   formula holds there, as for Euler's column, and not at an asymmetric one.
//!
//! `dK/dlambda` is exact, not a difference: the structure's load data (held values,
//! applied loads, a spring's free stroke and preload) scaled by `1 + eps` in a dual
//! number, with the displacement `u + eps lambda du/dlambda`, carry `lambda dK/dlambda`
//! along the path in their derivative part.

use faer::Mat;
use num_dual::Dual64;

use super::eigen::{lowest_pair, scaling};
use super::Critical;
use crate::model::large::assemble::{System, SystemOf};
use crate::model::large::sensitivity::Factored;
use crate::model::large::{BeamOf, LargeError, LocalOf, SpringOf, Structure, StructureOf};
use crate::model::scalar::Scalar;

/// Where `|phi^T q|` is below this fraction of `|phi| |q|`, the critical point is a
/// bifurcation (its `phi^T q` round-off of a perfect path); above it, a limit point.
const BIFURCATION: f64 = 1e-6;

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `phi^T K phi` for a row-major `K` over any scalar.
fn quadratic<D: Scalar>(k: &[D], phi: &[f64]) -> D {
    let n = phi.len();
    let mut sum = D::from(0.0);
    for (i, &pi) in phi.iter().enumerate() {
        for (j, &pj) in phi.iter().enumerate() {
            sum = sum + k[i * n + j] * (pi * pj);
        }
    }
    sum
}

/// The critical load factor `critical` of the real structure `real`, as a dual number
/// carrying its derivatives by the design that `dual` (the same structure built over `D`)
/// carries.
pub fn critical_by_design<D: Scalar>(
    real: &Structure,
    dual: &StructureOf<D>,
    critical: &Critical,
) -> Result<D, LargeError> {
    let system = System::new(real)?;
    let dual_system = SystemOf::new(dual)?;
    let lambda = critical.lambda;
    let end = critical.path.end();
    let free: Vec<f64> = system.free.iter().map(|&i| end.displacement[i]).collect();
    let a = system.assemble(&end.displacement, lambda);
    let (_, mut phi) = lowest_pair(&a.tangent, &scaling(&system)?)?;
    let size = dot(&phi, &phi).sqrt();
    phi.iter_mut().for_each(|v| *v /= size);
    let at: Vec<D> = free.iter().map(|&v| D::from(v)).collect();
    // dr/dp at the critical point, the derivative parts alone
    let by_design: Vec<D> = dual_system
        .residual(&at, lambda)
        .into_iter()
        .map(|r| r - r.re())
        .collect();
    let pq = dot(&phi, &a.load);
    let q_norm = dot(&a.load, &a.load).sqrt();
    if pq.abs() > BIFURCATION * q_norm {
        let work = phi
            .iter()
            .zip(&by_design)
            .fold(D::from(0.0), |s, (&p, &r)| s + r * p);
        return Ok(work / pq + lambda);
    }
    let n = phi.len();
    let bordered = Factored::new(&Mat::from_fn(n + 1, n + 1, |i, j| match (i < n, j < n) {
        (true, true) => a.tangent[(i, j)],
        (true, false) => phi[i],
        (false, true) => phi[j],
        (false, false) => 0.0,
    }));
    if !bordered.is_regular() {
        return Err(LargeError::Singular { lambda });
    }
    let solve = |b: Vec<D>| {
        let mut b = b;
        b.push(D::from(0.0));
        let mut w = bordered.solve(&b);
        w.truncate(n);
        w
    };
    // the displacement's derivative by the design at fixed lambda, off the mode
    let du = solve(by_design.iter().map(|&r| -r).collect());
    let moved: Vec<D> = at.iter().zip(&du).map(|(&u, &d)| u + d).collect();
    let k = dual_system.tangent_at(&dual_system.expand(&moved, lambda), lambda);
    let mu_p = quadratic(&k, &phi);
    let mut load = a.load.clone();
    load.push(0.0);
    let rate = bordered.solve(&load);
    let mu_lambda = along_path(real, &system, &free, lambda, &rate[..n], &phi)?;
    Ok((mu_p - mu_p.re()) * (-1.0 / mu_lambda) + lambda)
}

/// `phi^T (dK/dlambda) phi` along the path at `free` (load factor `lambda`), the path's
/// rate `rate = du/dlambda` given (its real parts), exactly: the load data scaled by `1 +
/// eps` carry `lambda d/dlambda` in a dual number's derivative part.
fn along_path(
    real: &Structure,
    system: &System,
    free: &[f64],
    lambda: f64,
    rate: &[f64],
    phi: &[f64],
) -> Result<f64, LargeError> {
    let scaled = by_load(real);
    let scaled_system = SystemOf::new(&scaled)?;
    debug_assert_eq!(scaled_system.free, system.free);
    let moved: Vec<Dual64> = free
        .iter()
        .zip(rate)
        .map(|(&u, r)| Dual64::new(u, lambda * r))
        .collect();
    let k = scaled_system.tangent_at(&scaled_system.expand(&moved, lambda), lambda);
    let mu_lambda = quadratic(&k, phi).eps / lambda;
    if mu_lambda == 0.0 || !mu_lambda.is_finite() {
        return Err(LargeError::Singular { lambda });
    }
    Ok(mu_lambda)
}

/// `real` over dual numbers whose derivative part is its load data (held values, loads,
/// springs' free strokes and preloads), the rest constant: `d/deps` of the structure with
/// its load scaled by `1 + eps`.
fn by_load(real: &Structure) -> StructureOf<Dual64> {
    let constant = |v: f64| Dual64::new(v, 0.0);
    let load = |v: f64| Dual64::new(v, v);
    StructureOf {
        nodes: real.nodes.iter().map(|p| p.map(constant)).collect(),
        beams: real
            .beams
            .iter()
            .map(|b| BeamOf {
                a: b.a,
                b: b.b,
                section: b.section,
                local: b.local.map(|l| LocalOf {
                    axial: constant(l.axial),
                    bending: l.bending.map(|row| row.map(constant)),
                }),
            })
            .collect(),
        springs: real
            .springs
            .iter()
            .map(|s| SpringOf {
                a: s.a,
                b: s.b,
                stiffness: constant(s.stiffness),
                free_stroke: load(s.free_stroke),
                preload: load(s.preload),
            })
            .collect(),
        slaves: real.slaves.clone(),
        held: real.held.iter().map(|&(n, d, v)| (n, d, load(v))).collect(),
        loads: real.loads.iter().map(|&(n, f)| (n, f.map(load))).collect(),
    }
}
