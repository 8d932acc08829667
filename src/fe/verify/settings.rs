//! How a verification runs ([`VerifySettings`]: its tolerance, its meshes' budget, what it
//! computes) and why a sequence of meshes stopped short ([`BudgetStop`]).

use serde::Serialize;

#[cfg(doc)]
use super::Solid3d;
#[cfg(doc)]
use crate::fe::FeError;

/// How a verification runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VerifySettings {
    /// Every converging output's estimated relative error must fall below this.
    pub tolerance: f64,
    /// The most meshes in the sequence (at least three).
    pub max_levels: usize,
    /// The force a load of share 1 carries (N).
    pub test_force: f64,
    /// Elements through a hinge's thickness on the first mesh (element size `t / n` at the
    /// hinges).
    pub per_thickness: f64,
    /// The stiffness of every element outside the hinges' thin sections is multiplied by
    /// this: 1 for the part as it is, large to make its links, blocks and fillets nearly
    /// rigid, as the analytic model has them (a measurement of what that assumption costs).
    pub body_stiffening: f64,
    /// Compute the natural modes too (where the material has a density).
    pub modal: bool,
    /// Make the 3D check too ([`Solid3d`]).
    pub solid: bool,
    /// The most degrees of freedom a mesh of the half part may have: the sequence stops
    /// before a mesh that would have more, and a part whose first mesh would is refused
    /// ([`FeError::Budget`]). Memory grows with it, about 4 kB a degree of freedom for both
    /// idealizations and the modes (docs/guide/src/fe-check.md, measured).
    pub max_dofs: usize,
}

/// The default [`VerifySettings::max_dofs`]: 400,000, about 1.6 GB.
pub const MAX_DOFS: usize = 400_000;

impl VerifySettings {
    /// Elements through a hinge's thickness for a `tolerance`: 4 at the default 0.5 % and
    /// below, fewer for a looser one, as the stiffness error of the six-node triangles falls
    /// as the third power of the element size or faster (the observed orders of
    /// `verify.json`): `4 (0.005 / tolerance)^(1/3)`, never below 2.
    pub fn per_thickness_for(tolerance: f64) -> f64 {
        (4.0 * (0.005 / tolerance).cbrt()).clamp(2.0, 4.0)
    }
}

/// Why a sequence of meshes ended before its outputs converged: the next mesh would have
/// had more degrees of freedom than the budget.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BudgetStop {
    /// The degrees of freedom the next mesh would have had (about four times the last's).
    pub next_dofs: usize,
    pub max_dofs: usize,
}

impl std::fmt::Display for BudgetStop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the next mesh would have about {} degrees of freedom, more than the budget of {} \
             (--max-dofs)",
            self.next_dofs, self.max_dofs
        )
    }
}

impl Default for VerifySettings {
    fn default() -> Self {
        VerifySettings {
            tolerance: 0.005,
            max_levels: 4,
            test_force: 10.0,
            per_thickness: 4.0,
            body_stiffening: 1.0,
            modal: true,
            solid: true,
            max_dofs: MAX_DOFS,
        }
    }
}
