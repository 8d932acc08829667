//! Where a model's fitted formulas hold: ranges of ratios of its parameters (a notch
//! hinge's `t/r`, a leaf's `l/t`), each with what it keeps valid and the source that fitted
//! or checked the formula. A hinge kind declares its ranges over its own dimensions
//! ([`crate::model::hinge::kinds::Kind::FIT`]); a model lists them over its parameters
//! ([`crate::model::Model::fit_limits`]), and the problem layer warns of a design outside
//! them or keeps the study inside them as constraints.

use serde::Serialize;

use super::scalar::Scalar;

/// The relative margin by which a ratio may pass a bound and still count as inside: the
/// study's feasibility tolerance (`problem::nlp::FEASIBILITY_TOLERANCE`, held equal to this
/// by a check there), so that an optimum the study leaves on a bound draws no warning.
pub const TOLERANCE: f64 = 1e-8;

/// The range of one ratio and where it comes from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FitRange {
    /// The least value, if any.
    pub lower: Option<f64>,
    /// The largest value, if any.
    pub upper: Option<f64>,
    /// What holds within the range: "the beam model of the notch", say.
    pub holds: &'static str,
    /// The formula's source and the range's: author, journal, year, equation.
    pub source: &'static str,
}

impl FitRange {
    /// Whether `value` lies within the range, up to [`TOLERANCE`].
    pub fn contains(&self, value: f64) -> bool {
        let above = |b: f64| value >= b - TOLERANCE * b.abs();
        let below = |b: f64| value <= b + TOLERANCE * b.abs();
        value.is_finite() && self.lower.is_none_or(above) && self.upper.is_none_or(below)
    }

    /// The range in words: "at most 1", "at least 0.05", "from 0.05 to 1".
    pub fn text(&self) -> String {
        match (self.lower, self.upper) {
            (Some(lo), Some(hi)) => format!("from {lo} to {hi}"),
            (Some(lo), None) => format!("at least {lo}"),
            (None, Some(hi)) => format!("at most {hi}"),
            (None, None) => "any value".into(),
        }
    }
}

/// A range over a model's parameters: the ratio `x[numerator] / x[denominator]`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FitLimit {
    /// What the range belongs to, as a warning names it: "hinge b (circular)".
    pub owner: String,
    /// The ratio by the parameters' names: "t2/r2".
    pub ratio: String,
    /// Parameter indices of the ratio's two terms.
    pub numerator: usize,
    pub denominator: usize,
    pub range: FitRange,
}

impl FitLimit {
    /// The ratio at the design `x` (every parameter), generic over the scalar so that the
    /// study's constraint on it has the exact gradient the models' outputs have.
    pub fn value<D: Scalar>(&self, x: &[D]) -> D {
        x[self.numerator] / x[self.denominator]
    }

    /// The ratio at the design `x` (SI, every parameter) against its range.
    pub fn check(&self, x: &[f64]) -> FitCheck {
        let value = self.value(x);
        FitCheck {
            owner: self.owner.clone(),
            ratio: self.ratio.clone(),
            value,
            lower: self.range.lower,
            upper: self.range.upper,
            inside: self.range.contains(value),
            holds: self.range.holds,
            source: self.range.source,
        }
    }
}

/// One ratio of a design against its range: what reports hold and warnings say.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FitCheck {
    pub owner: String,
    pub ratio: String,
    pub value: f64,
    pub lower: Option<f64>,
    pub upper: Option<f64>,
    pub inside: bool,
    pub holds: &'static str,
    pub source: &'static str,
}

impl FitCheck {
    /// The warning of a ratio outside its range; names the owner, the ratio, its value and
    /// the range.
    pub fn warning(&self) -> String {
        let range = FitRange {
            lower: self.lower,
            upper: self.upper,
            holds: self.holds,
            source: self.source,
        };
        format!(
            "{}: {} = {} lies outside {} {}, the range of {}: the model's figures are not to \
             be trusted there",
            self.owner,
            self.ratio,
            crate::vocab::units::short(format!("{:.4e}", self.value).parse().unwrap_or(self.value)),
            self.ratio,
            range.text(),
            self.holds
        )
    }
}

/// The checks of every limit at `x` (SI, every parameter).
pub fn check_all(limits: &[FitLimit], x: &[f64]) -> Vec<FitCheck> {
    limits.iter().map(|l| l.check(x)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const RANGE: FitRange = FitRange {
        lower: Some(0.05),
        upper: Some(1.0),
        holds: "a test",
        source: "none",
    };

    #[test]
    fn a_bound_reached_within_the_tolerance_is_inside() {
        assert!(RANGE.contains(1.0 + 0.5 * TOLERANCE));
        assert!(RANGE.contains(0.05 * (1.0 - 0.5 * TOLERANCE)));
        assert!(!RANGE.contains(1.0 + 2.0 * TOLERANCE));
        assert!(!RANGE.contains(0.049));
        assert!(!RANGE.contains(f64::NAN));
        assert_eq!(RANGE.text(), "from 0.05 to 1");
    }

    #[test]
    fn a_warning_names_the_owner_the_ratio_its_value_and_the_range() {
        let limit = FitLimit {
            owner: "hinge b (circular)".into(),
            ratio: "t2/r2".into(),
            numerator: 1,
            denominator: 0,
            range: FitRange {
                lower: None,
                ..RANGE
            },
        };
        let c = limit.check(&[0.25e-3, 2e-3]);
        assert!(!c.inside);
        let w = c.warning();
        assert!(
            w.starts_with(
                "hinge b (circular): t2/r2 = 8 lies outside t2/r2 at most 1, the range of a test"
            ),
            "{w}"
        );
    }
}
