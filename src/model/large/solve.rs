//! Equilibrium paths: Newton's method with load continuation (a tangent predictor, then
//! full Newton at the step's load factor, the step halved where Newton fails), and
//! Crisfield's cylindrical arc length (M. A. Crisfield, "A fast incremental/iterative
//! solution procedure that handles snap-through", Computers & Structures 13 (1981) 55-62;
//! and his 1991 book, vol. 1, section 9.3: the constraint `|Delta u|^2 = Delta l^2` on
//! the free degrees of freedom, the root of its quadratic nearest the previous increment,
//! the predictor's sign from the previous increment's direction (Feng's criterion)) for
//! paths that turn back. Every iteration count is bounded, every failure a
//! [`LargeError`].

use faer::prelude::Solve;
use faer::Mat;

use super::assemble::{Assembled, System};
use super::{LargeError, PathPoint, Structure};

/// The bounds and tolerance of the equilibrium iterations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Load steps from 0 to the end load factor (continuation), or the first arc length as
    /// a fraction of the end load factor (arc length: `1 / steps`).
    pub steps: usize,
    /// Newton iterations per step before the step is cut.
    pub iterations: usize,
    /// Halvings of a step before the path gives up.
    pub cuts: usize,
    /// Converged when the residual is below `tolerance` times the load vector's norm, or
    /// the Newton correction below `tolerance` times the displacement's norm.
    pub tolerance: f64,
    /// Arc-length steps at most.
    pub max_steps: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            steps: 10,
            iterations: 30,
            cuts: 12,
            tolerance: 1e-11,
            max_steps: 2000,
        }
    }
}

/// A sequence of converged equilibria from the unloaded structure.
#[derive(Debug, Clone, PartialEq)]
pub struct Path {
    pub points: Vec<PathPoint>,
}

