//! Finite elements: the analytic answer checked on the part itself.
//!
//! A part's outline ([`geometry`]) is meshed ([`mesh`]) with elements behind one interface
//! ([`element`]; the six-node triangle today), assembled into sparse matrices and solved
//! by sparse Cholesky ([`assembly`]); loads and face averages in [`loads`], natural modes
//! in [`modal`], stresses and the hinges' section resultants in [`stress`], the
//! discretization error from a sequence of uniformly refined meshes in [`richardson`],
//! CalculiX decks of the same analysis in [`calculix`], and paper 004's load cases on a
//! bridge in [`verify`]. Everything is SI inside.

pub mod assembly;
pub mod calculix;
pub mod element;
pub mod geometry;
pub mod hinge;
pub mod loads;
pub mod mesh;
pub mod modal;
pub mod richardson;
pub mod solid;
pub mod stress;
pub mod verify;

pub use element::{Elastic, Fidelity, Idealization};

/// Why an analysis could not be done.
#[derive(Debug, Clone, PartialEq)]
pub enum FeError {
    /// The outline could not be meshed.
    Mesh(String),
    /// The system could not be built or solved.
    Solve(String),
    /// The part lacks what the analysis needs (a named face, say).
    Setup(String),
    /// The part needs more degrees of freedom than the check may spend.
    Budget(String),
}

impl std::fmt::Display for FeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FeError::Mesh(m) => write!(f, "meshing failed: {m}"),
            FeError::Solve(m) => write!(f, "the finite-element solve failed: {m}"),
            FeError::Setup(m) => write!(f, "{m}"),
            FeError::Budget(m) => write!(f, "over the budget: {m}"),
        }
    }
}

impl std::error::Error for FeError {}

/// The displacements (full vectors, two a node) of `mesh` under each of `loads` (full force
/// vectors), with the degrees of freedom `fixed` held at `prescribed`.
pub fn solve_static<E: element::Element>(
    mesh: &mesh::Mesh<E>,
    material: &Elastic,
    width: f64,
    idealization: Idealization,
    fixed: &[bool],
    prescribed: &[f64],
    loads: &[Vec<f64>],
) -> Result<Vec<Vec<f64>>, FeError> {
    let pattern = assembly::Pattern::new(mesh, fixed)?;
    let k = pattern.stiffness(mesh, material, width, idealization)?;
    let factor = pattern.factor(&k)?;
    let n = pattern.dofs.count();
    let mut rhs = faer::Mat::<f64>::zeros(n, loads.len());
    for (j, f) in loads.iter().enumerate() {
        let r = assembly::reduced_rhs(
            mesh,
            &pattern.dofs,
            material,
            width,
            idealization,
            f,
            prescribed,
        )?;
        for (i, v) in r.into_iter().enumerate() {
            rhs[(i, j)] = v;
        }
    }
    factor.solve(&mut rhs);
    Ok((0..loads.len())
        .map(|j| {
            let x: Vec<f64> = (0..n).map(|i| rhs[(i, j)]).collect();
            pattern.dofs.expand(&x, prescribed)
        })
        .collect())
}
