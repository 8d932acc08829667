//! Issue 51, item 5: a report a reviewer reads. The part rules' table shows the active and
//! broken rules and the nearest ones, and counts the rest; the refinement's deviation
//! column is labelled as what it holds; a network's drawing names each hinge's dimensions
//! once, counts its bodies in words and gives one legend entry per face name; `sweep` takes
//! its base design from an optimum's report.

use std::path::{Path, PathBuf};

use flexopt::part::{Annotation, Part};
use flexopt::problem::design::design_from_optimum;
use flexopt::problem::Problem;
use serde_json::Value;

use crate::common::{flexopt, flexopt_ok};

fn fresh(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexopt-review-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A copy of the committed set `results/NAME`, files only (the report reads no subfolder).
fn copied_set(name: &str, into: &Path) -> PathBuf {
    let to = into.join(name);
    std::fs::create_dir_all(&to).unwrap();
    for entry in std::fs::read_dir(Path::new("results").join(name)).unwrap() {
        let entry = entry.unwrap();
        if entry.file_type().unwrap().is_file() {
            std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
        }
    }
    to
}

/// The report of a copy of the committed set `results/NAME`, in `dir`: the set and its page.
fn reported(name: &str, dir: &Path) -> (PathBuf, String) {
    let set = copied_set(name, dir);
    flexopt_ok(&["report", set.to_str().unwrap()]);
    let html = std::fs::read_to_string(set.join("report.html")).unwrap();
    (set, html)
}

fn json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The rows of the table that follows `heading` in `html`.
fn rows_after<'a>(html: &'a str, heading: &str) -> Vec<&'a str> {
    let at = html
        .find(heading)
        .unwrap_or_else(|| panic!("no {heading:?}"));
    let table = &html[at..];
    let end = table.find("</table>").unwrap();
    let body = &table[table.find("<tbody>").unwrap()..end];
    body.split("<tr").skip(1).collect()
}

