//! The study's picture `zones.png`: every start's optimum, sorted, by zone
//! (`configurations.png` is [`super::configurations`]).

use std::path::Path;

use plotters::prelude::*;

use super::plot::{axis_tick, draw_legend, range, render_png, FAMILY};
use super::WriteError;
use crate::problem::Problem;
use crate::study::Study;

const ZONE_COLOURS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
];

pub(super) fn colour(rank: usize) -> RGBColor {
    ZONE_COLOURS[(rank - 1) % ZONE_COLOURS.len()]
}

/// Fig. 4 analogue: every feasible start's optimum, sorted, coloured by zone, with the
/// zone thresholds.
pub(super) fn zones_png(path: &Path, problem: &Problem, study: &Study) -> Result<(), WriteError> {
    // in the objective's display unit, as the summary prints it
    let unit = super::display::output_unit(problem, problem.objective.index);
    let mut pts: Vec<(f64, usize)> = study
        .runs
        .iter()
        .filter_map(|r| r.zone.map(|z| (unit.from_si(r.objective), z)))
        .collect();
    pts.sort_by(|a, b| b.0.total_cmp(&a.0));
    let thresholds: Vec<f64> = problem
        .zones
        .thresholds
        .iter()
        .map(|&t| unit.from_si(t))
        .collect();
    let title = format!(
        "{}: optima of {} starts, sorted",
        problem.name,
        study.runs.len()
    );
    let ylabel = if problem.objective.absolute {
        format!("|{}|", problem.objective.output)
    } else {
        problem.objective.output.clone()
    };
    let ylabel = match unit.name.as_str() {
        "1" | "" => ylabel,
        u => format!("{ylabel} ({u})"),
    };
    render_png(path, (900, 560), |root| {
        let yr = range(pts.iter().map(|p| p.0).chain(thresholds.iter().copied()));
        let mut chart = ChartBuilder::on(root)
            .caption(&title, (FAMILY, 20))
            .margin(12)
            // room for the last tick's label, centred on the axis's end
            .margin_right(36)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d(0f64..(pts.len().max(1) as f64), yr.0..yr.1)?;
        chart
            .configure_mesh()
            .x_desc("start, sorted by its optimum")
            .y_desc(&ylabel)
            .label_style((FAMILY, 13))
            .light_line_style(TRANSPARENT)
            .bold_line_style(BLACK.mix(0.12))
            .y_labels(10)
            .y_label_formatter(&|v| axis_tick(*v, yr, 10))
            // starts are counted: whole ticks
            .x_label_formatter(&|v| format!("{v:.0}"))
            .draw()?;
        for &t in &thresholds {
            chart.draw_series(LineSeries::new(
                [(0.0, t), (pts.len() as f64, t)],
                BLACK.mix(0.4).stroke_width(1),
            ))?;
        }
        for rank in 1..=study.clustering.zones.len() {
            let series: Vec<(f64, f64)> = pts
                .iter()
                .enumerate()
                .filter(|(_, p)| p.1 == rank)
                .map(|(i, p)| (i as f64 + 0.5, p.0))
                .collect();
            if series.is_empty() {
                continue;
            }
            let n = series.len();
            chart
                .draw_series(
                    series
                        .into_iter()
                        .map(|p| Circle::new(p, 3, colour(rank).filled())),
                )?
                .label(format!("zone {rank}: {n}"))
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, colour(rank).filled()));
        }
        draw_legend(&mut chart, 13)?;
        Ok(())
    })
}
