//! Shared fixtures of the integration tests.
#![allow(dead_code)]

pub mod exact;
pub mod hs;

use flexopt::model::bridge::dynamics::DynamicsSettings;
use flexopt::model::bridge::part::PartSettings;
use flexopt::model::bridge::{Actuator, Bridge, BridgeSettings, Geometry};
use flexopt::model::hinge::HingeKind;
use flexopt::model::material::Material;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub const MM: f64 = 1e-3;
pub const DEG: f64 = std::f64::consts::PI / 180.0;

/// Paper 004, Sec. 3: w = 10 mm, Al 7075-T6, 17.4 um nominal stroke, 40 N preload.
pub fn wei2017_settings() -> BridgeSettings {
    BridgeSettings {
        hinge_b: HingeKind::Strip,
        hinge_d: HingeKind::Strip,
        width: 10.0 * MM,
        material: Material::al7075_t6(),
        actuator: Actuator {
            nominal_stroke: 17.4e-6,
            preload: 40.0,
            stiffness: None,
            mass: None,
        },
        // the stage of problems/wei2017_dynamic.toml, so that every output has a value
        dynamics: Some(DynamicsSettings::new(10e-3, 3e-3, 3e-3, 3e-3, 0.02)),
        part: PartSettings::default(),
    }
}

pub fn wei2017() -> Bridge {
    Bridge::new(wei2017_settings())
}

/// Table 1's optimal result, SI.
pub fn table1_optimum() -> [f64; 8] {
    [
        1.96 * MM,
        4.07 * DEG,
        0.4 * MM,
        8.1 * MM,
        4.01 * DEG,
        1.96 * MM,
        4.07 * DEG,
        0.4 * MM,
    ]
}

/// Table 1's bounds, SI, in parameter order.
pub fn table1_bounds() -> [(f64, f64); 8] {
    let (l, a, t) = (
        (0.5 * MM, 20.0 * MM),
        (-45.0 * DEG, 45.0 * DEG),
        (0.4 * MM, 2.0 * MM),
    );
    [l, a, t, l, a, l, a, t]
}

pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A design drawn uniformly from Table 1's bounds.
pub fn random_design(rng: &mut ChaCha8Rng) -> [f64; 8] {
    table1_bounds().map(|(lo, hi)| rng.random_range(lo..hi))
}

/// A design drawn uniformly from a problem file's bounds (SI, every parameter in model
/// order; a fixed variable at its value).
pub fn design_within_bounds(p: &flexopt::problem::Problem, r: &mut ChaCha8Rng) -> Vec<f64> {
    let mut x = vec![0.0; p.variables.len()];
    for v in &p.variables {
        x[v.parameter] = if v.fixed {
            v.lower
        } else {
            r.random_range(v.lower..v.upper)
        };
    }
    x
}

pub fn geometry(x: [f64; 8]) -> Geometry<f64> {
    Geometry::from_array(x)
}

/// Relative difference, with the scale floored so that values near zero compare absolutely
/// against `scale`.
pub fn rel(a: f64, b: f64, scale: f64) -> f64 {
    (a - b).abs() / b.abs().max(scale)
}

/// Whether a peer program a test runs (CalculiX, ezdxf, Chromium) is here, `found`: where it
/// is not, the test says so (`missing`: what is missing, `skipped`: what is not run) and
/// passes, but under CI (the variable `CI` set), where it fails: `.ci/run` installs it.
pub fn peer_present(found: bool, missing: &str, skipped: &str) -> bool {
    if !found {
        assert!(
            std::env::var_os("CI").is_none(),
            "{missing} is missing, and CI is set: .ci/run must install it"
        );
        eprintln!("{missing} not found: {skipped} is not run here");
    }
    found
}

/// The Python of the virtual environment `.ci/run` makes (`.venv`), where it imports
/// `module`; otherwise [`peer_present`]'s verdict for `skipped`.
pub fn venv_python(module: &str, skipped: &str) -> Option<&'static str> {
    let venv = ".venv/bin/python";
    let found = std::path::Path::new(venv).is_file()
        && std::process::Command::new(venv)
            .args(["-c", &format!("import {module}")])
            .output()
            .is_ok_and(|o| o.status.success());
    peer_present(found, &format!("{venv} with {module}"), skipped).then_some(venv)
}