impl Path {
    /// The last point.
    pub fn end(&self) -> &PathPoint {
        self.points
            .last()
            .expect("a path starts at its unloaded point")
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `K^{-1} rhs` for each right-hand side, `None` where the result is not finite.
pub(crate) fn solve_each(k: &Mat<f64>, rhs: &[&[f64]]) -> Option<Vec<Vec<f64>>> {
    let n = k.nrows();
    if n == 0 {
        return Some(rhs.iter().map(|_| Vec::new()).collect());
    }
    let b = Mat::from_fn(n, rhs.len(), |i, j| rhs[j][i]);
    let x = k.partial_piv_lu().solve(&b);
    let out: Vec<Vec<f64>> = (0..rhs.len())
        .map(|j| (0..n).map(|i| x[(i, j)]).collect())
        .collect();
    out.iter().flatten().all(|v| v.is_finite()).then_some(out)
}

/// A state on the way: the free displacements and the load factor.
#[derive(Debug, Clone)]
pub(crate) struct State {
    pub free: Vec<f64>,
    pub lambda: f64,
}

impl System<'_> {
    /// The unloaded structure: every path and search starts there.
    pub(crate) fn unloaded(&self) -> State {
        State {
            free: vec![0.0; self.free.len()],
            lambda: 0.0,
        }
    }

    pub(crate) fn at(&self, state: &State) -> Assembled {
        self.assemble(&self.expand(&state.free, state.lambda), state.lambda)
    }

    /// The equilibrium `free` at `lambda` iterated on by Newton while its residual falls (at
    /// most six times): a path stops within its tolerance, and an output's derivative checked
    /// by differences of such ends would see that tolerance as noise; polished, the ends are
    /// the equilibrium to round-off and smooth in the design.
    pub(crate) fn polish(&self, mut free: Vec<f64>, lambda: f64) -> Vec<f64> {
        let mut best = (f64::INFINITY, free.clone());
        for _ in 0..6 {
            let a = self.assemble(&self.expand(&free, lambda), lambda);
            let r = norm(&a.residual);
            if r.is_nan() || r >= best.0 {
                break;
            }
            best = (r, free.clone());
            let Some(step) = solve_each(&a.tangent, &[&a.residual]) else {
                break;
            };
            for (f, s) in free.iter_mut().zip(&step[0]) {
                *f -= s;
            }
        }
        best.1
    }

    pub(crate) fn point(&self, state: &State) -> PathPoint {
        PathPoint {
            lambda: state.lambda,
            displacement: self.expand(&state.free, state.lambda),
        }
    }

    /// Converged when the residual is small against the load, or the correction against
    /// the displacement, or when the residual has stopped falling (less than four times
    /// from the last iteration, `previous`) below `sqrt(tol)` of the load: Newton's
    /// quadratic fall has then reached the round-off of the internal forces, which for a
    /// strip's axial stiffness can exceed `tol` of a small load.
    fn converged(
        &self,
        a: &Assembled,
        correction: &[f64],
        free: &[f64],
        previous: f64,
        tol: f64,
    ) -> bool {
        let (r, q) = (norm(&a.residual), norm(&a.load));
        r <= tol * q
            || norm(correction) <= tol * norm(free)
            || (r > 0.25 * previous && r <= tol.sqrt() * q)
    }

    /// Newton's method at fixed `lambda` from `start`; `None` if it does not converge.
    pub(crate) fn newton(&self, start: &[f64], lambda: f64, opts: &Options) -> Option<Vec<f64>> {
        let mut free = start.to_vec();
        let mut previous = f64::INFINITY;
        for _ in 0..opts.iterations {
            let a = self.at(&State {
                free: free.clone(),
                lambda,
            });
            let minus_r: Vec<f64> = a.residual.iter().map(|r| -r).collect();
            let step = solve_each(&a.tangent, &[&minus_r])?.remove(0);
            for (u, d) in free.iter_mut().zip(&step) {
                *u += d;
            }
            if self.converged(&a, &step, &free, previous, opts.tolerance) {
                return Some(free);
            }
            previous = norm(&a.residual);
        }
        None
    }

    /// From a converged `state`, the equilibrium at `lambda` by a tangent predictor and
    /// Newton, the step halved (up to `opts.cuts` times) where Newton fails.
    pub(crate) fn advance(
        &self,
        state: &State,
        lambda: f64,
        opts: &Options,
    ) -> Result<State, LargeError> {
        let mut current = state.clone();
        let mut target = lambda;
        let mut cuts = 0;
        while current.lambda != lambda {
            let a = self.at(&current);
            let rate = solve_each(&a.tangent, &[&a.load]).ok_or(LargeError::Singular {
                lambda: current.lambda,
            })?;
            let dl = target - current.lambda;
            let guess: Vec<f64> = current
                .free
                .iter()
                .zip(&rate[0])
                .map(|(u, v)| u + dl * v)
                .collect();
            match self.newton(&guess, target, opts) {
                Some(free) => {
                    current = State {
                        free,
                        lambda: target,
                    };
                    target = lambda;
                }
                None if cuts < opts.cuts => {
                    cuts += 1;
                    target = current.lambda + 0.5 * (target - current.lambda);
                }
                None => {
                    let a = self.at(&State {
                        free: guess,
                        lambda: target,
                    });
                    return Err(LargeError::NotConverged {
                        lambda: target,
                        residual: norm(&a.residual),
                        cuts,
                    });
                }
            }
        }
        Ok(current)
    }
}

/// The equilibrium path from the unloaded structure to `lambda_end` in `opts.steps` equal
/// load steps (each cut where Newton needs it); the path keeps the end of every step.
pub fn continuation(
    structure: &Structure,
    lambda_end: f64,
    opts: &Options,
) -> Result<Path, LargeError> {
    let system = System::new(structure)?;
    let mut state = system.unloaded();
    let mut points = vec![system.point(&state)];
    let steps = opts.steps.max(1);
    for i in 1..=steps {
        let lambda = lambda_end * i as f64 / steps as f64;
        state = system.advance(&state, lambda, opts)?;
        points.push(system.point(&state));
    }
    Ok(Path { points })
}

/// One arc-length step of length `dl` from `state` (the previous increment `previous`
/// orienting it); the new state and its increment, or `None` if it fails to converge.
fn arc_step(
    system: &System,
    state: &State,
    previous: Option<&[f64]>,
    dl: f64,
    opts: &Options,
) -> Result<Option<(State, Vec<f64>)>, LargeError> {
    let singular = || LargeError::Singular {
        lambda: state.lambda,
    };
    let a = system.at(state);
    let uq = solve_each(&a.tangent, &[&a.load])
        .ok_or_else(singular)?
        .remove(0);
    let sign = match previous {
        Some(p) if dot(p, &uq) < 0.0 => -1.0,
        _ => 1.0,
    };
    let mut dlambda = sign * dl / norm(&uq).max(f64::MIN_POSITIVE);
    let mut du: Vec<f64> = uq.iter().map(|v| dlambda * v).collect();
    let mut previous = f64::INFINITY;
    for _ in 0..opts.iterations {
        let trial = State {
            free: state.free.iter().zip(&du).map(|(u, d)| u + d).collect(),
            lambda: state.lambda + dlambda,
        };
        let a = system.at(&trial);
        let minus_r: Vec<f64> = a.residual.iter().map(|r| -r).collect();
        let Some(mut sol) = solve_each(&a.tangent, &[&minus_r, &a.load]) else {
            return Ok(None);
        };
        let (uq, ur) = (sol.remove(1), sol.remove(0));
        let base: Vec<f64> = du.iter().zip(&ur).map(|(d, r)| d + r).collect();
        let qa = dot(&uq, &uq);
        let qb = 2.0 * dot(&uq, &base);
        let qc = dot(&base, &base) - dl * dl;
        let disc = qb * qb - 4.0 * qa * qc;
        if disc < 0.0 || qa == 0.0 {
            return Ok(None);
        }
        let root = disc.sqrt();
        // the root whose increment turns least from the current one (Crisfield 1981)
        let pick = [(-qb + root) / (2.0 * qa), (-qb - root) / (2.0 * qa)]
            .into_iter()
            .map(|dlam| {
                let new: Vec<f64> = base.iter().zip(&uq).map(|(b, q)| b + dlam * q).collect();
                (dot(&new, &du), dlam, new)
            })
            .max_by(|x, y| x.0.total_cmp(&y.0));
        let (_, dlam, new) = pick.expect("two roots");
        let correction: Vec<f64> = new.iter().zip(&du).map(|(n, d)| n - d).collect();
        du = new;
        dlambda += dlam;
        let free: Vec<f64> = state.free.iter().zip(&du).map(|(u, d)| u + d).collect();
        if system.converged(&a, &correction, &free, previous, opts.tolerance) {
            let next = State {
                free,
                lambda: state.lambda + dlambda,
            };
            return Ok(Some((next, du)));
        }
        previous = norm(&a.residual);
    }
    Ok(None)
}

/// The equilibrium path by cylindrical arc length from the unloaded structure until the
/// load factor first reaches `lambda_end` (where the last point is put by Newton at exactly
/// `lambda_end`), through limit points where the load falls back. The first arc is the
/// displacement of a linear step of `lambda_end / opts.steps`; arcs shrink where an
/// iteration fails and grow back after easy steps.
pub fn arc_length(
    structure: &Structure,
    lambda_end: f64,
    opts: &Options,
) -> Result<Path, LargeError> {
    let system = System::new(structure)?;
    let mut state = system.unloaded();
    let mut points = vec![system.point(&state)];
    let a = system.at(&state);
    let uq = solve_each(&a.tangent, &[&a.load])
        .ok_or(LargeError::Singular { lambda: 0.0 })?
        .remove(0);
    let nominal = lambda_end.abs() / opts.steps.max(1) as f64 * norm(&uq);
    let mut dl = nominal;
    let mut previous: Option<Vec<f64>> = None;
    let mut cuts = 0;
    let toward = lambda_end.signum();
    for _ in 0..opts.max_steps {
        match arc_step(&system, &state, previous.as_deref(), dl, opts)? {
            Some((next, du)) => {
                if toward * (next.lambda - lambda_end) >= 0.0 {
                    let t = (lambda_end - state.lambda) / (next.lambda - state.lambda);
                    let guess: Vec<f64> =
                        state.free.iter().zip(&du).map(|(u, d)| u + t * d).collect();
                    let Some(free) = system.newton(&guess, lambda_end, opts) else {
                        let a = system.at(&State {
                            free: guess,
                            lambda: lambda_end,
                        });
                        return Err(LargeError::NotConverged {
                            lambda: lambda_end,
                            residual: norm(&a.residual),
                            cuts,
                        });
                    };
                    points.push(system.point(&State {
                        free,
                        lambda: lambda_end,
                    }));
                    return Ok(Path { points });
                }
                state = next;
                points.push(system.point(&state));
                previous = Some(du);
                cuts = 0;
                dl = (2.0 * dl).min(nominal);
            }
            None if cuts < opts.cuts => {
                cuts += 1;
                dl *= 0.5;
            }
            None => {
                return Err(LargeError::NotConverged {
                    lambda: state.lambda,
                    residual: norm(&system.at(&state).residual),
                    cuts,
                })
            }
        }
    }
    Err(LargeError::PathTooLong {
        steps: opts.max_steps,
        lambda: state.lambda,
    })
}
