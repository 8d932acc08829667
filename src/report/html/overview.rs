//! The report's front: its heading (the verdict), the problem as stated, and the optimum with
//! its zones.

use maud::{html, Markup};
use serde_json::Value;

use super::sections::{figure, in_unit, limits, list, num, text};
use super::{ProblemText, Set};

/// The objective's value at the optimum in the unit its output is shown in, with the unit.
fn objective_value(o: &Value) -> String {
    let output = text(o, "objective_output");
    let of = |key: &str| {
        o.get(key)
            .and_then(|u| u.get(output))
            .and_then(Value::as_str)
    };
    let (value, unit) = in_unit(
        o.get("objective"),
        of("output_units").unwrap_or(""),
        of("display_units"),
    );
    match unit.as_str() {
        "" | "1" => value,
        _ => format!("{value} {unit}"),
    }
}

fn objective_line(o: &Value) -> String {
    let output = text(o, "objective_output");
    let output = if o.get("absolute").and_then(Value::as_bool) == Some(true) {
        format!("|{output}|")
    } else {
        output.to_string()
    };
    format!("{} {output}", text(o, "sense"))
}

/// The fidelity of the optimum's FE check (`run --verify`) and what its part fails there, if
/// it fails anything.
fn part_fails(set: &Set) -> Option<(String, Vec<String>)> {
    let verdict = set.verify.as_ref()?.0.get("verdict")?;
    let fails: Vec<String> = list(Some(verdict), "fails")
        .iter()
        .map(|f| text(f, "shown").to_string())
        .collect();
    (!fails.is_empty()).then(|| (fidelity_name(verdict), fails))
}

fn fidelity_name(verdict: &Value) -> String {
    match text(verdict, "fidelity") {
        "3d" => "3D".into(),
        f => f.replace('_', " "),
    }
}

/// What a feasible optimum's verdict is judged by: the model, or the model and its part's FE
/// check, naming the constraints that check does not measure.
fn judged_by(set: &Set) -> String {
    let Some(verdict) = set.verify.as_ref().and_then(|(v, _)| v.get("verdict")) else {
        return "judged by the model".into();
    };
    let model_only: Vec<&str> = list(Some(verdict), "model_only")
        .iter()
        .filter_map(Value::as_str)
        .collect();
    let mut s = format!(
        "in the model and on its part by the {} finite elements",
        fidelity_name(verdict)
    );
    if !model_only.is_empty() {
        s += &format!("; model only: {}", model_only.join(", "));
    }
    s
}

/// The refinement's verdict (`refined.json`), where the set holds one: what its refined
/// design meets on the part, or what the least violating one misses there, as refined.json
/// says.
fn refinement_line(set: &Set) -> Option<Markup> {
    let r = set.refined.as_ref()?;
    let fidelity = text(r, "fidelity");
    let misses: Vec<String> = list(r.get("refined"), "constraints")
        .iter()
        .filter(|c| c.get("satisfied").and_then(Value::as_bool) == Some(false))
        .map(|c| {
            format!(
                "{} = {} {}",
                text(c, "output"),
                num(c.get("value")),
                text(c, "unit")
            )
        })
        .collect();
    let feasible = r.get("feasible").and_then(Value::as_bool) == Some(true);
    Some(html! {
        "Refined against its part (" (fidelity) "): "
        @if feasible {
            "the refined design meets every constraint as measured"
            @if r.get("converged").and_then(Value::as_bool) != Some(true) { " (not converged)" }
            "."
        } @else {
            strong.bad { "no design the refinement checked meets every constraint on the part" }
            "; the least violating one (refined.json) misses " (misses.join(", ")) "."
        }
    })
}

pub(super) fn heading(set: &Set) -> Markup {
    let o = &set.optimum;
    let feasible = o.get("feasible").and_then(Value::as_bool) == Some(true);
    html! {
        header {
            h1 { "Design report: " (text(o, "problem")) }
            p.lead {
                "Model " strong { (text(o, "model")) } ". "
                @if let Some((fidelity, fails)) = part_fails(set).filter(|_| feasible) {
                    "The optimum meets every constraint in the model, but "
                    strong.bad { "its part fails by the " (fidelity) " finite elements" } ": "
                    @for (i, f) in fails.iter().enumerate() {
                        @if i > 0 { "; " }
                        (f)
                    }
                    ". " (objective_line(o)) " = " strong { (objective_value(o)) } " (model)."
                } @else if feasible {
                    "The optimum meets every constraint (" (judged_by(set)) "): " (objective_line(o)) " = "
                    strong { (objective_value(o)) } ", zone " (num(o.get("zone")))
                    ", configuration " (text(o, "configuration")) "."
                } @else {
                    strong.bad { "No start ended feasible" }
                    ": the design below is the least violating one."
                }
                @if let Some(line) = refinement_line(set) { " " (line) }
            }
            p.small {
                "Written by flexopt " (env!("CARGO_PKG_VERSION")) " from the set's files; seed " (num(o.get("seed"))) ", " (num(o.get("starts"))) " starts, solver "
                (text(o, "solver")) ", problem file content " code { (text(o, "problem_fnv1a64")) }
                " (FNV-1a of its data)."
            }
        }
    }
}

