//! wei2017 written as a flexure network against the built-in bridge (issue 25's goal: the
//! network at most 3x the bridge's time per evaluation with gradients): each model's
//! outputs that wei2017's objective and constraints read (the stress limit on each hinge
//! end), values and gradients, at Table 1's design. The models alone: the bridge's problem
//! also checks its part's rules, which the network has not yet. The two are timed in alternating
//! rounds in one run (the machine is shared) and the medians compared; the figures go to
//! results/bench/network.json and network.txt.

use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

use flexopt::model::Model;
use flexopt::problem::Problem;

const ROUNDS: usize = 31;
const CALLS: usize = 2000;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let bridge = Problem::load(Path::new("problems/wei2017.toml")).unwrap();
    let network = Problem::load(Path::new("problems/wei2017_network.toml")).unwrap();
    let deg = std::f64::consts::PI / 180.0;
    let x = [
        1.96e-3,
        4.07 * deg,
        0.4e-3,
        8.1e-3,
        4.01 * deg,
        1.96e-3,
        4.07 * deg,
        0.4e-3,
    ];
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
        let (mut tb, mut tn) = (Vec::new(), Vec::new());
        for round in 0..ROUNDS {
            // alternate which goes first, so that neither always meets a cold cache
            let first_bridge = round % 2 == 0;
            for bridge_now in [first_bridge, !first_bridge] {
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
                let per = start.elapsed().as_secs_f64() / CALLS as f64;
                if bridge_now {
                    tb.push(per)
                } else {
                    tn.push(per)
                }
            }
        }
        let (b, n) = (median(tb), median(tn));
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
    print!("{text}");
    std::fs::create_dir_all("results/bench").unwrap();
    std::fs::write("results/bench/network.txt", &text).unwrap();
    std::fs::write(
        "results/bench/network.json",
        serde_json::to_string_pretty(&json).unwrap() + "\n",
    )
    .unwrap();
}