#[test]
fn the_rules_table_shows_the_active_and_nearest_rules_and_counts_the_rest() {
    let dir = fresh("rules");
    let (set, html) = reported("wei2017", &dir);
    let optimum = json(&set.join("optimum.json"));
    let rules = optimum["part_rules"].as_array().unwrap();
    let flag = |r: &Value, k: &str| r[k].as_bool().unwrap();
    let binds = |r: &Value| flag(r, "active") || !flag(r, "met");
    let binding: Vec<&Value> = rules.iter().filter(|r| binds(r)).collect();
    let mut others: Vec<f64> = rules
        .iter()
        .filter(|r| !binds(r))
        .map(|r| r["margin_mm"].as_f64().unwrap())
        .collect();
    others.sort_by(f64::total_cmp);
    assert!(rules.len() > 20 && others.len() > 5, "{}", rules.len());
    let rows = rows_after(&html, "The part's size rules");
    assert_eq!(rows.len(), binding.len() + 5);
    for r in &binding {
        let name = r["rule"].as_str().unwrap();
        assert!(
            rows.iter()
                .any(|row| row.contains(&format!("<code>{name}</code>"))),
            "{name} is not shown"
        );
    }
    // the nearest five are shown, and no farther rule is
    let shown_margins: Vec<f64> = rules
        .iter()
        .filter(|r| !binds(r))
        .filter(|r| {
            let name = r["rule"].as_str().unwrap();
            rows.iter()
                .any(|row| row.contains(&format!("<code>{name}</code>")))
        })
        .map(|r| r["margin_mm"].as_f64().unwrap())
        .collect();
    assert_eq!(shown_margins.len(), 5);
    assert!(
        shown_margins.iter().all(|&m| m <= others[4]),
        "{shown_margins:?}"
    );
    let said = format!("{} more rules met, none closer than", others.len() - 5);
    assert!(html.contains(&said), "no {said:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_refinements_deviation_column_says_what_it_holds() {
    let dir = fresh("deviation");
    let (set, html) = reported("wei2017_refined", &dir);
    assert!(html.contains("(model − FE) / FE"));
    assert!(!html.contains("model over FE"));
    // the column holds (model - FE) / FE, as refined.json gives it
    let refined = json(&set.join("refined.json"));
    let amp = refined["refined"]["outputs"]
        .as_array()
        .unwrap()
        .iter()
        .find(|o| o["output"] == "amplification")
        .unwrap();
    let (model, fe) = (
        amp["analytic"].as_f64().unwrap(),
        amp["measured"].as_f64().unwrap(),
    );
    assert!(((model - fe) / fe - amp["deviation"].as_f64().unwrap()).abs() < 1e-12);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_networks_drawing_names_each_hinges_dimensions_and_counts_in_words() {
    for (file, set, described) in [
        ("problems/lever_network.toml", "lever_network", 1),
        ("problems/wei2017_network.toml", "wei2017_network", 2),
    ] {
        let problem = Problem::load(Path::new(file)).unwrap();
        let optimum = Path::new("results").join(set).join("optimum.json");
        let x = design_from_optimum(&problem, &optimum).unwrap().x;
        let spec = problem.mechanism().part_spec(&x).unwrap().unwrap();
        let part = Part::build(&spec).unwrap();
        let notes: Vec<&str> = part
            .annotations
            .iter()
            .filter_map(|a| match a {
                Annotation::Note { label, .. } => Some(label.as_str()),
                Annotation::Length { .. } => None,
            })
            .collect();
        // one note per hinge of the described part, none for its mirror images
        assert!(part.hinges.len() >= notes.len());
        assert_eq!(notes.len(), described, "{file}: {notes:?}");
        for h in part.hinges.iter().filter(|h| !h.name.ends_with(')')) {
            let t = format!("{} t {}", h.name, flexopt::part::mm::length(h.thickness));
            assert!(
                notes.iter().any(|n| n.starts_with(&t)),
                "{file}: no {t:?} in {notes:?}"
            );
        }
        assert!(!part.caption.contains("1 bodies") && !part.caption.contains("1 hinges"));
    }
    let lever = Problem::load(Path::new("problems/lever_network.toml")).unwrap();
    let x = design_from_optimum(&lever, Path::new("results/lever_network/optimum.json"))
        .unwrap()
        .x;
    let part = Part::build(&lever.mechanism().part_spec(&x).unwrap().unwrap()).unwrap();
    assert!(part.caption.contains("1 hinge"), "{}", part.caption);
    assert!(!part.caption.contains("1 hinges"), "{}", part.caption);
}

#[test]
fn sweep_takes_its_base_design_from_an_optimum_and_marks_it_within_range() {
    let dir = fresh("sweep");
    let optimum = "results/wei2017/optimum.json";
    let out = dir.join("sweep");
    let o = out.to_str().unwrap();
    let base = "sweep problems/wei2017.toml --param l3 --steps 5 --from 10 --to 20 --optimum";
    let mut args: Vec<&str> = base.split(' ').collect();
    args.extend([optimum, "--out", o]);
    flexopt_ok(&args);
    let sweep = json(&out.join("l3.json"));
    let design = json(Path::new(optimum))["design"].clone();
    for (name, v) in sweep["around"].as_object().unwrap() {
        let want = design[name].as_f64().unwrap();
        let got = v.as_f64().unwrap();
        assert!(
            (got - want).abs() <= 1e-12 * want.abs().max(1.0),
            "{name}: {got} vs {want}"
        );
    }
    // both ways of giving the base design at once are refused, and nothing is written
    let other = dir.join("other");
    let mut both: Vec<&str> = base.split(' ').collect();
    let o2 = other.to_str().unwrap();
    both.extend([optimum, "--around", "l3=12", "--out", o2]);
    let refused = flexopt(&both);
    assert_eq!(refused.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("--optimum"));
    assert!(!other.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
