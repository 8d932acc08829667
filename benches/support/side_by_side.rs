//! The medians of alternating rounds, for the benchmarks that time two things side by side
//! (the machines are shared and noisy, so a ratio measured in one run is the figure).

pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The medians over `rounds` rounds of `time(true)` and `time(false)`, each a time (s),
/// alternating which goes first, so that neither always meets a cold cache.
pub fn alternate(rounds: usize, mut time: impl FnMut(bool) -> f64) -> (f64, f64) {
    let (mut a, mut b) = (Vec::new(), Vec::new());
    for round in 0..rounds {
        let first = round % 2 == 0;
        for now in [first, !first] {
            let t = time(now);
            if now {
                a.push(t)
            } else {
                b.push(t)
            }
        }
    }
    (median(a), median(b))
}

/// Prints `text` and writes it to `results/bench/<name>.txt`, and `json` to `<name>.json`.
pub fn write_results(name: &str, text: &str, json: &[serde_json::Value]) {
    print!("{text}");
    std::fs::create_dir_all("results/bench").unwrap();
    std::fs::write(format!("results/bench/{name}.txt"), text).unwrap();
    std::fs::write(
        format!("results/bench/{name}.json"),
        serde_json::to_string_pretty(json).unwrap() + "\n",
    )
    .unwrap();
}
