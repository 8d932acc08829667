//! The part's rules ([`crate::model::part_rules`]) as the study and its reports treat
//! them: the study keeps to them where the model's part states them and enforces them
//! (`[part] enforce`, the default; rows of [`super::nlp`]), and a report lists each one's
//! margin at its design and which are active there.

use serde::Serialize;

use super::nlp::ACTIVE_TOLERANCE;
use super::Problem;
use crate::model::mechanism::PartMaker;
use crate::model::part_rules::{broken, SCALE};

/// The part whose rules the study keeps to, if it keeps to any.
pub fn enforced(problem: &Problem) -> Option<&dyn PartMaker> {
    let part = problem.mechanism().part_maker.as_deref()?;
    (part.enforces_rules() && !part.rules().is_empty()).then_some(part)
}

/// One rule at a design.
#[derive(Debug, Clone, Serialize)]
pub struct RuleCheck {
    pub rule: String,
    pub description: String,
    /// How far the part is inside the rule (mm); negative where it breaks it.
    pub margin_mm: f64,
    pub met: bool,
    /// On the rule's limit: within the study's activity tolerance of it.
    pub active: bool,
    /// Where the part measures it (mm), for the drawing ([`crate::model::part_rules::Witness`]).
    #[serde(skip)]
    pub witness_mm: Option<[[f64; 2]; 2]>,
}

/// Every rule the problem's part states, at the design `x` (SI, every parameter); none for
/// a model without a part or rules.
pub fn checks(problem: &Problem, x: &[f64]) -> Vec<RuleCheck> {
    let Some(part) = problem.mechanism().part_maker.as_deref() else {
        return Vec::new();
    };
    let rules = part.rules();
    let mut margins = vec![0.0; rules.len()];
    part.rule_margins(x, &mut margins);
    let mut witnesses = vec![None; rules.len()];
    part.rule_witnesses(x, &mut witnesses);
    rules
        .iter()
        .zip(margins)
        .zip(witnesses)
        .map(|((r, m), w)| RuleCheck {
            witness_mm: w.map(|w| w.points.map(|p| p.map(|v| v * crate::part::MM))),
            rule: r.name.to_string(),
            description: r.description.to_string(),
            margin_mm: m * crate::part::MM,
            met: !broken(m),
            active: (m / SCALE).abs() <= ACTIVE_TOLERANCE,
        })
        .collect()
}
