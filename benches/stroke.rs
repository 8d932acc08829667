//! wei2017's network at its working stroke beside its linear model (issue 48's goals: the
//! outputs at stroke with gradients at most 20x the linear evaluation's; the 300-start study
//! at stroke at most 2 s, whole process, on two threads), each timed side by side with the
//! linear peer in one run (the machine is shared and noisy: the ratios are the figures).
//!
//! (a) The outputs wei2017's objective and constraints read, values and exact gradients, at
//! Table 1's design: problems/wei2017_network.toml's (amplification, span_x, span_y,
//! stress_max, k_in, k_out) against problems/wei2017_stroke.toml's (nl_amplification, span_x,
//! span_y, nl_stress_max, nl_k_in, nl_k_out), alternating rounds, medians.
//! (b) `flexopt run` of the two files on two threads, whole process as a user runs it,
//! alternating, medians; and the study at stroke on one thread, whose files must be the
//! two threads' byte for byte (the thread count changes nothing).
//!
//! The figures go to results/bench/stroke.json and stroke.txt.

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use flexopt::model::Model;
use flexopt::problem::Problem;

#[path = "support/side_by_side.rs"]
mod side_by_side;
#[path = "support/table1.rs"]
mod table1;
use side_by_side::{alternate, write_results};
use table1::table1_design;

const ROUNDS: usize = 21;
/// Each side's calls in a round are as many as fill about this long (s).
const ROUND_SECONDS: f64 = 0.02;
const STUDY_ROUNDS: usize = 3;

/// A model with the indices of the outputs its problem's objective and constraints read.
struct Evaluated<'a> {
    model: &'a dyn Model,
    wanted: Vec<usize>,
    calls: usize,
}

impl Evaluated<'_> {
    /// The time of one evaluation (s), over `self.calls` calls.
    fn time(&self, x: &[f64], gradients: bool) -> f64 {
        let n = self.wanted.len();
        let (mut c, mut j) = (vec![0.0; n], vec![0.0; n * x.len()]);
        let start = Instant::now();
        for _ in 0..self.calls {
            if gradients {
                self.model
                    .evaluate_with_gradient(black_box(x), &self.wanted, &mut c, &mut j);
            } else {
                self.model.evaluate(black_box(x), &self.wanted, &mut c);
            }
            black_box(&c);
        }
        assert!(c.iter().chain(&j).all(|v| v.is_finite()));
        start.elapsed().as_secs_f64() / self.calls as f64
    }
}

/// The outputs the linear study's objective and constraints read (wei2017_network.toml's),
/// or with `at_stroke` the ones at stroke in place of the amplification, the stress and the
/// stiffnesses, as wei2017_stroke.toml reads them.
fn read_by(problem: &Problem, at_stroke: bool) -> Vec<usize> {
    let m = problem.model();
    std::iter::once(&problem.objective.output)
        .chain(problem.constraints.iter().map(|c| &c.output))
        .map(|name| match at_stroke && !name.starts_with("span_") {
            true => format!("nl_{name}"),
            false => name.clone(),
        })
        .map(|name| m.output_index(&name).unwrap())
        .collect()
}

/// `problem`'s model with as many calls a round as fill about [`ROUND_SECONDS`].
fn sized<'a>(problem: &'a Problem, at_stroke: bool, x: &[f64], gradients: bool) -> Evaluated<'a> {
    let mut e = Evaluated {
        model: problem.model(),
        wanted: read_by(problem, at_stroke),
        calls: 1,
    };
    let once = e.time(x, gradients);
    e.calls = ((ROUND_SECONDS / once) as usize).clamp(1, 100_000);
    e
}

