//! Which sampled parts can be made. A sample whose part breaks one of the rules its model
//! states ([`crate::model::part_rules`]: a link thinner than its hinges, a slot narrower
//! than the wire, the actuator's room) is a failed part: it counts against the yield beside
//! the parts that miss a performance limit, and the analyses report the share of them.
//!
//! Every rule counts, whether or not the study keeps to them (`[part] enforce`): that
//! setting says what the optimizer is held to, not what can be cut. A model without a part,
//! or whose part states no rules, makes every sample.

use crate::model::mechanism::PartMaker;
use crate::model::part_rules::broken;
use crate::problem::Problem;

/// The rules a sampled part must keep.
pub struct Rules<'a> {
    part: Option<&'a dyn PartMaker>,
    count: usize,
}

impl<'a> Rules<'a> {
    /// The rules of `problem`'s part, if it has one.
    pub fn of(problem: &'a Problem) -> Self {
        let part = problem.mechanism().part_maker.as_deref();
        let count = part.map_or(0, |p| p.rules().len());
        Rules { part, count }
    }

    /// How many rules there are.
    pub fn len(&self) -> usize {
        self.count
    }

    /// Whether there are none (every sample can be made).
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// The rules' names, in their order.
    pub fn names(&self) -> Vec<String> {
        self.part.map_or_else(Vec::new, |p| {
            p.rules().iter().map(|r| r.name.to_string()).collect()
        })
    }

    /// Each rule's margin (m) at the design `x` (SI) into `margins` ([`Rules::len`] of
    /// them); whether the part keeps every one.
    pub fn keeps_all(&self, x: &[f64], margins: &mut [f64]) -> bool {
        match self.part {
            Some(part) if self.count > 0 => {
                part.rule_margins(x, margins);
                !margins.iter().any(|&m| broken(m))
            }
            _ => true,
        }
    }

    /// The names of the rules the part at `x` breaks, with their margins (mm), joined for a
    /// message; empty where it keeps them all.
    pub fn broken_at(&self, x: &[f64]) -> String {
        let mut margins = vec![0.0; self.count];
        if self.keeps_all(x, &mut margins) {
            return String::new();
        }
        self.names()
            .iter()
            .zip(&margins)
            .filter(|(_, &m)| broken(m))
            .map(|(name, m)| format!("{name} ({:.4} mm)", m * crate::part::MM))
            .collect::<Vec<_>>()
            .join(", ")
    }
}
