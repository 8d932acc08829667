//! Run time against error: how fast each solver reaches how accurate an optimum.
//!
//! `cargo bench --bench time_vs_error` sweeps, on `problems/wei2017.toml` and
//! `problems/bridge_stress.toml` (another active set), the solver (flexopt's SQP with exact
//! gradients and with central differences, the constrained Nelder-Mead, the `slsqp` crate),
//! the number of starts (10, 30, 100, 300, 1000) and the stopping tolerance (1e-4, 1e-6,
//! 1e-8, and 1e-10 for SQP), all from the same seeded starts on two threads. Each setting
//! runs 5 times; it records the median wall time, the model evaluations, the error of the
//! best feasible objective against the reference (flexopt's SQP at 1e-12 from 1000 starts,
//! KKT-checked), the share of starts that reach the global optimum (1e-3 relative) and the
//! largest constraint violation of the best design. Writes `results/bench/time_vs_error.json`,
//! the table as `results/bench/time_vs_error.txt`, and `results/bench/time_vs_error.png` (every setting a dot; each solver's line is its
//! frontier, the smallest error reached within a given time), and prints a table.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use flexopt::optim::finite_differences::CentralDifferences;
use flexopt::optim::multistart::{self, Sampling};
use flexopt::optim::nelder_mead::{self, NelderMeadSettings};
use flexopt::optim::sqp::{self, SqpSettings};
use flexopt::optim::{Problem, Status};
use flexopt::problem::nlp::DesignNlp;
use flexopt::problem::Problem as DesignProblem;
use flexopt::report::plot::{draw_legend, render_png, FAMILY};
use flexopt::report::write_json;
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Serialize;

#[path = "support/peer.rs"]
mod peer;

const REPEATS: usize = 5;
const STARTS: [usize; 5] = [10, 30, 100, 300, 1000];
const PROBLEMS: [&str; 2] = ["problems/wei2017.toml", "problems/bridge_stress.toml"];

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
enum Solver {
    SqpExact,
    SqpFiniteDifferences,
    NelderMead,
    SlsqpCrate,
}

impl Solver {
    const ALL: [Solver; 4] = [
        Solver::SqpExact,
        Solver::SqpFiniteDifferences,
        Solver::NelderMead,
        Solver::SlsqpCrate,
    ];

    fn tolerances(self) -> &'static [f64] {
        match self {
            Solver::SqpExact | Solver::SqpFiniteDifferences => &[1e-4, 1e-6, 1e-8, 1e-10],
            _ => &[1e-4, 1e-6, 1e-8],
        }
    }

    fn label(self) -> &'static str {
        match self {
            Solver::SqpExact => "SQP, exact gradients",
            Solver::SqpFiniteDifferences => "SQP, central differences",
            Solver::NelderMead => "Nelder-Mead",
            Solver::SlsqpCrate => "slsqp crate",
        }
    }
}

/// Counts the model evaluations of a problem (with or without gradients).
struct Counting<'a> {
    inner: &'a dyn Problem,
    count: AtomicUsize,
}

impl Problem for Counting<'_> {
    fn dimension(&self) -> usize {
        self.inner.dimension()
    }
    fn bounds(&self) -> (&[f64], &[f64]) {
        self.inner.bounds()
    }
    fn equality_count(&self) -> usize {
        self.inner.equality_count()
    }
    fn constraint_count(&self) -> usize {
        self.inner.constraint_count()
    }
    fn evaluate(&self, x: &[f64], c: &mut [f64]) -> f64 {
        self.count.fetch_add(1, Ordering::Relaxed);
        self.inner.evaluate(x, c)
    }
    fn evaluate_with_gradient(
        &self,
        x: &[f64],
        c: &mut [f64],
        g: &mut [f64],
        j: &mut [f64],
    ) -> f64 {
        self.count.fetch_add(1, Ordering::Relaxed);
        self.inner.evaluate_with_gradient(x, c, g, j)
    }
}

/// One end point: objective (solver's, minimized), violation, converged.
type End = (f64, f64, bool);

