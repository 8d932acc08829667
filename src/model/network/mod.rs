//! Planar compliant mechanisms described as networks of rigid bodies and flexures (issue
//! 25): the structural analysis ([`structure`]) of bodies joined through the hinge
//! library's compliances, over [`crate::model::scalar::Scalar`] for exact gradients. The
//! problem file's description, its outputs and its part build on it.

pub mod structure;
