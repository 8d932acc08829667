//! The study's pictures: `zones.png` (every start's optimum, sorted, by zone) and
//! `configurations.png` (each zone's optima drawn to scale).

use std::path::Path;

use plotters::prelude::*;

use super::plot::{draw_legend, format_tick, range, render_png, FAMILY};
use super::WriteError;
use crate::model::Skeleton;
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

fn colour(rank: usize) -> RGBColor {
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
            .y_label_formatter(&|v| format_tick(*v))
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

/// Fig. 5 analogue: the model's drawing of every feasible start's optimum as a chain of
/// members ([`crate::model::Depiction::skeleton`]), one row per zone that has optima, drawn to
/// scale (one mm is as long across as along) with each member at its thickness.
pub(super) fn configurations_png(
    path: &Path,
    problem: &Problem,
    study: &Study,
) -> Result<(), WriteError> {
    let depiction = problem.depiction();
    let lines: Vec<(usize, Skeleton)> = study
        .runs
        .iter()
        .filter_map(|r| Some((r.zone?, depiction.skeleton(&r.x_end)?)))
        .collect();
    let ranks: Vec<usize> = study
        .clustering
        .zones
        .iter()
        .map(|z| z.rank)
        .filter(|&r| lines.iter().any(|l| l.0 == r))
        .collect();
    let pad = 0.5
        * lines
            .iter()
            .flat_map(|l| l.1.thickness_mm.iter().copied())
            .fold(0.0, f64::max);
    let xr = range(lines.iter().flat_map(|l| l.1.nodes_mm.iter().map(|p| p.0)));
    let yr = range(lines.iter().flat_map(|l| l.1.nodes_mm.iter().map(|p| p.1)));
    let (xr, yr) = ((xr.0 - pad, xr.1 + pad), (yr.0 - pad, yr.1 + pad));
    // equal scales: the plot's height follows the drawing's, within reason, and the
    // shorter range grows to fill the plot
    const WIDTH: u32 = 1000;
    const LEFT: u32 = 56;
    const BOTTOM: u32 = 40;
    const CAPTION: u32 = 28;
    const MARGIN: u32 = 10;
    let plot_w = (WIDTH - LEFT - 2 * MARGIN) as f64;
    let per_mm = plot_w / (xr.1 - xr.0);
    let plot_h = ((yr.1 - yr.0) * per_mm).clamp(120.0, 480.0);
    let grow = (plot_h / per_mm - (yr.1 - yr.0)) / 2.0;
    let yr = (yr.0 - grow.max(0.0), yr.1 + grow.max(0.0));
    let shrink = ((yr.1 - yr.0) * per_mm - plot_h).max(0.0) / per_mm / 2.0;
    let yr = (yr.0 + shrink, yr.1 - shrink);
    let row = plot_h as u32 + BOTTOM + CAPTION + 2 * MARGIN;
    let title = format!(
        "{}: configurations by zone ({})",
        problem.name,
        problem.depiction().skeleton_legend()
    );
    let rows = ranks.len().max(1) as u32;
    render_png(path, (WIDTH, 36 + row * rows), |root| {
        let root = root.titled(&title, (FAMILY, 16))?;
        let panels = root.split_evenly((rows as usize, 1));
        for (&rank, area) in ranks.iter().zip(&panels) {
            let count = lines.iter().filter(|l| l.0 == rank).count();
            let mut chart = ChartBuilder::on(area)
                .caption(format!("zone {rank}: {count} starts"), (FAMILY, 15))
                .margin(MARGIN)
                .x_label_area_size(BOTTOM)
                .y_label_area_size(LEFT)
                .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)?;
            chart
                .configure_mesh()
                .x_desc("x (mm)")
                .y_desc("y (mm)")
                .label_style((FAMILY, 12))
                .light_line_style(TRANSPARENT)
                .bold_line_style(BLACK.mix(0.1))
                .x_label_formatter(&|v| format_tick(*v))
                .y_label_formatter(&|v| format_tick(*v))
                .draw()?;
            for (_, skeleton) in lines.iter().filter(|l| l.0 == rank) {
                let members = skeleton
                    .nodes_mm
                    .windows(2)
                    .zip(&skeleton.rigid)
                    .zip(&skeleton.thickness_mm);
                for ((seg, &rigid), &t) in members {
                    let (a, b) = (seg[0], seg[1]);
                    if rigid || t <= 0.0 {
                        chart
                            .draw_series(LineSeries::new([a, b], BLACK.mix(0.4).stroke_width(1)))?;
                        continue;
                    }
                    // the member as a band of its thickness about its centre line
                    let len = (b.0 - a.0).hypot(b.1 - a.1).max(1e-12);
                    let n = (-(b.1 - a.1) / len * t / 2.0, (b.0 - a.0) / len * t / 2.0);
                    let band = vec![
                        (a.0 + n.0, a.1 + n.1),
                        (b.0 + n.0, b.1 + n.1),
                        (b.0 - n.0, b.1 - n.1),
                        (a.0 - n.0, a.1 - n.1),
                    ];
                    chart.draw_series([Polygon::new(band, colour(rank).mix(0.5).filled())])?;
                }
            }
        }
        Ok(())
    })
}
