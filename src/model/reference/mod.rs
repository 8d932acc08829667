//! Reference formulations that check the models; no problem file selects them.
//!
//! - [`bridge_matrix`]: the quarter bridge solved as a small linear elastic system, sharing
//!   no formula with the closed form of [`super::bridge`]; the tests compare the two.
//! - [`closed_forms`]: paper 004's formulas for the parallel, rhombic and aligned bridges
//!   (Sec. 5), limits the general model must reach.
//! - [`bridge_lagrange`] and [`platform6`]: paper 001's rigid-beam bridge and its 6-DOF
//!   platform, reproduced to check that paper's printed equations and tables. They are not
//!   models a problem file can select: the bridge of paper 001 is the general bridge of
//!   [`super::bridge`] with a rigid beam, which that model covers with its own dynamics, and
//!   the platform needs masses and dimensions paper 001 does not print (see `docs/papers.md`).

pub mod bridge_lagrange;
pub mod bridge_matrix;
pub mod closed_forms;
pub mod platform6;
