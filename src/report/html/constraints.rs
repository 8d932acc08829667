//! The constraints at a design and the part's size rules: a reviewer reads the active and
//! broken rules and the nearest ones, with a count of the rest.

use maud::{html, Markup};
use serde_json::Value;

use super::sections::{list, num, text, yes};
use super::Set;
use crate::problem::display::significant;

pub(super) fn constraint_table(constraints: &[Value]) -> Markup {
    html! {
        table {
            thead { tr {
                th { "constraint" } th.num { "value" } th.num { "lower" } th.num { "upper" }
                th { "unit" } th.num { "margin" } th.num { "relative" } th { "met" } th { "active" }
            } }
            tbody {
                @for c in constraints {
                    tr.active[c.get("active").and_then(Value::as_bool) == Some(true)]
                      .bad[c.get("satisfied").and_then(Value::as_bool) == Some(false)] {
                        td { code { (text(c, "output")) } }
                        td.num { (num(c.get("value"))) }
                        td.num { (num(c.get("lower"))) }
                        td.num { (num(c.get("upper"))) }
                        td { (text(c, "unit")) }
                        td.num { (num(c.get("margin"))) }
                        td.num { (num(c.get("relative_margin"))) }
                        td { (yes(c, "satisfied")) }
                        td { (yes(c, "active")) }
                    }
                }
            }
        }
    }
}

pub(super) fn constraints(set: &Set) -> Markup {
    let o = &set.optimum;
    let fits = list(Some(o), "fit_ranges");
    let rules = list(Some(o), "part_rules");
    html! {
        section #constraints {
            h2 { "Constraints at the optimum" }
            p.small {
                "Margin: the distance to the nearer limit in the constraint's unit, positive \
                 inside; relative: over the limit. Active rows (shaded) hold the optimum where it is."
            }
            (constraint_table(list(Some(o), "constraints")))
            @if !fits.is_empty() {
                h3 { "Ranges where the model's formulas hold" }
                table {
                    thead { tr { th { "owner" } th { "ratio" } th.num { "value" } th.num { "lower" } th.num { "upper" } th { "inside" } th { "source" } } }
                    tbody {
                        @for f in fits {
                            tr.bad[f.get("inside").and_then(Value::as_bool) == Some(false)] {
                                td { (text(f, "owner")) } td { code { (text(f, "ratio")) } }
                                td.num { (num(f.get("value"))) } td.num { (num(f.get("lower"))) }
                                td.num { (num(f.get("upper"))) } td { (yes(f, "inside")) }
                                td.small { (text(f, "source")) }
                            }
                        }
                    }
                }
            }
            @if !rules.is_empty() {
                @let (shown_rules, rest) = rules_to_show(rules);
                h3 { "The part's size rules" }
                p.small {
                    "The active and broken rules and the " (NEAREST_RULES) " nearest to their limits; \
                     all " (rules.len()) " are in " code { "optimum.json" } " (" code { "part_rules" } ")."
                }
                table {
                    thead { tr { th { "rule" } th { "what" } th.num { "margin, mm" } th { "met" } th { "active" } } }
                    tbody {
                        @for r in shown_rules {
                            tr.active[r.get("active").and_then(Value::as_bool) == Some(true)]
                              .bad[r.get("met").and_then(Value::as_bool) == Some(false)] {
                                td { code { (text(r, "rule")) } } td { (text(r, "description")) }
                                td.num { (num(r.get("margin_mm"))) } td { (yes(r, "met")) } td { (yes(r, "active")) }
                            }
                        }
                    }
                }
                @if let Some((count, least)) = rest {
                    p.small { (count) " more rules met, none closer than " (significant(least, 3)) " mm to its limit." }
                }
            }
        }
    }
}

/// How many rules the table shows beyond the active and broken ones.
const NEAREST_RULES: usize = 5;

/// The rules a reviewer reads: the active and broken ones, then the nearest to their
/// limits, in the file's order; and the count of the rest with their least margin.
fn rules_to_show(rules: &[Value]) -> (Vec<&Value>, Option<(usize, f64)>) {
    let flag = |r: &Value, key: &str| r.get(key).and_then(Value::as_bool);
    let margin = |r: &Value| {
        r.get("margin_mm")
            .and_then(Value::as_f64)
            .unwrap_or(f64::INFINITY)
    };
    let binding = |r: &Value| flag(r, "active") == Some(true) || flag(r, "met") == Some(false);
    let mut others: Vec<usize> = (0..rules.len()).filter(|&i| !binding(&rules[i])).collect();
    others.sort_by(|&a, &b| {
        margin(&rules[a])
            .total_cmp(&margin(&rules[b]))
            .then(a.cmp(&b))
    });
    let hidden = others.split_off(others.len().min(NEAREST_RULES));
    let shown: Vec<&Value> = (0..rules.len())
        .filter(|&i| binding(&rules[i]) || others.contains(&i))
        .map(|i| &rules[i])
        .collect();
    let least = hidden
        .iter()
        .map(|&i| margin(&rules[i]))
        .fold(f64::INFINITY, f64::min);
    let rest = (!hidden.is_empty()).then_some((hidden.len(), least));
    (shown, rest)
}
