//! A network's part as its file draws it: the description, the `[part]` settings and the
//! layout of the part's rules, stated once and shared by the part maker
//! ([`super::NetworkPart`]) and the model, whose footprint outputs (`part_width`,
//! `part_height`, issue 51) read the same solids the part is cut from.

use super::super::description::Description;
use super::rules::{Layout, Rules};
use super::settings::PartSettings;
use crate::model::scalar::Scalar;

/// The part as drawn: the description (its expressions numbered for the layout's tape), the
/// settings and the rules' layout.
#[derive(Debug, Clone)]
pub struct Drawing {
    pub description: Description,
    pub settings: PartSettings,
    pub(super) layout: Layout,
}

impl Drawing {
    pub fn new(mut description: Description, settings: PartSettings) -> Self {
        Drawing {
            layout: Layout::new(&mut description),
            description,
            settings,
        }
    }

    /// The outline's width along x and height along y (m) at the design `x` (SI) over `D`:
    /// its bounding box, every image about the mirror axes and every pad included; `None`
    /// where an expression has no value there.
    pub fn footprint<D: Scalar>(&self, x: &[D]) -> Option<[D; 2]> {
        let [x0, y0, x1, y1] = self.layout.extent(&self.description, &self.settings, x)?;
        Some([x1 - x0, y1 - y0])
    }

    pub(super) fn rules(&self) -> Rules<'_> {
        Rules {
            layout: &self.layout,
            d: &self.description,
            s: &self.settings,
        }
    }
}
