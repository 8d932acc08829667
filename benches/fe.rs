//! The finite-element check: its time, and the same solves by CalculiX in the same run.
//!
//! `cargo bench --bench fe` verifies the optimum of `problems/wei2017.toml` (the committed
//! `results/wei2017/optimum.json`) to the default 0.5 % estimated error, seven times, and
//! records each time with the degrees of freedom and time of every mesh level. Then, on the
//! whole part's mesh of each level, it solves the two static load cases in plane strain with
//! flexopt (assembly, ordering, factorization, both solves) and runs `ccx` on the 2D deck of
//! the same mesh and cases (CPE6: its time is its whole run, reading the deck and writing
//! the results included, as a designer would run it), three times each, alternating. Writes
//! `results/bench/fe.json` and the table `results/bench/fe.txt`. Without `ccx` on the PATH
//! the peer's columns are left empty.
//!
//! Beside it, the cost of the outputs under the stack (`fe_stroke_out`, `fe_k_out_actuated`
//! and the others of [`Quantity::Actuated`]): the same part verified with and without them,
//! alternating, seven times each (they solve nothing more: the stack's spring is a rank-one
//! term solved on the two load cases' fields; the part's statement without them still reads
//! the one more face they need).

use std::path::Path;
use std::process::Command;
use std::time::Instant;

use flexopt::fe::verify::{verify, verify_design, VerifySettings};
use flexopt::fe::{Elastic, Idealization};
use flexopt::part::analysis::Quantity;
use flexopt::problem::design::design_from_optimum;
use flexopt::problem::Problem;
use flexopt::report::write_json;
use serde::Serialize;

const REPEATS: usize = 7;
const PEER_REPEATS: usize = 3;

#[derive(Serialize)]
struct LevelTiming {
    level: usize,
    elements_half: usize,
    dofs_half: usize,
    seconds: f64,
}

#[derive(Serialize)]
struct PeerRow {
    level: usize,
    elements: usize,
    dofs: usize,
    flexopt_seconds: Vec<f64>,
    ccx_seconds: Vec<f64>,
}

#[derive(Serialize)]
struct Report {
    verify_seconds: Vec<f64>,
    verify_median: f64,
    /// The verification with the outputs under the stack and without them, alternating.
    with_actuated_seconds: Vec<f64>,
    without_actuated_seconds: Vec<f64>,
    actuated_ratio: f64,
    converged: bool,
    levels: Vec<LevelTiming>,
    peer: Vec<PeerRow>,
}

fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s[s.len() / 2]
}

