//! The report's sections, each from the set's JSON as written: values in SI are shown in the
//! unit the file chose for them or a designer's usual one, to the digits that matter.

use maud::{html, Markup};
use serde_json::Value;

use super::constraints::constraint_table;
use super::{ProblemText, Set, TOLERANCE, VERIFY};
use crate::problem::display::{human, significant};
use crate::vocab::units::{tables, Unit};

pub(super) fn num(v: Option<&Value>) -> String {
    v.and_then(Value::as_f64).map_or("–".into(), human)
}

pub(super) fn text<'a>(v: &'a Value, key: &str) -> &'a str {
    v.get(key).and_then(Value::as_str).unwrap_or("–")
}

pub(super) fn list<'a>(v: Option<&'a Value>, key: &str) -> &'a [Value] {
    v.and_then(|v| v.get(key))
        .and_then(Value::as_array)
        .map_or(&[], Vec::as_slice)
}

pub(super) fn yes(v: &Value, key: &str) -> &'static str {
    match v.get(key).and_then(Value::as_bool) {
        Some(true) => "yes",
        Some(false) => "no",
        None => "–",
    }
}

/// The unit a value given in the SI unit `si` is shown in (`display` where it is one of that
/// dimension's units, else the designer's usual one), with its factor from SI.
pub(super) fn shown(si: &str, display: Option<&str>) -> Unit {
    tables()
        .iter()
        .find(|(_, units)| units.iter().any(|&(n, f)| n == si && f == 1.0))
        .map_or(
            Unit {
                name: si.to_string(),
                dimension: crate::vocab::Dimension::Ratio,
                to_si: 1.0,
            },
            |&(d, _)| Unit::shown(d, display),
        )
}

/// `value` (SI, in `si`) in the unit [`shown`] gives, and that unit's name.
pub(super) fn in_unit(value: Option<&Value>, si: &str, display: Option<&str>) -> (String, String) {
    let unit = shown(si, display);
    let v = value
        .and_then(Value::as_f64)
        .map_or("–".into(), |v| human(unit.from_si(v)));
    (v, unit.name)
}

/// A constraint's limits as the problem states them: `7.5 mm <= span_x <= 12 mm`.
pub(super) fn limits(c: &Value) -> String {
    let unit = text(c, "unit");
    let unit = if unit == "1" { "" } else { unit };
    let bound = |k: &str| c.get(k).and_then(Value::as_f64).map(human);
    let output = text(c, "output");
    match (bound("lower"), bound("upper")) {
        (Some(l), Some(u)) => format!("{l} {unit} ≤ {output} ≤ {u} {unit}"),
        (Some(l), None) => format!("{output} ≥ {l} {unit}"),
        (None, Some(u)) => format!("{output} ≤ {u} {unit}"),
        (None, None) => output.to_string(),
    }
}

pub(super) fn figure(set: &Set, name: &str, caption: &str) -> Markup {
    html! {
        @if let Some(uri) = set.picture(name) {
            figure {
                img src=(uri) alt=(caption);
                figcaption { (caption) " (" code { (name) } ")" }
            }
        }
    }
}

fn part_facts(part: &Value) -> Markup {
    let bb: Vec<f64> = list(Some(part), "bounding_box")
        .iter()
        .filter_map(Value::as_f64)
        .collect();
    html! {
        p {
            "Plate thickness (the part's width out of the plane) "
            strong { (num(part.get("width"))) " mm" }
            @if let [x0, y0, x1, y1] = bb[..] {
                "; outline " (human(x1 - x0)) " mm × " (human(y1 - y0)) " mm"
            }
            "; area " (num(part.get("area"))) " mm²."
        }
        table {
            thead { tr { th { "hinge" } th { "kind" } th.num { "length, mm" } th.num { "least thickness, mm" } th.num { "root, mm" } th.num { "fillet, mm" } } }
            tbody {
                @for h in list(Some(part), "hinges") {
                    @let ends: Vec<f64> = ["start", "end"].iter().flat_map(|k| list(Some(h), k)).filter_map(Value::as_f64).collect();
                    tr {
                        td { (text(h, "name")) } td { (text(h, "kind")) }
                        td.num { @if let [a, b, c, d] = ends[..] { (human((c - a).hypot(d - b))) } }
                        td.num { (num(h.get("thickness"))) } td.num { (num(h.get("root"))) }
                        td.num { (num(h.get("fillet"))) }
                    }
                }
            }
        }
    }
}