fn main() {
    let file = "problems/wei2017_network.toml";
    let linear = Problem::load(Path::new(file)).unwrap();
    // the same file with wei2017_stroke.toml's [analysis]: its model lists the outputs at
    // stroke beside the linear ones
    let text = std::fs::read_to_string(file).unwrap();
    let analysis = "\n[analysis]\ndeflection = \"large\"\nelements = 8\nsteps = 10\n";
    let stroke = Problem::parse(Path::new(file), &(text + analysis)).unwrap();
    let x = table1_design();
    let names = |p: &Problem, at_stroke: bool| {
        let m = p.model();
        read_by(p, at_stroke)
            .iter()
            .map(|&i| m.outputs()[i].name.to_string())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut text = format!(
        "wei2017's network at its working stroke beside its linear model, per evaluation at \
         Table 1's design, medians of {ROUNDS} alternating rounds\n  linear: {}\n  at stroke: \
         {}\n",
        names(&linear, false),
        names(&stroke, true)
    );
    let mut json = Vec::new();
    for (what, gradients) in [("values", false), ("with gradients", true)] {
        let (lin, nl) = (
            sized(&linear, false, &x, gradients),
            sized(&stroke, true, &x, gradients),
        );
        let (l, n) = alternate(ROUNDS, |linear_now| {
            if linear_now {
                lin.time(&x, gradients)
            } else {
                nl.time(&x, gradients)
            }
        });
        json.push(serde_json::json!({
            "case": format!("evaluation, {what}"), "linear_ns": l * 1e9, "at_stroke_ns": n * 1e9,
            "ratio": n / l, "rounds": ROUNDS, "linear_calls_per_round": lin.calls,
            "at_stroke_calls_per_round": nl.calls,
        }));
        text += &format!(
            "{what:>15}: linear {:10.0} ns, at stroke {:10.0} ns, ratio {:6.1}\n",
            l * 1e9,
            n * 1e9,
            n / l
        );
    }
    // FLEXOPT_BENCH_QUICK: the evaluations alone, printed and not written, to iterate on
    if std::env::var_os("FLEXOPT_BENCH_QUICK").is_some() {
        print!("{text}");
        return;
    }
    studies(&mut text, &mut json);
    write_results("stroke", &text, &json);
}

/// `flexopt run file --threads threads --out out`, whole process: its wall time (s).
fn run(file: &str, threads: usize, out: &Path) -> f64 {
    let _ = std::fs::remove_dir_all(out);
    let start = Instant::now();
    let o = Command::new(env!("CARGO_BIN_EXE_flexopt"))
        .args(["run", file, "--quiet", "--threads", &threads.to_string()])
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    let seconds = start.elapsed().as_secs_f64();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    seconds
}

/// Every file under `dir`, by its path within it, with its bytes.
fn files(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let bytes = std::fs::read(&p).unwrap();
                out.push((p.strip_prefix(dir).unwrap().to_path_buf(), bytes));
            }
        }
    }
    out.sort();
    out
}

/// The 300-start studies, whole process on two threads, the one at stroke against the
/// linear one, alternating; then the one at stroke on one thread, its files checked
/// against the two threads'.
fn studies(text: &mut String, json: &mut Vec<serde_json::Value>) {
    let dir = std::env::temp_dir().join(format!("flexopt-bench-stroke-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (lin_out, nl_out, one_out) = (dir.join("linear"), dir.join("stroke"), dir.join("one"));
    let (l, n) = alternate(STUDY_ROUNDS, |linear_now| {
        if linear_now {
            run("problems/wei2017_network.toml", 2, &lin_out)
        } else {
            run("problems/wei2017_stroke.toml", 2, &nl_out)
        }
    });
    let one = run("problems/wei2017_stroke.toml", 1, &one_out);
    let (two_files, one_files) = (files(&nl_out), files(&one_out));
    let names = |f: &[(PathBuf, Vec<u8>)]| f.iter().map(|f| f.0.clone()).collect::<Vec<_>>();
    assert_eq!(names(&two_files), names(&one_files));
    for ((path, a), (_, b)) in two_files.iter().zip(&one_files) {
        assert!(
            a == b,
            "{}: one thread's differs from two's",
            path.display()
        );
    }
    *text += &format!(
        "\nflexopt run, 300 starts, whole process on 2 threads, medians of {STUDY_ROUNDS} \
         alternating\n  linear (wei2017_network.toml) {l:7.3} s\n  at stroke \
         (wei2017_stroke.toml) {n:7.3} s, ratio {:.1}\n  at stroke on 1 thread (once) {one:7.3} \
         s; its {} files byte-identical to the 2 threads'\n",
        n / l,
        one_files.len()
    );
    json.push(serde_json::json!({
        "case": "flexopt run, 300 starts, 2 threads", "linear_s": l, "at_stroke_s": n,
        "ratio": n / l, "rounds": STUDY_ROUNDS, "at_stroke_1_thread_s": one,
        "files_identical_1_and_2_threads": one_files.len(),
    }));
    let _ = std::fs::remove_dir_all(&dir);
}
