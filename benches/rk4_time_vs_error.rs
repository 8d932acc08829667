//! Run time against error of the Runge-Kutta step response (`cargo bench --bench
//! rk4_time_vs_error`): for the damping ratios and frequencies of paper 001's Table 4 and
//! requested accuracies from 1e-2 to 1e-12, the step `Oscillator::step_for` picks, the time
//! of one `step_response` (median of 21) and its largest error against the exact solution.
//! Writes `results/bench/rk4_time_vs_error.json` and `.png`.

use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

use flexopt::dynamics::{max_relative_error, step_response, Oscillator, PAPER001_TABLE4};
use flexopt::report::plot::{draw_legend, render_png, FAMILY};
use flexopt::report::write_json;
use plotters::prelude::*;
use serde::Serialize;

#[derive(Serialize)]
struct Record {
    frequency: f64,
    zeta: f64,
    tolerance: f64,
    step: f64,
    median_us: f64,
    max_relative_error: f64,
}

fn main() {
    let mut records = Vec::new();
    for &(f, zeta) in &PAPER001_TABLE4 {
        let osc = Oscillator::from_frequency(f, zeta);
        for k in 2..=12 {
            let tol = 10f64.powi(-k);
            let mut times: Vec<f64> = (0..21)
                .map(|_| {
                    let t = Instant::now();
                    black_box(step_response(black_box(&osc), 1.0, 0.02, tol));
                    t.elapsed().as_secs_f64() * 1e6
                })
                .collect();
            times.sort_by(f64::total_cmp);
            let h = osc.step_for(tol);
            let err = max_relative_error(&osc, 1.0, h, 10.0 / (zeta * osc.omega()));
            println!("f {f:>7} Hz zeta {zeta:.4} tol {tol:.0e}: step {h:.3e} s, {:>9.1} us, error {err:.1e}", times[10]);
            records.push(Record {
                frequency: f,
                zeta,
                tolerance: tol,
                step: h,
                median_us: times[10],
                max_relative_error: err,
            });
        }
    }
    write_json(Path::new("results/bench/rk4_time_vs_error.json"), &records)
        .expect("results/bench is writable");
    plot(Path::new("results/bench/rk4_time_vs_error.png"), &records).expect("the plot is written");
    println!("wrote results/bench/rk4_time_vs_error.json and .png");
}

fn plot(path: &Path, records: &[Record]) -> Result<(), flexopt::report::WriteError> {
    render_png(path, (900, 600), |root| {
        let tmin = records
            .iter()
            .map(|r| r.median_us)
            .fold(f64::INFINITY, f64::min)
            / 2.0;
        let tmax = records.iter().map(|r| r.median_us).fold(0.0, f64::max) * 2.0;
        let mut chart = ChartBuilder::on(root)
            .caption(
                "RK4 step response: run time against error (Table 4 of paper 001)",
                (FAMILY, 18),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d((tmin..tmax).log_scale(), (1e-16f64..1.0).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("median time of one step response (us)")
            .y_desc("largest error relative to Sp")
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .label_style((FAMILY, 12))
            .draw()?;
        let colours = [BLUE, RED, GREEN, MAGENTA, CYAN, BLACK];
        for (k, &(f, zeta)) in PAPER001_TABLE4.iter().enumerate() {
            let pts: Vec<(f64, f64)> = records
                .iter()
                .filter(|r| r.frequency == f && r.zeta == zeta)
                .map(|r| (r.median_us, r.max_relative_error.max(1e-16)))
                .collect();
            let c = colours[k];
            chart
                .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))?
                .label(format!("{f} Hz, zeta {zeta}"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 16, y)], c.stroke_width(2))
                });
            chart.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, c.filled())))?;
        }
        draw_legend(&mut chart, 12)?;
        Ok(())
    })
}