pub(super) fn part(set: &Set) -> Markup {
    html! {
        section #part {
            h2 { "The part" }
            @match &set.part {
                Some(part) => {
                    (figure(set, "part.png", "The part, dimensioned (mm)"))
                    (part_facts(part))
                    p.small { "For the shop: " code { "part.dxf" } " (outline, plate thickness on layer PLATE), "
                        code { "part.svg" } ", " code { "part.json" } "; for mechanical CAD: "
                        code { "part.step" } " (the solid, the outline extruded through the plate thickness)." }
                }
                None => p.note { "The set holds no part: the model has none, or the optimum's cannot be made (optimum.json names why)." },
            }
        }
    }
}

/// The FE check's idealizations as verify.json names them, with their headings.
const IDEALIZATIONS: [(&str, &str); 3] = [
    ("plane_stress", "plane stress"),
    ("plane_strain", "plane strain"),
    ("3d", "3D"),
];

/// The outputs whose model value is off the part's by more than 5 % beyond the FE's error
/// (`verdict.model_off` of verify.json), as one sentence.
fn model_off(v: &Value) -> Option<String> {
    let gaps = v.get("verdict")?.get("model_off")?.as_array()?;
    if gaps.is_empty() {
        return None;
    }
    let each: Vec<String> = gaps
        .iter()
        .map(|g| {
            let d = g
                .get("deviation_percent")
                .and_then(Value::as_f64)
                .unwrap_or(f64::NAN);
            format!("{} {:+.1} %", text(g, "output"), d)
        })
        .collect();
    Some(format!(
        "(model − FE) / FE is {} in the {} column, more than 5 % beyond the FE's error. The \
         model's rigid links and blocks and its hinge formulas (within their ranges of fit) \
         are its idealization; here the part departs from it: judge by the FE, or refine \
         against it (run --refine fe).",
        each.join(", "),
        match text(v.get("verdict")?, "fidelity") {
            "3d" => "3D".to_string(),
            f => f.replace('_', " "),
        }
    ))
}

pub(super) fn fe_check(set: &Set) -> Markup {
    let Some((v, _)) = &set.verify else {
        return html! {
            section #fe {
                h2 { "Finite-element check" }
                p.note { (set.verify_skipped.as_deref().unwrap_or(
                    "The set holds no finite-element check of the optimum: run with --verify \
                     (or flexopt verify PROBLEM --optimum optimum.json --out DIR/verify).")) }
            }
        };
    };
    let read = text(v, "read");
    let outputs = v.get("outputs");
    let columns: Vec<(&str, &str)> = IDEALIZATIONS
        .into_iter()
        .filter(|(k, _)| outputs.and_then(|o| o.get(*k)).is_some())
        .collect();
    let names = &set.order.fe;
    let read_heading = columns
        .iter()
        .find(|(k, _)| *k == read)
        .map_or(read, |(_, h)| *h);
    html! {
        section #fe {
            h2 { "Finite-element check of the optimum's part" }
            p {
                "The " @if v.get("whole_part").and_then(Value::as_bool) == Some(true) { "whole" } @else { "half" } " part meshed and solved in " (columns.len()) " idealizations, each output's
                discretization error estimated over refined meshes (tolerance "
                (num(v.get("tolerance"))) ", " @if v.get("converged").and_then(Value::as_bool) == Some(true) { "reached" } @else { strong.bad { "not reached" } } ")."
                " The plate's width over its thinnest hinge is " (num(v.get("width_over_thickness")))
                ": " strong { "read the " (read_heading) " column" } " (shaded); the others bound it."
            }
            p.small {
                "Each cell: the FE value, ± its estimated relative error, and the model's deviation \
                 from it ((model − FE) / FE). Test force " (num(v.get("test_force"))) " N; the force \
                 the actuator needs for its stroke: model " (num(v.get("analytic_actuation_force"))) " N"
                @for (k, h) in &columns {
                    ", " (h) " " (num(v.get("actuation_force").and_then(|a| a.get(*k)))) " N"
                }
                "."
            }
            table.fe {
                thead { tr {
                    th { "output" } th { "unit" } th.num { "model" }
                    @for (k, h) in &columns { th.num.read[*k == read] { (h) } }
                } }
                tbody {
                    @for name in names {
                        @let first = columns.iter().find_map(|(k, _)| outputs?.get(*k)?.get(name.as_str()));
                        @let si = first.map_or("", |f| text(f, "unit"));
                        @let display = first.and_then(|f| f.get("display_unit")).and_then(Value::as_str);
                        tr {
                            td { code { (name) } br; span.small { (first.map_or("", |f| text(f, "meaning"))) } }
                            td { (shown(si, display).name) }
                            td.num { (in_unit(first.and_then(|f| f.get("analytic")), si, display).0) }
                            @for (k, _) in &columns {
                                @let cell = outputs.and_then(|o| o.get(*k)).and_then(|o| o.get(name.as_str()));
                                td.num.read[*k == read] {
                                    @if let Some(c) = cell {
                                        (in_unit(c.get("value"), si, display).0) br;
                                        span.small {
                                            "± " (c.get("relative_error").and_then(Value::as_f64).map_or("–".into(), |e| significant(100.0 * e, 2))) " %"
                                            @if let Some(d) = c.get("deviation_percent").and_then(Value::as_f64) {
                                                ", dev. " (significant(d, 3)) " %"
                                            }
                                            @if c.get("converging").and_then(Value::as_bool) == Some(false) { ", not converging" }
                                        }
                                        @if let Some(at) = c.get("at").and_then(Value::as_str) { br; span.small { (at) } }
                                    } @else { "–" }
                                }
                            }
                        }
                    }
                }
            }
            @if let Some(off) = model_off(v) {
                p { strong.bad { "The model does not hold on this part: " } (off) }
            }
            (figure(set, &format!("{VERIFY}/stress.png"), "Von Mises stress under the actuation"))
            (figure(set, &format!("{VERIFY}/deformed.png"), "The part deformed under the test force"))
            p.small { "CalculiX decks of the same meshes for an independent check: "
                code { "verify/part.inp" } ", " code { "verify/part3d.inp" } "." }
        }
    }
}

