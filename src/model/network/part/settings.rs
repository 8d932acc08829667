//! `[part]` of a network read into its settings: apart from the part's making so that the
//! flexures' cutting and the rules read the settings without importing the part back.

use serde::Deserialize;

use crate::vocab::reader::{k, Res};
use crate::vocab::schema::{Measured, NonNegativeLength, PositiveLength};
use crate::vocab::sections::Sections;

/// `[part]` of a network: a file with this section has a part.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RawNetworkPart {
    /// The radius of the fillets at a strip's roots (default 0.2 mm).
    fillet_radius: Option<Measured<NonNegativeLength>>,
    /// The narrowest slot the wire cuts (default 0.4 mm).
    min_slot: Option<Measured<NonNegativeLength>>,
    /// How deep each hinge's pad reaches into its body (default 2 mm).
    pad: Option<Measured<PositiveLength>>,
    /// How far a pad reaches beside the hinge's root and fillet (default 1 mm).
    pad_margin: Option<Measured<PositiveLength>>,
    /// The length of a port's face (default 2 mm).
    face: Option<Measured<PositiveLength>>,
    /// Whether the study keeps to the part's rules (default true): its slots and keep-out
    /// bands as constraints; `false` checks the part after the study only.
    enforce: Option<bool>,
}

/// `[part]` of a network (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PartSettings {
    pub fillet_radius: f64,
    pub min_slot: f64,
    pub pad: f64,
    pub pad_margin: f64,
    pub face: f64,
    /// Whether the study keeps to the part's rules ([`super::rules`]): `[part] enforce`.
    pub enforce: bool,
}

impl Default for PartSettings {
    /// As the bridge's part: wire EDM with a 0.25 mm wire cuts inner corners of about 0.17
    /// mm radius and slots of about 0.33 mm.
    fn default() -> Self {
        PartSettings {
            fillet_radius: 0.2e-3,
            min_slot: 0.4e-3,
            pad: 2e-3,
            pad_margin: 1e-3,
            face: 2e-3,
            enforce: true,
        }
    }
}

impl PartSettings {
    /// `[part]`, each key with its default.
    pub fn read(s: &Sections, p: &RawNetworkPart) -> Res<Self> {
        let at = |key: &str| [k("part"), k(key)];
        let d = PartSettings::default();
        Ok(PartSettings {
            fillet_radius: s.measured_or(
                &at("fillet_radius"),
                &p.fillet_radius,
                d.fillet_radius,
            )?,
            min_slot: s.measured_or(&at("min_slot"), &p.min_slot, d.min_slot)?,
            pad: s.measured_or(&at("pad"), &p.pad, d.pad)?,
            pad_margin: s.measured_or(&at("pad_margin"), &p.pad_margin, d.pad_margin)?,
            face: s.measured_or(&at("face"), &p.face, d.face)?,
            enforce: p.enforce.unwrap_or(d.enforce),
        })
    }
}
