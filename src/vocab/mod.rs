//! The problem file's vocabulary, below every other layer that reads a file: physical
//! dimensions and units, the values a file writes, the reader that names the key of every
//! error, and the view of its sections that a model reads its own from.
//!
//! Both [`crate::model`] (each model reads its own sections) and [`crate::problem`] (the
//! common keys, the binding of outputs to objective and constraints) stand on it; it
//! imports neither.

pub mod dimension;
pub mod error;
pub mod input;
pub mod reader;
pub mod schema;
pub mod sections;
pub mod units;
pub mod values;

pub use dimension::Dimension;
pub use error::ProblemError;