pub(super) fn refinement(set: &Set) -> Markup {
    let Some(r) = &set.refined else {
        return html! {};
    };
    let refined = r.get("refined");
    let start = r.get("analytic_optimum");
    let design_of = |d: Option<&Value>| d.and_then(|d| d.get("design")).cloned();
    let (a, b) = (design_of(start), design_of(refined));
    let settings = r.get("settings");
    html! {
        section #refinement {
            h2 { "Refinement against the part" }
            p {
                "Fidelity: " (text(r, "fidelity")) ". Status " strong { (text(r, "status")) }
                ", converged " (yes(r, "converged")) ", feasible " (yes(r, "feasible")) ", after "
                (num(r.get("measurements"))) " FE checks (at most " (num(settings.and_then(|s| s.get("max_fe")))) ", tolerance "
                (num(settings.and_then(|s| s.get("tolerance")))) ", stress " (settings.map_or("–", |s| text(s, "stress"))) ")."
            }
            table {
                thead { tr { th { "variable" } th.num { "analytic optimum" } th.num { "refined" } } }
                tbody {
                    @for name in set.order.design.keys() {
                        tr { td { code { (name) } } td.num { (num(a.as_ref().and_then(|a| a.get(name)))) }
                             td.num { (num(b.as_ref().and_then(|b| b.get(name)))) } }
                    }
                }
            }
            h3 { "The refined design's outputs: model and FE" }
            table {
                thead { tr { th { "output" } th { "unit" } th.num { "model" } th.num { "FE" } th.num { "FE error" } th.num { "(model − FE) / FE" } } }
                tbody {
                    @for out in list(refined, "outputs") {
                        tr {
                            td { code { (text(out, "output")) } } td { (text(out, "unit")) }
                            td.num { (num(out.get("analytic"))) } td.num { (num(out.get("measured"))) }
                            td.num { (num(out.get("error"))) } td.num { (num(out.get("deviation"))) }
                        }
                    }
                }
            }
            h3 { "The refined design's constraints, as measured" }
            (constraint_table(list(refined, "constraints")))
            (figure(set, "refined_part.png", "The refined part, dimensioned (mm)"))
            @if let Some(p) = &set.refined_part { (part_facts(p)) }
        }
    }
}