pub(super) fn problem(set: &Set, problem: Option<&ProblemText>) -> Markup {
    let o = &set.optimum;
    let units = o.get("design_units");
    html! {
        section #problem {
            h2 { "The problem" }
            p { "Objective: " strong { (objective_line(o)) } "." }
            p { "Constraints:" }
            ul {
                @for c in list(Some(o), "constraints") { li { (limits(c)) } }
            }
            p {
                "Design variables (in the file's units): "
                @for (i, name) in set.order.design.keys().enumerate() {
                    @if i > 0 { ", " }
                    code { (name) } " [" (units.and_then(|u| u.get(name)).and_then(Value::as_str).unwrap_or("")) "]"
                }
                "."
            }
            @match problem {
                Some(p) => p { "The problem file as stated, " code { (p.path) } ", is the "
                    a href="#problem-file" { "last section" } "." },
                None => p.note {
                    "The problem file is not part of the set; "
                    code { "flexopt report DIR --problem FILE" }
                    " adds it, checked against the content the run read."
                },
            }
        }
    }
}

pub(super) fn problem_file(problem: Option<&ProblemText>) -> Markup {
    html! {
        @if let Some(p) = problem {
            section #problem-file {
                h2 { "The problem file" }
                p { code { (p.path) } ", as the run read it:" }
                pre.source { (p.text) }
            }
        }
    }
}

pub(super) fn optimum(set: &Set) -> Markup {
    let o = &set.optimum;
    let design = o.get("design");
    let units = o.get("design_units");
    let outputs = o.get("outputs");
    let ends = o.get("ends");
    html! {
        section #optimum {
            h2 { "The optimum" }
            div.columns {
                div {
                    table {
                        thead { tr { th { "variable" } th.num { "value" } th { "unit" } } }
                        tbody {
                            @for name in set.order.design.keys() {
                                tr {
                                    td { code { (name) } }
                                    td.num { (num(design.and_then(|d| d.get(name)))) }
                                    td { (units.and_then(|u| u.get(name)).and_then(Value::as_str).unwrap_or("")) }
                                }
                            }
                        }
                    }
                    p {
                        "The local solve from start " (num(o.get("start"))) " ended "
                        (o.get("status").map_or("–", |s| text(s, "status")))
                        " after " (num(o.get("iterations"))) " iterations (KKT residual "
                        (num(o.get("kkt_residual"))) "). Of the starts, "
                        @if let Some(e) = ends {
                            (num(e.get("converged"))) " converged, " (num(e.get("iteration_limit")))
                            " hit the iteration limit, " (num(e.get("infeasible"))) " ended infeasible and "
                            (num(e.get("failed"))) " failed."
                        }
                    }
                    @if let Some(z) = &set.zones {
                        h3 { "Zones of the optima" }
                        table {
                            thead { tr { th { "zone" } th.num { "from" } th.num { "to" } th.num { "starts" } th.num { "best" } th.num { "optima" } } }
                            tbody {
                                @for zone in list(Some(z), "zones") {
                                    tr {
                                        td { (num(zone.get("rank"))) }
                                        td.num { (num(zone.get("low"))) }
                                        td.num { (num(zone.get("high"))) }
                                        td.num { (num(zone.get("count"))) }
                                        td.num { (num(zone.get("best"))) }
                                        td.num { (list(Some(zone), "optima").len()) }
                                    }
                                }
                            }
                        }
                        @if let Some(rule) = z.get("configuration_rule").and_then(Value::as_str) {
                            p.small { "Configurations: " (rule) }
                        }
                    }
                }
                table {
                    thead { tr { th { "output" } th.num { "value" } th { "unit" } } }
                    tbody {
                        @for name in set.order.outputs.keys() {
                            @let v = outputs.and_then(|d| d.get(name));
                            @let si = o.get("output_units").and_then(|u| u.get(name)).and_then(Value::as_str).unwrap_or("");
                            @let display = o.get("display_units").and_then(|u| u.get(name)).and_then(Value::as_str);
                            @let (value, unit) = in_unit(v, si, display);
                            tr { td { code { (name) } } td.num { (value) } td { (unit) } }
                        }
                    }
                }
            }
            (figure(set, "zones.png", "The starts' objectives by zone"))
            (figure(set, "configurations.png", "Each zone's optima, to scale"))
        }
    }
}
