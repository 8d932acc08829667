//! The ranges where the model's fitted formulas hold ([`crate::model::Model::fit_limits`]),
//! as the problem file's `[search] fit_ranges` treats them: the checks a report holds, the
//! warnings of a design outside them, and the study's test that its variables' bounds can
//! reach them at all. The study's constraints on them are rows of [`super::nlp`].

use super::{FitRanges, Problem};
use crate::model::fit::{check_all, FitCheck, FitLimit};

/// Every range of the problem's model checked at the design `x` (SI, every parameter).
pub fn checks(problem: &Problem, x: &[f64]) -> Vec<FitCheck> {
    check_all(problem.model().fit_limits(), x)
}

/// The warnings of the `checks` outside their ranges, unless the file allows designs
/// there (`fit_ranges = "allow"`).
pub fn warnings(problem: &Problem, checks: &[FitCheck]) -> Vec<String> {
    if problem.search.fit_ranges == FitRanges::Allow {
        return Vec::new();
    }
    checks
        .iter()
        .filter(|c| !c.inside)
        .map(FitCheck::warning)
        .collect()
}

/// The ranges the study keeps to as constraints: every one, unless the file says
/// otherwise.
pub fn constrained(problem: &Problem) -> &[FitLimit] {
    match problem.search.fit_ranges {
        FitRanges::Constraint => problem.model().fit_limits(),
        FitRanges::Warn | FitRanges::Allow => &[],
    }
}

/// Why no design within the variables' bounds meets one of the ranges the study keeps to,
/// if none does: a ratio of two variables spans `[lower_n / upper_d, upper_n / lower_d]`.
pub fn unreachable(problem: &Problem) -> Option<String> {
    for l in constrained(problem) {
        let (n, d) = (
            &problem.variables[l.numerator],
            &problem.variables[l.denominator],
        );
        let least = n.lower / d.upper;
        let most = if d.lower > 0.0 {
            n.upper / d.lower
        } else {
            f64::INFINITY
        };
        let r = &l.range;
        let low = r.upper.is_some_and(|hi| !r.contains(least) && least > hi);
        let high = r.lower.is_some_and(|lo| !r.contains(most) && most < lo);
        if low || high {
            let show = |v: f64| crate::vocab::units::short(format!("{v:.4e}").parse().unwrap_or(v));
            let span = if n.fixed && d.fixed {
                format!("is {} at their fixed values", show(least))
            } else {
                format!(
                    "lies between {} and {} within their bounds",
                    show(least),
                    show(most)
                )
            };
            return Some(format!(
                "{}: variables `{}` and `{}`: {}: {} {span}, never {}, the range of {}; widen \
                 their bounds, or set `fit_ranges = \"warn\"` in [search] to let the study \
                 leave the range",
                problem.file.display(),
                n.name,
                d.name,
                l.owner,
                l.ratio,
                r.text(),
                r.holds
            ));
        }
    }
    None
}
