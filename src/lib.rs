//! flexopt: design and optimization of piezo-driven compliant (flexure-hinge) mechanisms.
//!
//! - [`vocab`]: the problem file's vocabulary (dimensions, units, values, the reader,
//!   errors), which both `model` and `problem` stand on.
//! - [`model`]: the closed-form mechanism models, generic over dual numbers.
//! - [`problem`]: problem files (TOML), units, validation and the binding of model
//!   outputs to an objective and constraints.
//! - [`report`]: JSON export and plots.
//! - [`sweep`]: curves of every output against one design variable.
//! - [`pareto`]: trade-off fronts by stepping the limit of one constraint.
//! - [`refine`]: an optimum refined against the finite elements of its part.
//! - [`dynamics`]: Runge-Kutta step responses of single-degree-of-freedom systems.

pub mod dynamics;
pub mod fe;
pub mod model;
pub mod optim;
pub mod pareto;
pub mod part;
pub mod problem;
pub mod refine;
pub mod report;
pub mod study;
pub mod sweep;
pub mod tolerance;
pub mod vocab;
