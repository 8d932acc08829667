//! `pareto.json` and `pareto.png`: a trade-off front of [`crate::pareto`].

use std::path::{Path, PathBuf};

use plotters::prelude::*;

use super::folder::OutputSet;
use super::plot::{axis_tick, draw_legend, range, render_png, FAMILY};
use super::{write_json, WriteError};
use crate::pareto::Pareto;

/// Writes `pareto.json` and `pareto.png` into `dir`, added to the folder's set
/// ([`super::folder`]: a run's files there stay, an earlier front is replaced); returns the
/// paths in place.
pub fn write_pareto(dir: &Path, front: &Pareto) -> Result<Vec<PathBuf>, WriteError> {
    let names = ["pareto.json", "pareto.png"];
    let set = OutputSet::begin(dir)?;
    set.write(|set| {
        write_json(&set.path(names[0]), front)?;
        plot(&set.path(names[1]), front)
    })?;
    set.commit_added(&names)
}

fn plot(path: &Path, front: &Pareto) -> Result<(), WriteError> {
    let feasible: Vec<(f64, f64, bool)> = front
        .points
        .iter()
        .filter_map(|p| Some((p.value?, p.objective?, p.on_front)))
        .collect();
    let xr = range(
        feasible
            .iter()
            .map(|q| q.0)
            .chain(front.points.iter().map(|p| p.limit)),
    );
    let yr = range(feasible.iter().map(|q| q.1));
    let title = format!(
        "{}: best {} against {} ({} starts per point)",
        front.problem, front.objective, front.output, front.starts
    );
    render_png(path, (800, 560), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(&title, (FAMILY, 18))
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(64)
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)?;
        chart
            .configure_mesh()
            .x_desc(format!("{} ({})", front.output, front.unit))
            .y_desc(&front.objective)
            .label_style((FAMILY, 13))
            .light_line_style(TRANSPARENT)
            .bold_line_style(BLACK.mix(0.12))
            .x_label_formatter(&|v| axis_tick(*v, xr, 10))
            .y_label_formatter(&|v| axis_tick(*v, yr, 10))
            .draw()?;
        let mut best: Vec<(f64, f64)> = feasible
            .iter()
            .filter(|q| q.2)
            .map(|q| (q.0, q.1))
            .collect();
        best.sort_by(|a, b| a.0.total_cmp(&b.0));
        chart
            .draw_series(LineSeries::new(best.iter().copied(), BLUE.stroke_width(2)))?
            .label("front")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], BLUE.stroke_width(2)));
        chart
            .draw_series(
                best.iter()
                    .map(|&(x, y)| Circle::new((x, y), 4, BLUE.filled())),
            )?
            .label("best design at each limit")
            .legend(|(x, y)| Circle::new((x + 9, y), 4, BLUE.filled()));
        let behind: Vec<_> = feasible.iter().filter(|q| !q.2).collect();
        if !behind.is_empty() {
            chart
                .draw_series(
                    behind
                        .iter()
                        .map(|q| Circle::new((q.0, q.1), 4, RED.stroke_width(1))),
                )?
                .label("dominated (a local optimum)")
                .legend(|(x, y)| Circle::new((x + 9, y), 4, RED.stroke_width(1)));
        }
        draw_legend(&mut chart, 13)?;
        Ok(())
    })
}
