//! Issue 23's benchmark as one process: the 300-start studies of wei2017 and
//! wei2017_min_stress (two threads) with the part's rules enforced and with `[part] enforce
//! = false`, each with the SQP's constraint screening and without, the four alternating,
//! medians of the argument's count (7); with each the counts that tell whether a change moved
//! the iterates (starts at the best, iterations, evaluations). A second argument sets the
//! threads (2); a third, `enforced` or `free`, runs that study alone, not screened, once per
//! round (for `valgrind --tool=callgrind`, whose counts the machine's load does not move); a
//! fourth, a part of a file's name (`wei2017.toml`), runs that file's studies alone, or a
//! problem file's path (`problems/wei2017_network.toml`) that file's.
use std::path::Path;
use std::time::Instant;

use flexopt::problem::Problem;
use flexopt::study::{self, StudyOptions};

fn main() {
    let reps: usize = std::env::args().nth(1).map_or(7, |s| s.parse().unwrap());
    let threads: usize = std::env::args().nth(2).map_or(2, |s| s.parse().unwrap());
    let only = std::env::args().nth(3);
    let file_filter = std::env::args().nth(4).unwrap_or_default();
    // a file's path as the fourth argument times that file (a network's, say) instead
    let given = [file_filter.as_str()];
    let files: &[&str] = if file_filter.ends_with(".toml") && Path::new(&file_filter).exists() {
        &given
    } else {
        &["problems/wei2017.toml", "problems/wei2017_min_stress.toml"]
    };
    for &file in files {
        if !file.contains(&file_filter) {
            continue;
        }
        let text = std::fs::read_to_string(file).unwrap();
        // into the file's own `[part]` where it has one (a table may not be given twice)
        let free = if text.contains("\n[part]\n") {
            text.replacen("\n[part]\n", "\n[part]\nenforce = false\n", 1)
        } else {
            text.replace("[search]", "[part]\nenforce = false\n\n[search]")
        };
        let mut times = [vec![], vec![], vec![], vec![]];
        let mut summary = [String::new(), String::new(), String::new(), String::new()];
        let configs = [(&text, true), (&free, true), (&text, false), (&free, false)];
        for _ in 0..reps {
            for (k, &(t, screening)) in configs.iter().enumerate() {
                let wanted = match only.as_deref() {
                    Some("enforced") => k == 2,
                    Some("free") => k == 3,
                    _ => true,
                };
                if !wanted {
                    continue;
                }
                let problem = Problem::parse(Path::new(file), t).unwrap();
                let options = StudyOptions {
                    threads,
                    screening,
                    ..StudyOptions::from_problem(&problem)
                };
                let begin = Instant::now();
                let s = study::run(&problem, &options);
                times[k].push(begin.elapsed().as_secs_f64() * 1e3);
                let best = s.runs[s.best].objective;
                let at_best = s
                    .runs
                    .iter()
                    .filter(|r| r.feasible && ((r.objective - best).abs() <= 1e-6 * best.abs()))
                    .count();
                let iters: usize = s.runs.iter().map(|r| r.solution.iterations).sum();
                let evals: usize = s.runs.iter().map(|r| r.solution.evaluations).sum();
                summary[k] = format!(
                    "best {best:.7} at_best {at_best} ends {:?} iters {iters} evals {evals}",
                    s.ends
                );
            }
        }
        let med = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
        };
        let m: Vec<f64> = times.iter_mut().map(med).collect();
        println!("{file}:");
        for (k, what) in ["screened", "not screened"].iter().enumerate() {
            let (a, b) = (m[2 * k], m[2 * k + 1]);
            println!(
                "  {what}: enforced {a:.1} ms, not {b:.1} ms, ratio {:.2}",
                a / b
            );
            println!("    enforced: {}", summary[2 * k]);
            println!("    not:      {}", summary[2 * k + 1]);
        }
        println!(
            "  screened against not: enforced {:.2}, not enforced {:.2}",
            m[0] / m[2],
            m[1] / m[3]
        );
    }
}
