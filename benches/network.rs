//! wei2017 written as a flexure network against the built-in bridge (issue 25's goal: the
//! network at most 3x the bridge's time per evaluation with gradients): each model's
//! outputs that wei2017's objective and constraints read (the stress limit on each hinge
//! end), values and gradients, at Table 1's design. The models alone: the bridge's problem
//! also checks its part's rules, which the network has not yet. The two are timed in alternating
//! rounds in one run (the machine is shared) and the medians compared; the figures go to
//! results/bench/network.json and network.txt. Then each shipped network's evaluation with
//! exact gradients against central differences of the same code, and the two-stage
//! amplifier's 300-start study against wei2017's network's; and the export of a chain of 50,
//! 100 and 200 bodies, whole process, whose ratios tell how the part's checks grow.

use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

use flexopt::model::Model;
use flexopt::problem::Problem;

#[path = "support/chain.rs"]
mod chain;
#[path = "support/side_by_side.rs"]
mod side_by_side;
#[path = "support/table1.rs"]
mod table1;
use side_by_side::{alternate, median, write_results};
use table1::table1_design;

const ROUNDS: usize = 31;
const CALLS: usize = 2000;

fn main() {
    let bridge = Problem::load(Path::new("problems/wei2017.toml")).unwrap();
    let network = Problem::load(Path::new("problems/wei2017_network.toml")).unwrap();
    let x = table1_design();
    let wanted = |m: &dyn Model, stresses: &[&str]| -> Vec<usize> {
        ["amplification", "span_x", "span_y", "k_in", "k_out"]
            .iter()
            .chain(stresses)
            .map(|name| m.output_index(name).unwrap())
            .collect()
    };
    let (mb, mn) = (bridge.model(), network.model());
    let wb = wanted(
        mb,
        &[
            "stress_node2",
            "stress_node3",
            "stress_node4",
            "stress_node5",
        ],
    );
    let wn = wanted(
        mn,
        &[
            "stress_b_from",
            "stress_b_to",
            "stress_d_from",
            "stress_d_to",
        ],
    );
    let mut rows = Vec::new();
    for (what, gradients) in [("values", false), ("with gradients", true)] {
        let (b, n) = alternate(ROUNDS, |bridge_now| {
            let (m, w) = if bridge_now { (mb, &wb) } else { (mn, &wn) };
            let (mut c, mut j) = (vec![0.0; w.len()], vec![0.0; w.len() * 8]);
            let start = Instant::now();
            for _ in 0..CALLS {
                if gradients {
                    m.evaluate_with_gradient(black_box(&x), w, &mut c, &mut j);
                } else {
                    m.evaluate(black_box(&x), w, &mut c);
                }
                black_box(&c);
            }
            start.elapsed().as_secs_f64() / CALLS as f64
        });
        rows.push((what, b, n));
    }
    let mut text = String::from(
        "wei2017 as a network against the built-in bridge: the outputs of its objective and \
         constraints per evaluation at Table 1's design, medians of alternating rounds\n",
    );
    let mut json = Vec::new();
    for (what, b, n) in &rows {
        text += &format!(
            "{what:>15}: bridge {:8.0} ns, network {:8.0} ns, ratio {:.2}\n",
            b * 1e9,
            n * 1e9,
            n / b
        );
        json.push(serde_json::json!({
            "case": what, "bridge_ns": b * 1e9, "network_ns": n * 1e9, "ratio": n / b,
            "rounds": ROUNDS, "calls_per_round": CALLS,
        }));
    }
    // FLEXOPT_BENCH_QUICK: the first table alone, printed and not written, to iterate on
    if std::env::var_os("FLEXOPT_BENCH_QUICK").is_some() {
        print!("{text}");
        return;
    }
    shipped(&mut text, &mut json);
    studies(&mut text, &mut json);
    chain_exports(&mut text, &mut json);
    write_results("network", &text, &json);
}