/// Runs `command`, which must succeed (its standard error shown where it does not), and
/// returns its output.
pub fn succeeds(command: &mut std::process::Command) -> std::process::Output {
    let out = command.output().unwrap();
    assert!(
        out.status.success(),
        "{command:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Runs the `flexopt` binary with `args` and collects its exit status and output.
pub fn flexopt(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_flexopt"))
        .args(args)
        .output()
        .unwrap()
}

/// Runs the `flexopt` binary with `args`, which must succeed, and returns its output.
pub fn flexopt_ok(args: &[&str]) -> std::process::Output {
    let out = flexopt(args);
    assert!(
        out.status.success(),
        "flexopt {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// `x` rounded to `digits` significant digits, the way a paper prints it.
pub fn printed(x: f64, digits: i32) -> f64 {
    let scale = 10f64.powi(digits - 1 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}

/// Runs the `flexopt` binary with `args` on a disk that holds no file longer than `blocks`
/// blocks of 512 bytes (the shell's `ulimit -f`): a write past it fails with EFBIG, as on a
/// full disk, without root. SIGXFSZ is ignored where `ignored`, else at its default (the
/// process's death, unless flexopt ignores it itself).
pub fn flexopt_on_full_disk(blocks: u32, ignored: bool, args: &[&str]) -> std::process::Output {
    let trap = if ignored { "''" } else { "-" };
    std::process::Command::new("sh")
        .arg("-c")
        .arg(format!(
            "trap {trap} XFSZ; ulimit -f {blocks}; exec \"$0\" \"$@\""
        ))
        .arg(env!("CARGO_BIN_EXE_flexopt"))
        .args(args)
        .output()
        .unwrap()
}

/// Every file under `dir`, hidden ones too, with its size and FNV-1a hash (a folder with
/// neither): two folders with equal snapshots hold the same files.
pub fn snapshot(dir: &std::path::Path) -> std::collections::BTreeMap<String, Option<(u64, u64)>> {
    walkdir::WalkDir::new(dir)
        .min_depth(1)
        .into_iter()
        .map(|entry| {
            let entry = entry.unwrap();
            let rel = entry
                .path()
                .strip_prefix(dir)
                .unwrap()
                .display()
                .to_string();
            if entry.file_type().is_dir() {
                return (format!("{rel}/"), None);
            }
            let bytes = std::fs::read(entry.path()).unwrap();
            let hash = flexopt::report::folder::fnv1a64(&bytes);
            (rel, Some((bytes.len() as u64, hash)))
        })
        .collect()
}

/// Asserts that `dir` holds one whole set of files and nothing else but `others` (the
/// user's): every file its `manifest.json` lists, with the size and FNV-1a hash listed; every
/// folder it lists a whole set itself; nothing hidden (a staging folder, a lock, a temporary
/// file). Returns the names the manifest lists.
pub fn assert_whole_set(dir: &std::path::Path, others: &[&str]) -> Vec<String> {
    let text = std::fs::read_to_string(dir.join("manifest.json"))
        .unwrap_or_else(|e| panic!("{}: no manifest: {e}", dir.display()));
    let manifest: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut listed = Vec::new();
    for f in manifest["files"].as_array().unwrap() {
        let name = f["name"].as_str().unwrap();
        let path = dir.join(name);
        if f["folder"] == true {
            assert!(path.is_dir(), "{}: {f}", dir.display());
            assert_whole_set(&path, &[]);
        } else {
            let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            assert_eq!(bytes.len() as u64, f["bytes"].as_u64().unwrap(), "{f}");
            let hash = format!("{:016x}", flexopt::report::folder::fnv1a64(&bytes));
            assert_eq!(hash, f["fnv1a64"].as_str().unwrap(), "{f}");
        }
        listed.push(name.to_string());
    }
    let mut present: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    present.sort();
    let mut expected: Vec<String> = listed
        .iter()
        .map(String::as_str)
        .chain(others.iter().copied())
        .chain(["manifest.json"])
        .map(String::from)
        .collect();
    expected.sort();
    assert_eq!(present, expected, "{}", dir.display());
    listed
}