fn solve_all(
    nlp: &DesignNlp,
    starts: &[Vec<f64>],
    solver: Solver,
    tol: f64,
    pool: &rayon::ThreadPool,
) -> (Vec<End>, usize, Duration) {
    let counting = Counting {
        inner: nlp,
        count: AtomicUsize::new(0),
    };
    let begin = Instant::now();
    let ends: Vec<End> = pool.install(|| match solver {
        Solver::SqpExact | Solver::SqpFiniteDifferences => {
            let fd = CentralDifferences::new(&counting);
            let p: &dyn Problem = if solver == Solver::SqpExact {
                &counting
            } else {
                &fd
            };
            let settings = SqpSettings {
                tolerance: tol,
                max_iterations: 500,
                ..SqpSettings::default()
            };
            starts
                .par_iter()
                .map(|x0| {
                    let s = sqp::solve(p, x0, &settings);
                    (s.objective, s.max_violation, s.status == Status::Converged)
                })
                .collect()
        }
        Solver::NelderMead => {
            let settings = NelderMeadSettings {
                tolerance: tol,
                ..NelderMeadSettings::default()
            };
            starts
                .par_iter()
                .map(|x0| {
                    let s = nelder_mead::solve(&counting, x0, &settings);
                    (s.objective, s.max_violation, s.status == Status::Converged)
                })
                .collect()
        }
        Solver::SlsqpCrate => starts
            .par_iter()
            .map(|x0| {
                let (f, v, evals) = peer::slsqp_solve(nlp, x0, tol);
                counting.count.fetch_add(evals, Ordering::Relaxed);
                (f, v, v <= 1e-8)
            })
            .collect(),
    });
    (
        ends,
        counting.count.load(Ordering::Relaxed),
        begin.elapsed(),
    )
}

#[derive(Debug, Clone, Serialize)]
struct Record {
    problem: String,
    solver: Solver,
    starts: usize,
    tolerance: f64,
    median_ms: f64,
    times_ms: Vec<f64>,
    evaluations: usize,
    best_objective: Option<f64>,
    /// |best - reference| / |reference|; `null` when no start ended feasible.
    error: Option<f64>,
    global_share: f64,
    max_violation: Option<f64>,
}

#[derive(Debug, Serialize)]
struct Report {
    description: &'static str,
    reference: Vec<(String, f64)>,
    records: Vec<Record>,
}

fn main() {
    // `cargo bench` passes `--bench`; a filter argument is not supported here
    let threads = 2;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    let mut records = Vec::new();
    let mut references = Vec::new();
    for file in PROBLEMS {
        let problem = DesignProblem::load(Path::new(file)).expect("the shipped problem files load");
        let nlp = DesignNlp::new(&problem);
        let n = nlp.dimension();
        let all_starts = multistart::start_points(
            &vec![0.0; n],
            &vec![1.0; n],
            1000,
            problem.search.seed,
            Sampling::Uniform,
        );
        // the reference: the tightest SQP solve from every start, checked for KKT
        let reference_settings = SqpSettings {
            tolerance: 1e-12,
            max_iterations: 1000,
            ..SqpSettings::default()
        };
        let reference = pool.install(|| {
            all_starts
                .par_iter()
                .map(|x0| sqp::solve(&nlp, x0, &reference_settings))
                .filter(|s| s.kkt_residual.is_some_and(|k| k <= 1e-8) && s.max_violation <= 1e-10)
                .map(|s| s.objective)
                .fold(|| f64::INFINITY, f64::min)
                .reduce(|| f64::INFINITY, f64::min)
        });
        assert!(reference.is_finite(), "no KKT-checked reference for {file}");
        eprintln!("{}: reference objective {:.12}", problem.name, -reference);
        references.push((problem.name.clone(), nlp.stated_objective(reference)));
        for solver in Solver::ALL {
            for &tol in solver.tolerances() {
                for count in STARTS {
                    let starts = &all_starts[..count];
                    let mut times = Vec::new();
                    let mut last = None;
                    for _ in 0..REPEATS {
                        let (ends, evaluations, elapsed) =
                            solve_all(&nlp, starts, solver, tol, &pool);
                        times.push(elapsed.as_secs_f64() * 1e3);
                        last = Some((ends, evaluations));
                    }
                    let (ends, evaluations) = last.expect("at least one repeat");
                    times.sort_by(f64::total_cmp);
                    let feasible: Vec<&End> = ends
                        .iter()
                        .filter(|e| e.0.is_finite() && e.1 <= 1e-8)
                        .collect();
                    let best = feasible.iter().min_by(|a, b| a.0.total_cmp(&b.0));
                    let global = feasible
                        .iter()
                        .filter(|e| ((e.0 - reference) / reference).abs() <= 1e-3)
                        .count();
                    let record = Record {
                        problem: problem.name.clone(),
                        solver,
                        starts: count,
                        tolerance: tol,
                        median_ms: times[REPEATS / 2],
                        times_ms: times,
                        evaluations,
                        best_objective: best.map(|e| nlp.stated_objective(e.0)),
                        error: best.map(|e| ((e.0 - reference) / reference).abs()),
                        global_share: global as f64 / count as f64,
                        max_violation: best.map(|e| e.1),
                    };
                    eprintln!(
                        "{:<14} {:<26} {:>5} starts tol {:>6.0e}: {:>9.2} ms, {:>8} evals, error {:>9}, global {:>5.1} %",
                        record.problem,
                        solver.label(),
                        count,
                        tol,
                        record.median_ms,
                        evaluations,
                        record.error.map_or("-".into(), |e| format!("{e:.1e}")),
                        100.0 * record.global_share
                    );
                    records.push(record);
                }
            }
        }
    }
    let text = table(&records);
    print!("{text}");
    flexopt::report::write_atomic(
        Path::new("results/bench/time_vs_error.txt"),
        text.as_bytes(),
    )
    .expect("results/bench is writable");
    let report = Report {
        description: "Run time against error of the best objective; see benches/time_vs_error.rs",
        reference: references,
        records,
    };
    write_json(Path::new("results/bench/time_vs_error.json"), &report)
        .expect("results/bench is writable");
    plot(
        Path::new("results/bench/time_vs_error.png"),
        &report.records,
    )
    .expect("the plot is written");
    println!("wrote results/bench/time_vs_error.json, .txt and .png");
}

