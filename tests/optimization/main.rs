//! The optimization: the local solvers on Hock-Schittkowski problems and at their edges, the
//! multistart study, and results that never claim more than they are.
//!
//! One test binary per subject (issue 21): each file is a module, the fixtures are shared.

#[path = "../common/mod.rs"]
mod common;

mod hock_schittkowski;
mod honest_results;
mod network_tolerances;
mod screening;
mod shards;
mod solver_robustness;
mod study;
mod tolerances;
mod unmakeable;
