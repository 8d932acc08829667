//! Solvers that know nothing of mechanisms: a dense SQP, a constrained Nelder-Mead, the
//! multistart engine and the clustering of optima, all written against [`Problem`].

pub mod cluster;
pub mod dense;
pub mod finite_differences;
pub mod hessian;
pub mod multistart;
pub mod nelder_mead;
pub mod problem;
pub mod progress;
pub mod qp;
pub mod sqp;
pub mod staged;

pub use problem::{Problem, Solution, Status};