/// The table, as printed and as written to `results/bench/time_vs_error.txt`.
fn table(records: &[Record]) -> String {
    use std::fmt::Write as _;
    let mut t = String::new();
    let _ = writeln!(
        t,
        "{:<14} {:<26} {:>6} {:>7} {:>10} {:>9} {:>9} {:>8}",
        "problem", "solver", "starts", "tol", "median ms", "evals", "error", "global"
    );
    for r in records {
        let _ = writeln!(
            t,
            "{:<14} {:<26} {:>6} {:>7.0e} {:>10.2} {:>9} {:>9} {:>7.1}%",
            r.problem,
            r.solver.label(),
            r.starts,
            r.tolerance,
            r.median_ms,
            r.evaluations,
            r.error.map_or("-".into(), |e| format!("{e:.1e}")),
            100.0 * r.global_share
        );
    }
    t
}

const COLOURS: [RGBColor; 4] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
];

/// Log-log time against error, one panel per problem, one curve per solver: for each
/// number of starts the point of each tolerance, joined in order of time.
fn plot(path: &Path, records: &[Record]) -> Result<(), flexopt::report::WriteError> {
    let floor = 1e-16;
    render_png(path, (1400, 600), |root| {
        let root = root.titled(
            "Run time against error of the best objective (two threads, median of 5)",
            (FAMILY, 20),
        )?;
        let panels = root.split_evenly((1, PROBLEMS.len()));
        let names: Vec<String> =
            records
                .iter()
                .map(|r| r.problem.clone())
                .fold(Vec::new(), |mut v, n| {
                    if !v.contains(&n) {
                        v.push(n);
                    }
                    v
                });
        for (area, name) in panels.iter().zip(&names) {
            let mine: Vec<&Record> = records.iter().filter(|r| &r.problem == name).collect();
            let tmax = mine.iter().map(|r| r.median_ms).fold(1.0, f64::max) * 2.0;
            let tmin = mine
                .iter()
                .map(|r| r.median_ms)
                .fold(f64::INFINITY, f64::min)
                .max(1e-3)
                / 2.0;
            let mut chart = ChartBuilder::on(area)
                .caption(name, (FAMILY, 16))
                .margin(10)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d((tmin..tmax).log_scale(), (floor..1.0).log_scale())?;
            chart
                .configure_mesh()
                .x_desc("median wall time (ms)")
                .y_desc("relative error of the best objective")
                .y_label_formatter(&|v| format!("{v:.0e}"))
                .x_label_formatter(&|v| format!("{v}"))
                .label_style((FAMILY, 12))
                .draw()?;
            for (k, solver) in Solver::ALL.iter().enumerate() {
                let mut pts: Vec<(f64, f64)> = mine
                    .iter()
                    .filter(|r| r.solver == *solver)
                    .filter_map(|r| r.error.map(|e| (r.median_ms, e.max(floor))))
                    .collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                // the frontier: the smallest error reached within each time
                let mut frontier: Vec<(f64, f64)> = Vec::new();
                for &(t, e) in &pts {
                    let best = frontier.last().map_or(f64::INFINITY, |p| p.1);
                    if e < best {
                        if let Some(&(_, prev)) = frontier.last() {
                            frontier.push((t, prev));
                        }
                        frontier.push((t, e));
                    }
                }
                let colour = COLOURS[k];
                chart
                    .draw_series(LineSeries::new(frontier, colour.stroke_width(2)))?
                    .label(solver.label())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 16, y)], colour.stroke_width(2))
                    });
                chart.draw_series(
                    pts.into_iter()
                        .map(|p| Circle::new(p, 3, colour.mix(0.6).filled())),
                )?;
            }
            draw_legend(&mut chart, 12)?;
        }
        Ok(())
    })
}
