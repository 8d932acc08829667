//! `report.html`: a run's set of files as one self-contained page for a design review: the
//! problem, the optimum and its zone, every constraint, the part, the FE check, the
//! refinement, the tolerances and the robust optimum, the files with their hashes and what reproduces them. It reads the set's JSON
//! files and embeds its pictures (base64 data URIs): nothing is recomputed, nothing is
//! fetched, no script runs, and the page carries no time, so that the same set gives the same
//! bytes.

mod constraints;
mod overview;
mod sections;
mod shape;
pub use shape::check_optimum;

use std::path::{Path, PathBuf};

use base64::Engine;
use indexmap::IndexMap;
use maud::{html, Markup, PreEscaped, DOCTYPE};
use serde::de::IgnoredAny;
use serde::Deserialize;
use serde_json::Value;

use super::folder::{self, Entry, OutputSet};
use super::WriteError;
use crate::vocab::input::MAX_SET_FILE_BYTES;

/// The report's file name in a set.
pub const REPORT: &str = "report.html";

/// The folder of `run --verify`'s check (and of a `verify --out DIR/verify` beside a run).
const VERIFY: &str = "verify";

/// The folder of `flexopt tolerance --optimum DIR/optimum.json`'s check (its default `--out`).
const TOLERANCE: &str = "tolerance";

/// The problem file a report states, as its text.
pub struct ProblemText {
    /// As the user named it.
    pub path: String,
    pub text: String,
}

/// The set a report is made of: its folder (in place, or the staging folder of `run
/// --report`), what its manifest lists, and the JSON files read from it.
struct Set {
    dir: PathBuf,
    files: Vec<Entry>,
    optimum: Value,
    zones: Option<Value>,
    part: Option<Value>,
    refined_part: Option<Value>,
    refined: Option<Value>,
    /// The check in `verify/`, with the files of its own manifest; only when it checked the
    /// optimum's design (a folder left by a check of another design is not this run's).
    verify: Option<(Value, Vec<Entry>)>,
    /// Why a `verify/` folder there is not shown, when it is not.
    verify_skipped: Option<String>,
    /// The tolerance check in `tolerance/`, with its own files; only of the optimum's design.
    tolerance: Option<(Value, Vec<Entry>)>,
    /// Why a `tolerance/` folder there is not shown, when it is not.
    tolerance_skipped: Option<String>,
    /// A robust run's optimum beside the nominal one (`robust.json`).
    robust: Option<Value>,
    /// The keys of the maps the report walks, in the order the files hold them (a parsed
    /// `Value` sorts them): the design's variables, the optimum's outputs, the FE outputs.
    order: Order,
}

#[derive(Default, Deserialize)]
struct Order {
    #[serde(default)]
    design: IndexMap<String, IgnoredAny>,
    #[serde(default)]
    outputs: IndexMap<String, IgnoredAny>,
    #[serde(skip)]
    fe: Vec<String>,
}

#[derive(Default, Deserialize)]
struct FeOrder {
    #[serde(default)]
    outputs: IndexMap<String, IndexMap<String, IgnoredAny>>,
}

fn read_text(path: &Path) -> Result<String, String> {
    crate::vocab::input::read_text(path, MAX_SET_FILE_BYTES, "a file of a set")
        .map_err(|e| format!("{}: {e}", path.display()))
}

fn parse<T: serde::de::DeserializeOwned>(path: &Path, text: &str) -> Result<T, String> {
    serde_json::from_str(text)
        .map_err(|e| format!("{}: not JSON flexopt wrote: {e}", path.display()))
}

fn read_json(path: &Path) -> Result<Value, String> {
    parse(path, &read_text(path)?)
}

impl Set {
    fn read(dir: &Path, files: Vec<Entry>) -> Result<Set, String> {
        let listed = |name: &str| files.iter().any(|e| e.name == name);
        let optional = |name: &str| -> Result<Option<Value>, String> {
            if listed(name) {
                read_json(&dir.join(name)).map(Some)
            } else {
                Ok(None)
            }
        };
        if !listed("optimum.json") {
            return Err(format!(
                "{}: its manifest lists no optimum.json: a report is made of a run's folder \
                 (flexopt run), not of an export's, a verification's or a sweep's",
                dir.display()
            ));
        }
        let path = dir.join("optimum.json");
        let text = read_text(&path)?;
        let optimum = parse(&path, &text)?;
        shape::check_optimum(&text).map_err(|e| {
            format!(
                "{}: not the optimum.json flexopt writes: {e}",
                path.display()
            )
        })?;
        let order: Order = parse(&path, &text)?;
        let mut set = Set {
            order,
            dir: dir.to_path_buf(),
            zones: optional("zones.json")?,
            part: optional("part.json")?,
            refined_part: optional("refined_part.json")?,
            refined: optional("refined.json")?,
            robust: optional("robust.json")?,
            verify: None,
            verify_skipped: None,
            tolerance: None,
            tolerance_skipped: None,
            optimum,
            files,
        };
        let check = dir.join(VERIFY);
        if check.join("verify.json").is_file() {
            let path = check.join("verify.json");
            let text = read_text(&path)?;
            let v: Value = parse(&path, &text)?;
            if v.get("design") == set.optimum.get("design") {
                let fe: FeOrder = parse(&path, &text)?;
                for name in fe.outputs.values().flat_map(IndexMap::keys) {
                    if !set.order.fe.contains(name) {
                        set.order.fe.push(name.clone());
                    }
                }
                let own = folder::listed(&check).unwrap_or_default();
                if let Some(why) = folder::differing(&check, &own) {
                    return Err(why);
                }
                set.verify = Some((v, own));
            } else {
                set.verify_skipped = Some(format!(
                    "{VERIFY}/ holds the finite-element check of another design than this \
                     optimum; run `flexopt verify PROBLEM --optimum optimum.json --out \
                     {VERIFY}` (or `run --verify`) to check this one"
                ));
            }
        }
        let check = dir.join(TOLERANCE);
        if check.join("tolerance.json").is_file() {
            let v = read_json(&check.join("tolerance.json"))?;
            if v.get("design") == set.optimum.get("design") {
                let own = folder::listed(&check).unwrap_or_default();
                if let Some(why) = folder::differing(&check, &own) {
                    return Err(why);
                }
                set.tolerance = Some((v, own));
            } else {
                set.tolerance_skipped = Some(format!(
                    "{TOLERANCE}/ holds the tolerance check of another design than this \
                     optimum; run `flexopt tolerance PROBLEM --optimum optimum.json --out \
                     {TOLERANCE}` to check this one"
                ));
            }
        }
        Ok(set)
    }

