//! A design as a designer reads it on a terminal: `flexopt eval --format table`, and the
//! constraint lines of the run summary. Every quantity in the unit the problem file used for
//! it, or the designer's usual one ([`super::display`]).

use std::fmt::{self, Display};

use super::display::{human, output_unit, with_unit};
use super::part::margin_text;
use super::{ConstraintReport, DesignReport};
use crate::model::fit::FitCheck;
use crate::problem::part_rules::RuleCheck;
use crate::problem::{Problem, Sense};

/// `eval`'s table: the design, every output, the objective and each constraint.
pub struct DesignTable<'a> {
    pub problem: &'a Problem,
    pub report: &'a DesignReport,
}

impl Display for DesignTable<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (p, r) = (self.problem, self.report);
        let model = p.model();
        writeln!(s, "{} ({} model)", p.name, r.model)?;
        writeln!(s, "design")?;
        for v in &p.variables {
            let value = r.design.get(&v.name).copied().unwrap_or(f64::NAN);
            let fixed = if v.fixed { "  (fixed)" } else { "" };
            writeln!(
                s,
                "  {:<22} {:>14} {}{fixed}",
                v.name,
                human(value),
                v.unit.name
            )?;
        }
        writeln!(s, "outputs")?;
        for (name, value) in &r.outputs {
            let Some(i) = model.output_index(name) else {
                continue;
            };
            let unit = output_unit(p, i);
            let shown = value.map_or("-".to_string(), |v| human(unit.from_si(v)));
            let u = if unit.name == "1" { "" } else { &unit.name };
            writeln!(s, "  {name:<22} {shown:>14} {u}")?;
        }
        let o = &p.objective;
        let unit = output_unit(p, o.index);
        writeln!(
            s,
            "objective: {} {}{}{} = {}",
            match o.sense {
                Sense::Maximize => "maximize",
                Sense::Minimize => "minimize",
            },
            if o.absolute { "|" } else { "" },
            o.output,
            if o.absolute { "|" } else { "" },
            r.objective.map_or("-".to_string(), |v| with_unit(v, &unit))
        )?;
        if !r.constraints.is_empty() {
            write!(s, "{}", ConstraintLines(&r.constraints))?;
        }
        if !r.fit_ranges.is_empty() {
            write!(s, "{}", FitLines(&r.fit_ranges))?;
        }
        if !r.part_rules.is_empty() {
            write!(s, "{}", RuleLines(&r.part_rules))?;
        }
        writeln!(
            s,
            "feasible: {}",
            if r.feasible {
                "yes, every constraint met"
            } else {
                "NO"
            }
        )
    }
}

/// The ranges where the model's fits hold, one aligned line each: the ratio, its value,
/// its range, the hinge (or part) it belongs to, and whether the design lies outside.
pub struct FitLines<'a>(pub &'a [FitCheck]);

impl Display for FitLines<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            s,
            "  {:<22} {:>14} {:>24}  {:<7} of",
            "range of fit", "value", "range", ""
        )?;
        for c in self.0 {
            let num = |v: Option<f64>| v.map_or(String::new(), human);
            let range = format!("{} .. {}", num(c.lower), num(c.upper));
            writeln!(
                s,
                "  {:<22} {:>14} {:>24}  {:<7} {}",
                c.ratio,
                human(c.value),
                range.trim(),
                if c.inside { "" } else { "OUTSIDE" },
                c.owner
            )?;
        }
        Ok(())
    }
}

/// The constraints, one aligned line each: value, limits, margin, and whether it is active
/// or violated.
pub struct ConstraintLines<'a>(pub &'a [ConstraintReport]);

impl Display for ConstraintLines<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            s,
            "  {:<22} {:>14} {:>24} {:>14}  {:<10} ",
            "constraint", "value", "limits", "margin", "unit"
        )?;
        for c in self.0 {
            let num = |v: Option<f64>| v.map_or(String::new(), human);
            let limits = format!("{} .. {}", num(c.lower), num(c.upper));
            let state = if !c.satisfied {
                "VIOLATED"
            } else if c.active {
                "active"
            } else {
                ""
            };
            writeln!(
                s,
                "  {:<22} {:>14} {:>24} {:>14}  {:<10} {state}",
                c.output,
                c.value.map_or("-".to_string(), human),
                limits.trim(),
                // a margin at the rounding of the limit is none
                match (c.margin, c.relative_margin) {
                    (Some(_), Some(r)) if r.abs() < 1e-9 => "0".to_string(),
                    (m, _) => m.map_or("-".to_string(), human),
                },
                c.unit,
            )?;
        }
        for c in self.0 {
            if let Some(what) = &c.stand_in {
                writeln!(
                    s,
                    "  {}: the model's value is {what}; only the finite elements measure it \
                     (run --refine fe)",
                    c.output
                )?;
            }
        }
        Ok(())
    }
}

/// The part's rules, one aligned line each: the margin in mm, whether the design breaks
/// the rule or stands on it, and what the rule asks.
pub struct RuleLines<'a>(pub &'a [RuleCheck]);

impl Display for RuleLines<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        // the networks' rules name two solids each: the column is as wide as the longest
        let width = self.0.iter().map(|r| r.rule.len()).fold(22, usize::max);
        writeln!(
            s,
            "  {:<width$} {:>14} {:<7} asks",
            "part rule", "margin mm", ""
        )?;
        for r in self.0 {
            let state = if !r.met {
                "BROKEN"
            } else if r.active {
                "active"
            } else {
                ""
            };
            writeln!(
                s,
                "  {:<width$} {:>14} {:<7} {}",
                r.rule,
                margin_text(r.margin_mm),
                state,
                r.description
            )?;
        }
        Ok(())
    }
}
