//! Planar compliant mechanisms described as networks of rigid bodies and flexures (issue
//! 25): the structural analysis ([`structure`]) of bodies joined through the hinge
//! library's compliances, and the natural modes of their masses on it ([`modes`]), over
//! [`crate::model::scalar::Scalar`] for exact gradients. The problem file's description,
//! its outputs and its part build on them.

pub mod modes;
pub mod ports;
pub mod structure;
