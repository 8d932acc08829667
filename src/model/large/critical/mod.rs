//! The critical load factor: the least load factor at which the tangent stiffness on the
//! free degrees of freedom stops being positive definite, its lowest eigenvalue (faer's
//! self-adjoint decomposition) passing through zero. The path is followed by load
//! continuation; the first step whose lowest eigenvalue is not positive brackets the
//! point, which the Illinois variant of regula falsi (Dowell and Jarratt, BIT 11 (1971)
//! 168-174) then closes, re-solving the equilibrium at each trial load factor from the
//! bracket's stable end. A bifurcation from a perfect path (Euler's column) is found this
//! way. A limit point, past which there is no equilibrium at a higher load factor, is found
//! where the continuation first fails to reach a load factor: the path is then followed by
//! displacement control, on which it passes the limit smoothly, and the same bracket is
//! closed on the controlled displacement ([`limit`]).
//!
//! [`by_design`] gives the critical load factor's derivatives by the design.

pub mod by_design;
mod eigen;
mod limit;

use super::assemble::System;
use super::solve::{Options, Path, State};
use super::{LargeError, Structure};
use eigen::{illinois_keeps, lowest, scaling};

/// The critical load factor and the path up to it.
#[derive(Debug, Clone, PartialEq)]
pub struct Critical {
    pub lambda: f64,
    /// The converged points of the continuation before the bracket, and the critical one.
    pub path: Path,
    /// The lowest eigenvalue of the unloaded structure's tangent, scaled to a unit diagonal.
    pub lowest_unloaded: f64,
}

/// The least load factor in `(0, lambda_max]` at which the tangent stiffness loses
/// positive definiteness, from `opts.steps` load steps and a bracket closed to a relative
/// width of `1e-12` (at most 200 trial points): a bifurcation on the load factor, a limit
/// point on the displacement that controls the path past it.
pub fn critical_load_factor(
    structure: &Structure,
    lambda_max: f64,
    opts: &Options,
) -> Result<Critical, LargeError> {
    let system = System::new(structure)?;
    let mut state = system.unloaded();
    let scale = scaling(&system)?;
    let lowest_unloaded = lowest(&system, &state, &scale)?;
    if lowest_unloaded <= 0.0 {
        return Err(LargeError::Singular { lambda: 0.0 });
    }
    let mut points = vec![system.point(&state)];
    let steps = opts.steps.max(1);
    let mut below = (state.clone(), lowest_unloaded);
    let found = |points: Vec<_>, critical: State| {
        let mut points = points;
        points.push(system.point(&critical));
        Ok(Critical {
            lambda: critical.lambda,
            path: Path { points },
            lowest_unloaded,
        })
    };
    for i in 1..=steps {
        let lambda = lambda_max * i as f64 / steps as f64;
        state = match system.advance(&below.0, lambda, opts) {
            Ok(state) => state,
            Err(LargeError::NotConverged { .. }) => {
                let critical = limit::locate(&system, &scale, below, lambda, opts)?;
                return found(points, critical);
            }
            Err(e) => return Err(e),
        };
        let mu = lowest(&system, &state, &scale)?;
        if mu > 0.0 {
            points.push(system.point(&state));
            below = (state.clone(), mu);
            continue;
        }
        let critical = illinois(&system, &scale, below, (lambda, mu), opts)?;
        return found(points, critical);
    }
    Err(LargeError::NoCriticalPoint { lambda_max })
}

/// Closes the bracket `[a, b]` (lowest eigenvalue positive at `a`, not at `b`); where a
/// trial load factor has no equilibrium the point is a limit, and [`limit::locate`] takes
/// over from the bracket's stable end.
fn illinois(
    system: &System,
    scale: &[f64],
    a: (State, f64),
    b: (f64, f64),
    opts: &Options,
) -> Result<State, LargeError> {
    let (mut sa, mut fa) = a;
    let (mut lb, mut fb) = b;
    let mut side: i8 = 0;
    for _ in 0..200 {
        if (lb - sa.lambda).abs() <= 1e-12 * lb.abs() {
            break;
        }
        let lc = (sa.lambda * fb - lb * fa) / (fb - fa);
        let sc = match system.advance(&sa, lc, opts) {
            Ok(sc) => sc,
            Err(LargeError::NotConverged { .. }) => {
                return limit::locate(system, scale, (sa, fa), lc, opts)
            }
            Err(e) => return Err(e),
        };
        let fc = lowest(system, &sc, scale)?;
        if illinois_keeps(fc, &mut fa, &mut fb, &mut side) {
            sa = sc;
        } else {
            lb = lc;
        }
    }
    Ok(sa)
}