    /// The files of the check shown from `folder` (`verify/` or `tolerance/`); none where it
    /// is not shown.
    fn check_files(&self, folder: &str) -> &[Entry] {
        let check = match folder {
            VERIFY => self.verify.as_ref(),
            TOLERANCE => self.tolerance.as_ref(),
            _ => None,
        };
        check.map_or(&[], |(_, own)| own.as_slice())
    }

    /// A picture of the set as a data URI, if the set holds it.
    fn picture(&self, name: &str) -> Option<String> {
        let path = self.dir.join(name);
        let in_set = match name.split_once('/') {
            Some((folder @ (VERIFY | TOLERANCE), inner)) => {
                self.check_files(folder).iter().any(|e| e.name == inner)
            }
            _ => self.files.iter().any(|e| e.name == name),
        };
        let bytes = crate::vocab::input::read_bytes(&path, MAX_SET_FILE_BYTES, "a picture")
            .ok()
            .filter(|_| in_set)?;
        Some(format!(
            "data:image/png;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(bytes)
        ))
    }
}

/// The page of the set.
fn render(set: &Set, problem: Option<&ProblemText>) -> Markup {
    let o = &set.optimum;
    let name = o.get("problem").and_then(Value::as_str).unwrap_or("?");
    html! {
        (DOCTYPE)
        html lang="en" {
            head {
                meta charset="utf-8";
                meta name="viewport" content="width=device-width, initial-scale=1";
                title { "flexopt design report: " (name) }
                style { (PreEscaped(include_str!("report.css"))) }
            }
            body {
                main {
                    (overview::heading(set))
                    (overview::problem(set, problem))
                    (overview::optimum(set))
                    (constraints::constraints(set))
                    (sections::part(set))
                    (sections::fe_check(set))
                    (sections::refinement(set))
                    (sections::tolerances(set))
                    (sections::files(set))
                    (sections::reproduce(set, problem))
                    (overview::problem_file(problem))
                }
            }
        }
    }
}

/// Writes `report.html` of the set staged in `dir` (`run --report`), whose files are `names`
/// (written already; the report lists them with their hashes).
pub fn write_staged(
    out: &Path,
    dir: &Path,
    names: &[&str],
    problem: Option<&ProblemText>,
) -> Result<(), WriteError> {
    let files = folder::entries_of(dir, names)?;
    let set = Set::read(dir, files).map_err(|message| WriteError {
        path: out.to_path_buf(),
        message,
    })?;
    super::write_atomic(out, render(&set, problem).into_string().as_bytes())
}

/// Why `flexopt report` refuses a folder or a problem file: the input's fault (exit 2), or a
/// write that failed (exit 1).
#[derive(Debug)]
pub enum ReportError {
    BadInput(String),
    Write(WriteError),
}

/// `flexopt report DIR`: writes `DIR/report.html` of the run's set in `DIR` and adds it to
/// the set (its manifest lists it, so the next run into the folder replaces or removes it).
/// `problem` is the problem file, whose content must be the one the run read.
pub fn write_report(dir: &Path, problem: Option<&ProblemText>) -> Result<PathBuf, ReportError> {
    let bad = ReportError::BadInput;
    if !dir.is_dir() {
        return Err(bad(format!("{}: not a folder", dir.display())));
    }
    let Some(files) = folder::listed(dir) else {
        return Err(bad(format!(
            "{}: no manifest.json that reads as one: not a folder of results flexopt wrote \
             (flexopt run PROBLEM --out {})",
            dir.display(),
            dir.display()
        )));
    };
    // an earlier report is not part of what this one describes
    let files: Vec<Entry> = files.into_iter().filter(|e| e.name != REPORT).collect();
    if let Some(why) = folder::differing(dir, &files) {
        return Err(bad(why));
    }
    let set = Set::read(dir, files.clone()).map_err(bad)?;
    if let Some(p) = problem {
        let recorded = set.optimum.get("problem_fnv1a64").and_then(Value::as_str);
        let hash = format!("{:016x}", crate::problem::fingerprint(&p.text));
        if recorded != Some(hash.as_str()) {
            return Err(bad(format!(
                "{}: key `--problem`: its content is not the one this run read \
                 (optimum.json's problem_fnv1a64 is {}, the file's {hash}): give the file \
                 the run was made of, or leave --problem out",
                p.path,
                recorded.unwrap_or("missing")
            )));
        }
    }
    let page = render(&set, problem).into_string();
    let out = OutputSet::begin(dir).map_err(ReportError::Write)?;
    out.write(|out| super::write_atomic(&out.path(REPORT), page.as_bytes()))
        .map_err(ReportError::Write)?;
    out.commit_added_to(&[REPORT], &files)
        .map_err(ReportError::Write)
        .map(|placed| {
            placed
                .into_iter()
                .next()
                .unwrap_or_else(|| dir.join(REPORT))
        })
}
