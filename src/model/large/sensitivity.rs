//! Derivatives of an equilibrium by the design, through the implicit function theorem.
//!
//! At a converged equilibrium `r(u, p) = 0` on the free degrees of freedom (`p` the design,
//! which moves the nodes, the sections, the springs and the prescribed values), the
//! displacement's derivative is `du/dp = -K_t^{-1} dr/dp|_u`, one solve with the tangent
//! already at hand for every direction of the design (the direct method of design
//! sensitivity analysis: Haftka and Gurdal, *Elements of Structural Optimization*, 3rd ed.,
//! Kluwer 1992, section 7.2.1, for a nonlinear response; Choi and Kim, *Structural
//! Sensitivity Analysis and Optimization 1*, Springer 2005, ch. 5).
//!
//! The structure is built a second time over a dual number `D` that carries the design's
//! derivatives ([`StructureOf`]); its residual at the real equilibrium `u` is `dr/dp|_u`
//! in its derivative parts (its real part vanishes to the path's tolerance). Solving with
//! the real tangent's factors gives `u` as a dual number carrying `du/dp`, and every output
//! computed from it over `D` carries its total derivative: a port's motion, an end load, and
//! the tangent's own functions (a stiffness at stroke) through [`Factored::solve_dual`].

use faer::linalg::solvers::PartialPivLu;
use faer::Mat;

use super::assemble::{System, SystemOf};
use super::LargeError;
use crate::model::scalar::Scalar;

/// A real matrix's LU factors, which solve right-hand sides in any scalar.
pub struct Factored {
    lu: PartialPivLu<f64>,
    n: usize,
}

impl Factored {
    pub fn new(k: &Mat<f64>) -> Self {
        Factored {
            lu: k.partial_piv_lu(),
            n: k.nrows(),
        }
    }

    /// Whether every pivot is finite and nonzero: the solves are then finite.
    pub fn is_regular(&self) -> bool {
        let u = self.lu.U();
        (0..self.n).all(|i| u[(i, i)].is_finite() && u[(i, i)] != 0.0)
    }

    /// The row-major `n x n` real parts of `k`, factored.
    pub fn of_real_parts<D: Scalar>(k: &[D], n: usize) -> Self {
        Factored::new(&Mat::from_fn(n, n, |i, j| k[i * n + j].re()))
    }

    /// `K^{-1} b` for a right-hand side in any scalar: `P K = L U`, the rows of `b` taken
    /// in the pivots' order, then the two triangular solves, each a sum of the scalar times
    /// real factors (so a dual number's parts are solved with the real matrix).
    pub fn solve<D: Scalar>(&self, b: &[D]) -> Vec<D> {
        let (l, u) = (self.lu.L(), self.lu.U());
        let (forward, _) = self.lu.P().arrays();
        let n = self.n;
        let mut y: Vec<D> = forward.iter().map(|&i| b[i]).collect();
        for i in 0..n {
            let mut sum = y[i];
            for j in 0..i {
                sum = sum - y[j] * l[(i, j)];
            }
            y[i] = sum / l[(i, i)];
        }
        for i in (0..n).rev() {
            let mut sum = y[i];
            for j in i + 1..n {
                sum = sum - y[j] * u[(i, j)];
            }
            y[i] = sum / u[(i, i)];
        }
        y
    }

    /// `z = K^{-1} e` where `K` (row-major, `n x n`) and `e` are dual numbers whose real
    /// parts these factors hold: `z0` from the real parts, then `dz = K0^{-1} (de - dK z0)`,
    /// the derivative of `K z = e`.
    pub fn solve_dual<D: Scalar>(&self, k: &[D], e: &[D]) -> Vec<D> {
        let n = self.n;
        let z0 = self.solve(&e.iter().map(|v| v.re()).collect::<Vec<f64>>());
        let residual: Vec<D> = (0..n)
            .map(|i| {
                let mut v = e[i];
                for (j, &z) in z0.iter().enumerate() {
                    v = v - k[i * n + j] * z;
                }
                // the derivative parts alone: the real part is e0 - K0 z0, round-off
                v - v.re()
            })
            .collect();
        let dz = self.solve(&residual);
        z0.iter().zip(dz).map(|(&z, d)| d + z).collect()
    }
}

/// Every node's displacement at the equilibrium `free` (the real free displacements of
/// `real` at load factor `lambda`) as dual numbers carrying their derivatives by the design
/// that `dual`, the same structure built over `D`, carries.
pub fn equilibrium_by_design<D: Scalar>(
    real: &System,
    dual: &SystemOf<D>,
    free: &[f64],
    lambda: f64,
) -> Result<Vec<D>, LargeError> {
    let tangent = real.assemble(&real.expand(free, lambda), lambda).tangent;
    let factored = Factored::new(&tangent);
    if !factored.is_regular() {
        return Err(LargeError::Singular { lambda });
    }
    let at: Vec<D> = free.iter().map(|&v| D::from(v)).collect();
    let by_design: Vec<D> = dual
        .residual(&at, lambda)
        .into_iter()
        .map(|r| r - r.re())
        .collect();
    let step = factored.solve(&by_design);
    let moved: Vec<D> = at.iter().zip(step).map(|(&u, s)| u - s).collect();
    Ok(dual.expand(&moved, lambda))
}
