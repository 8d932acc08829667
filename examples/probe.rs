use flexopt::problem::Problem;
use flexopt::study::{bridge_configuration, run, StudyOptions};
fn main() {
    let p = Problem::load(std::path::Path::new(
        &std::env::var("PROBLEM").unwrap_or("problems/wei2017.toml".into()),
    ))
    .unwrap();
    let mut o = StudyOptions::from_problem(&p);
    if let Some(s) = std::env::args().nth(1) {
        o.solver = if s == "nm" {
            flexopt::problem::Solver::NelderMead
        } else {
            flexopt::problem::Solver::Sqp
        };
    }
    let s = run(&p, &o);
    println!(
        "elapsed {:?}, feasible {}/{}",
        s.elapsed,
        s.feasible_runs.len(),
        s.runs.len()
    );
    let b = &s.runs[s.best];
    println!(
        "best {} x {:?} kkt {:?} status {:?} it {}",
        b.objective,
        b.x_end
            .iter()
            .enumerate()
            .map(|(i, v)| if [1, 4, 6].contains(&i) {
                v.to_degrees()
            } else {
                v * 1e3
            })
            .collect::<Vec<_>>(),
        b.solution.kkt_residual,
        b.solution.status,
        b.solution.iterations
    );
    for z in &s.clustering.zones {
        println!(
            "zone {} count {} optima {} best {} worst {}",
            z.rank,
            z.count,
            z.optima.len(),
            z.best,
            z.worst
        );
        for &k in z.optima.iter().take(3) {
            let r = &s.runs[s.feasible_runs[s.clustering.optima[k].representative]];
            println!(
                "   {:.5} n={} {} {:?}",
                s.clustering.optima[k].objective,
                s.clustering.optima[k].members.len(),
                bridge_configuration(&r.x_end),
                r.x_end
                    .iter()
                    .enumerate()
                    .map(|(i, v)| if [1, 4, 6].contains(&i) {
                        (v.to_degrees() * 1000.0).round() / 1000.0
                    } else {
                        (v * 1e6).round() / 1e3
                    })
                    .collect::<Vec<_>>()
            );
        }
    }
    let mut st = std::collections::BTreeMap::new();
    for r in &s.runs {
        *st.entry(format!("{:?}", r.solution.status)).or_insert(0) += 1;
    }
    println!("{:?}", st);
    let its: usize = s.runs.iter().map(|r| r.solution.iterations).sum();
    let ev: usize = s.runs.iter().map(|r| r.solution.evaluations).sum();
    println!("iterations {} evaluations {}", its, ev);
}
#[allow(dead_code)]
fn unused() {}
