//! The actuator that drives a mechanism's input, and its `[actuator]` section: one type and one
//! reader for every mechanism, so a problem file's `[actuator]` means the same whatever the
//! model (one schema for the section of that name).

use serde::{Deserialize, Serialize};

use crate::vocab::reader::{k, Res};
use crate::vocab::schema::{
    Measured, NonNegativeForce, NonNegativeMass, PositiveLength, PositiveStiffness,
};
use crate::vocab::sections::Sections;

/// The piezo actuator that drives the input (paper 004, Eq. 12-14).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Actuator {
    /// Nominal stroke X_PZT^nl (m).
    pub nominal_stroke: f64,
    /// Preload F_preload (N).
    pub preload: f64,
    /// Stiffness k_pzt (N/m); `None` for an actuator much stiffer than the mechanism.
    pub stiffness: Option<f64>,
    /// The stack's own mass (kg), where the file gives it: the natural modes carry its
    /// Rayleigh share on the faces it pushes ([`crate::part::stack_mass_share`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
}

/// `[actuator]` as the file writes it.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawActuator {
    pub(crate) nominal_stroke: Measured<PositiveLength>,
    pub(crate) preload: Measured<NonNegativeForce>,
    pub(crate) stiffness: Option<Measured<PositiveStiffness>>,
    pub(crate) length: Option<Measured<PositiveLength>>,
    pub(crate) height: Option<Measured<PositiveLength>>,
    pub(crate) mass: Option<Measured<NonNegativeMass>>,
}

impl Actuator {
    /// Reads `[actuator]`'s stroke, preload and stiffness (its `length` and `height` are the
    /// part's, read with it).
    pub(crate) fn read(s: &Sections, a: &RawActuator) -> Res<Actuator> {
        let path = |key: &str| [k("actuator"), k(key)];
        Ok(Actuator {
            nominal_stroke: s.measured(&path("nominal_stroke"), &a.nominal_stroke)?,
            preload: s.measured(&path("preload"), &a.preload)?,
            stiffness: match &a.stiffness {
                Some(q) => Some(s.measured(&path("stiffness"), q)?),
                None => None,
            },
            mass: match &a.mass {
                Some(q) => Some(s.measured(&path("mass"), q)?),
                None => None,
            },
        })
    }
}