/// Each shipped network's every output with its exact gradient, against central differences
/// of the same code for the free variables (one evaluation of the values at the design and
/// two a free variable, as a study would need without exact gradients), at the middle of the
/// file's bounds: alternating rounds, medians. The exact gradient covers every parameter,
/// fixed ones too.
fn shipped(text: &mut String, json: &mut Vec<serde_json::Value>) {
    *text += "\neach shipped network, every output, per evaluation at the middle of its bounds: \
              exact gradients against central differences of the same code\n";
    for file in [
        "rhombus_network",
        "guide_network",
        "lever_network",
        "scott_russell_network",
        "bridge_lever_network",
        "wei2017_network",
    ] {
        let p = Problem::load(Path::new(&format!("problems/{file}.toml"))).unwrap();
        let m = p.model();
        let x: Vec<f64> = p
            .variables
            .iter()
            .map(|v| 0.5 * (v.lower + v.upper))
            .collect();
        let free: Vec<(usize, f64)> = p
            .variables
            .iter()
            .enumerate()
            .filter(|(_, v)| !v.fixed)
            .map(|(i, v)| (i, 1e-6 * (v.upper - v.lower)))
            .collect();
        let all = m.available_outputs();
        let (mut c, mut j) = (vec![0.0; all.len()], vec![0.0; all.len() * x.len()]);
        let calls = CALLS / 4;
        let (e, cd) = alternate(ROUNDS, |exact_now| {
            let start = Instant::now();
            for _ in 0..calls {
                if exact_now {
                    m.evaluate_with_gradient(black_box(&x), &all, &mut c, &mut j);
                } else {
                    m.evaluate(black_box(&x), &all, &mut c);
                    let mut y = x.clone();
                    for &(k, h) in &free {
                        y[k] = x[k] + h;
                        m.evaluate(black_box(&y), &all, &mut c);
                        y[k] = x[k] - h;
                        m.evaluate(black_box(&y), &all, &mut c);
                        y[k] = x[k];
                    }
                }
                black_box(&c);
            }
            start.elapsed().as_secs_f64() / calls as f64
        });
        *text += &format!(
            "{file:>22}: {} outputs, {} free of {} parameters: exact {:8.0} ns, central \
             differences {:8.0} ns, ratio {:.2}\n",
            all.len(),
            free.len(),
            x.len(),
            e * 1e9,
            cd * 1e9,
            e / cd
        );
        json.push(serde_json::json!({
            "case": "shipped network, every output", "problem": file, "outputs": all.len(),
            "free": free.len(), "parameters": x.len(), "exact_ns": e * 1e9,
            "central_differences_ns": cd * 1e9, "ratio": e / cd,
            "rounds": ROUNDS, "calls_per_round": calls,
        }));
    }
}

/// The 300-start study of the two-stage amplifier (problems/bridge_lever_network.toml)
/// against wei2017's network's, alternating, medians of 5, each on its file's threads.
fn studies(text: &mut String, json: &mut Vec<serde_json::Value>) {
    use flexopt::study::{self, StudyOptions};
    let load = |f: &str| Problem::load(Path::new(&format!("problems/{f}.toml"))).unwrap();
    let (two, wei) = (load("bridge_lever_network"), load("wei2017_network"));
    let (a, b) = alternate(5, |two_now| {
        let p = if two_now { &two } else { &wei };
        let start = Instant::now();
        black_box(study::run(p, &StudyOptions::from_problem(p)));
        start.elapsed().as_secs_f64()
    });
    *text += &format!(
        "\nthe 300-start study: two-stage bridge-lever {:.1} ms, wei2017's network {:.1} ms, \
         ratio {:.2} (medians of 5, alternating)\n",
        a * 1e3,
        b * 1e3,
        a / b
    );
    json.push(serde_json::json!({
        "case": "300-start study", "bridge_lever_ms": a * 1e3, "wei2017_network_ms": b * 1e3,
        "ratio": a / b, "rounds": 5,
    }));
}

/// `flexopt export` of a chain of n bodies with its part, whole process as a user runs it
/// (medians of 5): the time at 200 bodies (issue 50 asks at most 2 s) and its ratio to 50
/// bodies' (4 where the part's checks grow linearly, 64 where cubically).
fn chain_exports(text: &mut String, json: &mut Vec<serde_json::Value>) {
    let dir = std::env::temp_dir().join(format!("flexopt-bench-chain-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut times = Vec::new();
    for n in [50, 100, 200] {
        let file = dir.join(format!("chain{n}.toml"));
        std::fs::write(&file, chain::chain_problem(n, "[part]")).unwrap();
        let once = || {
            let start = Instant::now();
            let o = std::process::Command::new(env!("CARGO_BIN_EXE_flexopt"))
                .args([
                    "export",
                    file.to_str().unwrap(),
                    "--design",
                    "l=2,t=0.5",
                    "--out",
                ])
                .arg(dir.join(format!("out{n}")))
                .output()
                .unwrap();
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
            start.elapsed().as_secs_f64()
        };
        times.push((n, median((0..5).map(|_| once()).collect())));
    }
    *text += "export of a chain of n bodies with its part, whole process, median of 5\n";
    let first = times[0].1;
    for &(n, t) in &times {
        *text += &format!("{n:>5} bodies: {t:6.3} s, {:5.2} x 50 bodies'\n", t / first);
        json.push(serde_json::json!({"case": format!("export of a {n}-body chain"), "seconds": t, "ratio_to_50": t / first}));
    }
    let _ = std::fs::remove_dir_all(&dir);
}