/// A fraction as a percentage, to two decimals.
fn percent(v: Option<&Value>) -> String {
    v.and_then(Value::as_f64)
        .map_or("–".into(), |f| format!("{:.2} %", 100.0 * f))
}

/// An output's unit as shown beside its value (none for a ratio).
fn unit_of(out: &Value) -> &str {
    match text(out, "unit") {
        "1" | "–" => "",
        unit => unit,
    }
}

/// The tolerance that drives most of an output's variance, with its share.
fn largest_share(out: &Value) -> String {
    let shares = out.get("shares").and_then(Value::as_object);
    let top = shares.and_then(|m| {
        m.iter()
            .filter_map(|(k, v)| Some((k, v.as_f64()?)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
    });
    top.map_or("–".into(), |(k, v)| format!("{k} {:.1} %", 100.0 * v))
}

/// A robust run's two optima side by side (`robust.json`).
fn robust_comparison(r: &Value) -> Markup {
    let nominal = r.get("nominal");
    let robust = r.get("robust");
    let target = match r.get("target_yield").and_then(Value::as_f64) {
        Some(y) => format!("a yield of {:.2} %", 100.0 * y),
        None => format!("{} standard deviations", num(r.get("k_sigma"))),
    };
    let yield_of = |side: Option<&Value>| {
        let interval = list(side, "yield_interval");
        format!(
            "{} ({} .. {})",
            percent(side.and_then(|s| s.get("yield"))),
            percent(interval.first()),
            percent(interval.get(1))
        )
    };
    let margins = robust
        .and_then(|s| s.get("margins_in_sigma"))
        .and_then(Value::as_object);
    html! {
        h3 { "The robust optimum beside the nominal one" }
        p { "Each constraint and each rule of the part tightened by its first-order spread at the design, for " (target)
            "; yields by Monte Carlo on " (num(r.get("samples"))) " samples (seed " (num(r.get("seed"))) ")." }
        table {
            thead { tr { th { "" } th.num { "nominal" } th.num { "robust" } } }
            tbody {
                tr { td { "objective" } td.num { (num(nominal.and_then(|s| s.get("objective")))) } td.num { (num(robust.and_then(|s| s.get("objective")))) } }
                tr { td { "yield (95 % interval)" } td.num { (yield_of(nominal)) } td.num { (yield_of(robust)) } }
                tr { td { "cannot be made (breaks a rule of the part)" }
                     td.num { (percent(nominal.and_then(|s| s.get("unmakeable")))) }
                     td.num { (percent(robust.and_then(|s| s.get("unmakeable")))) } }
                @if let Some(m) = margins {
                    @for (name, v) in m {
                        tr { td { "margin of " code { (name) } ", standard deviations" }
                             td.num { (num(nominal.and_then(|s| s.get("margins_in_sigma")).and_then(|n| n.get(name)))) }
                             td.num { (num(Some(v))) } }
                    }
                }
            }
        }
    }
}

pub(super) fn tolerances(set: &Set) -> Markup {
    if set.tolerance.is_none() && set.robust.is_none() && set.tolerance_skipped.is_none() {
        return html! {};
    }
    let t = set.tolerance.as_ref().map(|(v, _)| v);
    let outputs = list(t, "outputs");
    let interval = list(t, "yield_interval");
    html! {
        section #tolerances {
            h2 { "Machining tolerances and yield" }
            @if let Some(r) = &set.robust { (robust_comparison(r)) }
            @if let Some(note) = &set.tolerance_skipped { p.note { (note) } }
            @if let Some(t) = t {
                p {
                    "The optimum under its tolerances: " strong { (percent(t.get("yield"))) }
                    " of " (num(t.get("samples"))) " Monte Carlo parts can be made and meet every constraint ("
                    (text(t, "interval_method")) " interval " (percent(interval.first())) " .. "
                    (percent(interval.get(1))) "; seed " (num(t.get("seed"))) ")."
                    @if t.get("rules_broken").and_then(Value::as_object).is_some_and(|r| !r.is_empty()) {
                        " " (percent(t.get("unmakeable"))) " cannot be made: their part breaks one of \
                        the part's rules or more, and the yield counts them as failed."
                    }
                }
                p.small { "σ: the standard deviation, to first order from the exact gradients and by Monte \
                    Carlo (MC); in limits: the share of parts within the output's limits (– for the \
                    objective); the variance share: the tolerance that drives most of the output's spread." }
                table {
                    thead { tr { th { "tolerance" } th.num { "±" } th.num { "σ" } th { "unit" } th { "distribution" } th { "from" } } }
                    tbody {
                        @for tol in list(Some(t), "tolerances") {
                            tr { td { code { (text(tol, "name")) } } td.num { (num(tol.get("plus_minus"))) }
                                 td.num { (num(tol.get("sigma"))) } td { (text(tol, "unit")) }
                                 td { (text(tol, "distribution")) } td { (text(tol, "origin")) } }
                        }
                    }
                }
                table {
                    thead { tr { th { "output" } th.num { "nominal" } th.num { "σ 1st order" }
                                 th.num { "σ MC" } th.num { "in limits: 1st order, MC" }
                                 th { "largest variance share" } } }
                    tbody {
                        @for out in outputs {
                            tr {
                                td { code { (text(out, "name")) } }
                                td.num { (num(out.get("nominal"))) " " (unit_of(out)) }
                                td.num { (num(out.get("std"))) }
                                td.num { (num(out.get("monte_carlo").and_then(|m| m.get("std")))) }
                                td.num { (percent(out.get("first_order_yield"))) ", "
                                    (percent(out.get("monte_carlo_yield"))) }
                                td { (largest_share(out)) }
                            }
                        }
                    }
                }
                @for out in outputs.iter().filter(|o| o.get("role").and_then(Value::as_str) == Some("constraint")) {
                    (figure(set, &format!("{TOLERANCE}/histogram_{}.png", text(out, "name")),
                        &format!("{} over the Monte Carlo parts, its limits marked", text(out, "name"))))
                }
            }
        }
    }
}

pub(super) fn files(set: &Set) -> Markup {
    let check = set.check_files(VERIFY);
    let in_set = set.files.iter().any(|e| e.name == VERIFY && e.folder);
    let tolerance = set.check_files(TOLERANCE);
    html! {
        section #files {
            h2 { "The files of the set" }
            p.small { "As manifest.json lists them: size and FNV-1a 64-bit hash of each, to tell a file of this set from another's." }
            table.files {
                thead { tr { th { "file" } th.num { "bytes" } th { "fnv1a64" } } }
                tbody {
                    @for e in set.files.iter().filter(|e| !e.folder) {
                        tr { td { code { (e.name) } } td.num { (e.bytes.map_or(String::new(), |b| b.to_string())) } td { code { (e.fnv1a64.as_deref().unwrap_or("")) } } }
                    }
                    @for (folder, e) in check.iter().map(|e| (VERIFY, e)).chain(tolerance.iter().map(|e| (TOLERANCE, e))) {
                        tr { td { code { (folder) "/" (e.name) } } td.num { (e.bytes.map_or(String::new(), |b| b.to_string())) } td { code { (e.fnv1a64.as_deref().unwrap_or("")) } } }
                    }
                }
            }
            @if !check.is_empty() && !in_set {
                p.small { code { (VERIFY) "/" } " is a set of its own (written by " code { "flexopt verify" } "), listed by its own manifest." }
            }
            @if !tolerance.is_empty() {
                p.small { code { (TOLERANCE) "/" } " is a set of its own (written by " code { "flexopt tolerance" } "), listed by its own manifest." }
            }
        }
    }
}

pub(super) fn reproduce(set: &Set, problem: Option<&ProblemText>) -> Markup {
    let o = &set.optimum;
    let file = problem.map_or("PROBLEM.toml", |p| p.path.as_str());
    let mut command = format!(
        "flexopt run {file} --seed {} --starts {} --solver {}",
        num(o.get("seed")),
        num(o.get("starts")),
        text(o, "solver")
    );
    if set.refined.is_some() {
        command.push_str(" --refine fe");
    }
    if set.files.iter().any(|e| e.name == VERIFY && e.folder) {
        command.push_str(" --verify");
    }
    html! {
        section #reproduce {
            h2 { "To reproduce it" }
            p { "flexopt " (env!("CARGO_PKG_VERSION")) ", with the problem file whose content hashes to "
                code { (text(o, "problem_fnv1a64")) } ":" }
            pre { (command) " --report" }
            p.small { "Starts are seeded by their index: the thread count does not change a result." }
        }
    }
}