fn main() {
    let problem = Problem::load(Path::new("problems/wei2017.toml")).unwrap();
    let x = design_from_optimum(&problem, Path::new("results/wei2017/optimum.json"))
        .unwrap()
        .x;
    let settings = VerifySettings::default();
    let mechanism = problem.mechanism();
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..REPEATS {
        let start = Instant::now();
        let v = verify_design(mechanism, &x, &settings).unwrap();
        times.push(start.elapsed().as_secs_f64());
        last = Some(v);
    }
    let v = last.unwrap();
    let (with_actuated, without_actuated) =
        actuated_side_by_side(&problem, &x, &settings, &v.material);
    let levels: Vec<LevelTiming> = v
        .levels
        .iter()
        .map(|l| LevelTiming {
            level: l.level,
            elements_half: l.elements,
            dofs_half: l.dofs,
            seconds: l.seconds,
        })
        .collect();
    let ccx = Command::new("ccx").arg("-v").output().is_ok();
    let dir = std::env::temp_dir().join(format!("flexopt-bench-fe-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut peer = Vec::new();
    for level in 0..v.meshes.len() {
        let model = v.full_model(level).unwrap();
        let deck = model
            .deck("bench", &v.material, v.width, 1.0)
            .two_d(Idealization::PlaneStrain);
        std::fs::write(dir.join("part.inp"), &deck).unwrap();
        let (mut ours, mut theirs) = (Vec::new(), Vec::new());
        for _ in 0..PEER_REPEATS {
            let start = Instant::now();
            let u = model
                .solve(&v.material, v.width, Idealization::PlaneStrain)
                .unwrap();
            ours.push(start.elapsed().as_secs_f64());
            std::hint::black_box(u);
            if ccx {
                let start = Instant::now();
                let out = Command::new("ccx")
                    .arg("part")
                    .current_dir(&dir)
                    .output()
                    .unwrap();
                assert!(out.status.success());
                theirs.push(start.elapsed().as_secs_f64());
            }
        }
        peer.push(PeerRow {
            level,
            elements: model.mesh.elements.len(),
            dofs: 2 * (model.mesh.nodes.len() - model.clamp.len()),
            flexopt_seconds: ours,
            ccx_seconds: theirs,
        });
    }
    let _ = std::fs::remove_dir_all(&dir);
    let report = Report {
        verify_median: median(&times),
        verify_seconds: times,
        actuated_ratio: median(&with_actuated) / median(&without_actuated),
        with_actuated_seconds: with_actuated,
        without_actuated_seconds: without_actuated,
        converged: v.converged,
        levels,
        peer,
    };
    let mut text = format!(
        "one verification of the wei2017 optimum (0.5 % tolerance, both idealizations, modes \
         included): median {:.3} s of {REPEATS} (min {:.3}, max {:.3})\n",
        report.verify_median,
        report
            .verify_seconds
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min),
        report.verify_seconds.iter().copied().fold(0.0, f64::max),
    );
    text += &format!(
        "with the outputs under the stack {:.3} s, without them {:.3} s (medians of {REPEATS}, \
         alternating): {:.3}x\n",
        median(&report.with_actuated_seconds),
        median(&report.without_actuated_seconds),
        report.actuated_ratio
    );
    text += "level  elements(half)  dofs(half)  seconds\n";
    for l in &report.levels {
        text += &format!(
            "{:<6} {:<15} {:<11} {:.3}\n",
            l.level, l.elements_half, l.dofs_half, l.seconds
        );
    }
    text += "whole part, plane strain, two static load cases: flexopt (solve) against ccx (run)\n\
             level  elements  dofs     flexopt (s, median)  ccx (s, median)  ratio\n";
    for r in &report.peer {
        let (a, b) = (
            median(&r.flexopt_seconds),
            r.ccx_seconds.first().map(|_| median(&r.ccx_seconds)),
        );
        text += &format!(
            "{:<6} {:<9} {:<8} {:<20.3} {:<16} {}\n",
            r.level,
            r.elements,
            r.dofs,
            a,
            b.map_or("-".into(), |b| format!("{b:.3}")),
            b.map_or("-".into(), |b| format!("{:.1}x", b / a))
        );
    }
    print!("{text}");
    std::fs::create_dir_all("results/bench").unwrap();
    write_json(Path::new("results/bench/fe.json"), &report).unwrap();
    flexopt::report::write_atomic(Path::new("results/bench/fe.txt"), text.as_bytes()).unwrap();
}

/// The times of the optimum's verification with the outputs under the stack and without
/// them, alternating.
fn actuated_side_by_side(
    problem: &Problem,
    x: &[f64],
    settings: &VerifySettings,
    material: &Elastic,
) -> (Vec<f64>, Vec<f64>) {
    let with = problem.mechanism().part_spec(x).unwrap().unwrap();
    let mut without = with.clone();
    let analysis = without.analysis.as_mut().unwrap();
    analysis
        .outputs
        .retain(|o| !matches!(o.quantity, Quantity::Actuated { .. }));
    assert!(analysis.outputs.len() < with.analysis.as_ref().unwrap().outputs.len());
    let (mut a, mut b) = (Vec::new(), Vec::new());
    for _ in 0..REPEATS {
        for (spec, times) in [(&with, &mut a), (&without, &mut b)] {
            let start = Instant::now();
            std::hint::black_box(verify(spec, material, settings).unwrap());
            times.push(start.elapsed().as_secs_f64());
        }
    }
    (a, b)
}
