//! The part's manufacturability rules as constraints of the design.
//!
//! A model's part ([`super::PartMaker`]) states each rule it knows as a function of the
//! design, `g(x) >= 0` where the part meets the rule: the rule's margin in metres (how much
//! wider a slot is than the wire needs, how much thicker a wall is than its hinges). Each
//! is written once over [`super::scalar::Scalar`], as the model's outputs are, so that the
//! dual numbers give its exact gradient; it may have kinks only where the part itself
//! changes shape (a face as wide as the link or as the hinge and its fillets, whichever is
//! wider), never where the rule flips.
//!
//! A rule's sign agrees with the part's own check of the same thing: the check reports a
//! problem exactly where the margin is below `-TOLERANCE`, and the study
//! ([`crate::problem::nlp`]) keeps each margin, divided by [`SCALE`], within its
//! feasibility tolerance of 0, so that a design the study accepts passes the check.

use std::borrow::Cow;

/// The length (m) a rule's row in the study is divided by: the row is the margin in units
/// of 0.1 mm, so that the study's feasibility tolerance (relative 1e-8) is 1e-9 mm.
pub const SCALE: f64 = 1e-4;

/// The margin (m) below which a part's check reports a rule broken: what the study's
/// feasibility tolerance lets a row fall short of 0, 1e-9 mm.
pub const TOLERANCE: f64 = crate::part::checks::TOLERANCE;

/// The most a clearance rule reads (m): a pair farther than this beyond its rule is not
/// worked out, and the rule reads this there (the bridge's and the network's clearances).
pub const CAP: f64 = 1e-3;

/// One rule: its name (what reports call it) and what it asks, in words.
#[derive(Debug, Clone, PartialEq)]
pub struct PartRule {
    pub name: Cow<'static, str>,
    pub description: Cow<'static, str>,
}

/// Where a rule is measured on the part (m, in the part's frame), for a drawing to mark it:
/// two points, one on each feature the rule keeps apart (two solids, a solid and a hinge's
/// keep-out band, a disc's centre and the side it touches), as far apart as the rule's
/// margin plus `limit` (the slot it asks, the disc's radius; 0 for no overlap), or, where
/// two solids overlap, as far as the overlap is deep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Witness {
    pub points: [[f64; 2]; 2],
    pub limit: f64,
}

/// Whether a margin (m) breaks its rule, by the part's checks.
pub fn broken(margin: f64) -> bool {
    margin < -TOLERANCE
}
