//! The critical load factor: the least load factor at which the tangent stiffness on the
//! free degrees of freedom stops being positive definite, its lowest eigenvalue (faer's
//! self-adjoint decomposition) passing through zero. The path is followed by load
//! continuation; the first step whose lowest eigenvalue is not positive brackets the
//! point, which the Illinois variant of regula falsi (Dowell and Jarratt, BIT 11 (1971)
//! 168-174) then closes, re-solving the equilibrium at each trial load factor from the
//! bracket's stable end. A bifurcation from a perfect path (Euler's column) is found this
//! way; a limit point, past which there is no equilibrium to re-solve, ends in
//! [`LargeError::NotConverged`] at the limit.

use faer::{Mat, Side};

use super::assemble::System;
use super::solve::{Options, Path, State};
use super::{LargeError, Structure};

/// The critical load factor and the path up to it.
#[derive(Debug, Clone, PartialEq)]
pub struct Critical {
    pub lambda: f64,
    /// The converged points of the continuation before the bracket, and the critical one.
    pub path: Path,
    /// The lowest eigenvalue of the unloaded structure's tangent, scaled to a unit diagonal.
    pub lowest_unloaded: f64,
}

/// The lowest eigenvalue of the tangent stiffness on the free degrees of freedom, scaled
/// symmetrically by `scale` (a congruence: the signs of the eigenvalues are kept, by
/// Sylvester's law of inertia, while a strip's axial and bending stiffnesses, 1e9 apart,
/// are brought together so that an eigenvalue near zero is not lost in the round-off of
/// the largest).
fn lowest(system: &System, state: &State, scale: &[f64]) -> Result<f64, LargeError> {
    let a = system.at(state);
    if a.tangent.nrows() == 0 {
        return Err(LargeError::Invalid("no free degree of freedom".into()));
    }
    let n = scale.len();
    let scaled = Mat::from_fn(n, n, |i, j| scale[i] * a.tangent[(i, j)] * scale[j]);
    let values = scaled
        .self_adjoint_eigenvalues(Side::Lower)
        .map_err(|_| LargeError::Eigen)?;
    values
        .first()
        .copied()
        .filter(|v| v.is_finite())
        .ok_or(LargeError::Eigen)
}

/// The least load factor in `(0, lambda_max]` at which the tangent stiffness loses
/// positive definiteness, from `opts.steps` load steps and a bracket closed to a relative
/// width of `1e-12` (at most 200 trial load factors).
pub fn critical_load_factor(
    structure: &Structure,
    lambda_max: f64,
    opts: &Options,
) -> Result<Critical, LargeError> {
    let system = System::new(structure)?;
    let mut state = system.unloaded();
    let unloaded = system.at(&state).tangent;
    let scale: Vec<f64> = (0..unloaded.nrows())
        .map(|i| 1.0 / unloaded[(i, i)].abs().sqrt())
        .collect();
    if scale.iter().any(|s| !s.is_finite()) {
        return Err(LargeError::Singular { lambda: 0.0 });
    }
    let lowest_unloaded = lowest(&system, &state, &scale)?;
    if lowest_unloaded <= 0.0 {
        return Err(LargeError::Singular { lambda: 0.0 });
    }
    let mut points = vec![system.point(&state)];
    let steps = opts.steps.max(1);
    let mut below = (state.clone(), lowest_unloaded);
    for i in 1..=steps {
        let lambda = lambda_max * i as f64 / steps as f64;
        state = system.advance(&below.0, lambda, opts)?;
        let mu = lowest(&system, &state, &scale)?;
        if mu > 0.0 {
            points.push(system.point(&state));
            below = (state.clone(), mu);
            continue;
        }
        let critical = illinois(&system, &scale, below, (lambda, mu), opts)?;
        points.push(system.point(&critical));
        return Ok(Critical {
            lambda: critical.lambda,
            path: Path { points },
            lowest_unloaded,
        });
    }
    Err(LargeError::NoCriticalPoint { lambda_max })
}

/// Closes the bracket `[a, b]` (lowest eigenvalue positive at `a`, not at `b`).
fn illinois(
    system: &System,
    scale: &[f64],
    a: (State, f64),
    b: (f64, f64),
    opts: &Options,
) -> Result<State, LargeError> {
    let (mut sa, mut fa) = a;
    let (mut lb, mut fb) = b;
    let mut side = 0;
    for _ in 0..200 {
        if (lb - sa.lambda).abs() <= 1e-12 * lb.abs() {
            break;
        }
        let lc = (sa.lambda * fb - lb * fa) / (fb - fa);
        let sc = system.advance(&sa, lc, opts)?;
        let fc = lowest(system, &sc, scale)?;
        if fc > 0.0 {
            (sa, fa) = (sc, fc);
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            (lb, fb) = (lc, fc);
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
    }
    Ok(sa)
}
