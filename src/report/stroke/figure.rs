//! `stroke.svg`: the outputs against the fraction of the stroke in panels, each quantity with
//! its large deflection (solid) and its linear value (dashed, lighter).

use std::path::Path;

use plotters::prelude::*;

use super::super::plot::{panel_chart, range, register_font, DrawError, FAMILY};
use super::super::{write_atomic, WriteError};
use super::{columns, Column, StrokeRun};
use crate::model::large::report::StrokeReport;

/// The colours of the quantities of one panel, in turn.
const COLOURS: [RGBColor; 4] = [BLUE, RED, GREEN, MAGENTA];
/// A panel's size, pixels, and the panels a row.
const CELL: (u32, u32) = (520, 360);
const COLUMNS: usize = 3;

/// One panel: its title, its y axis's label and the quantities it draws.
struct Panel<'a> {
    title: String,
    y_label: String,
    columns: Vec<&'a Column>,
}

/// The panels: the output's stroke, the amplification, the input's stiffness, the largest
/// stress, each output's parasitic motion across and in rotation, and the natural
/// frequencies where the network has them.
fn panels(all: &[Column]) -> Vec<Panel<'_>> {
    let one = |label: &str, title: &str| {
        let c: Vec<&Column> = all.iter().filter(|c| c.label == label).collect();
        let unit = c.first().map_or("", |c| c.unit);
        Panel {
            title: title.into(),
            y_label: with_unit(label, unit),
            columns: c,
        }
    };
    let several = |prefix: &str, title: &str, unit: &str| Panel {
        title: title.into(),
        y_label: with_unit(prefix.trim_end_matches('_'), unit),
        columns: all.iter().filter(|c| c.label.starts_with(prefix)).collect(),
    };
    let mut panels = vec![
        one("stroke_out", "output stroke"),
        one("amplification", "amplification (secant)"),
        one("k_in", "input stiffness (tangent)"),
        one("stress_max", "largest stress"),
        several("parasitic_across_", "parasitic motion across", "um"),
        several("parasitic_rotation_", "parasitic rotation", "mrad"),
    ];
    let frequencies: Vec<&Column> = all.iter().filter(|c| c.unit == "Hz").collect();
    if !frequencies.is_empty() {
        panels.push(Panel {
            title: "natural frequencies".into(),
            y_label: with_unit("frequency", "Hz"),
            columns: frequencies,
        });
    }
    panels
}

fn with_unit(label: &str, unit: &str) -> String {
    if unit.is_empty() {
        format!("{label} (-)")
    } else {
        format!("{label} ({unit})")
    }
}

/// Draws the figure of `run` into the SVG `path`, whole or not at all.
pub fn stroke_svg(path: &Path, run: &StrokeRun) -> Result<(), WriteError> {
    register_font();
    let all = columns(&run.report);
    let panels = panels(&all);
    let rows = panels.len().div_ceil(COLUMNS) as u32;
    let size = (CELL.0 * COLUMNS as u32, CELL.1 * rows + 40);
    let title = format!(
        "{}: over the stroke, {} (solid) and linear (dashed)",
        run.problem, run.fidelity
    );
    let mut text = String::new();
    (|| -> Result<(), DrawError> {
        let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
        root.fill(&WHITE)?;
        let root = root.titled(&title, (FAMILY, 20))?;
        let areas = root.split_evenly((rows as usize, COLUMNS));
        for (panel, area) in panels.iter().zip(areas) {
            draw_panel(&area, panel, &run.report)?;
        }
        root.present()?;
        Ok(())
    })()
    .map_err(|e| WriteError {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    write_atomic(path, text.as_bytes())
}

/// The curves of one quantity: its large deflection's and its linear model's.
type Curves = (Vec<(f64, f64)>, Vec<(f64, f64)>);

fn curves(c: &Column, r: &StrokeReport) -> Curves {
    let large = r.curve.iter().map(|p| (p.fraction, c.value(p))).collect();
    let linear = r
        .curve
        .iter()
        .map(|p| (p.fraction, c.linear_at(&r.linear, p.fraction)))
        .collect();
    (large, linear)
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    panel: &Panel,
    r: &StrokeReport,
) -> Result<(), DrawError>
where
    DB::ErrorType: 'static,
{
    let drawn: Vec<Curves> = panel.columns.iter().map(|c| curves(c, r)).collect();
    let xr = range(r.curve.iter().map(|p| p.fraction));
    let ys = drawn.iter().flat_map(|(a, b)| a.iter().chain(b));
    // a quantity that stays 0 (held by a mirror axis) is drawn on a plain axis
    let yr = if ys.clone().all(|q| q.1 == 0.0) {
        (-1.0, 1.0)
    } else {
        range(ys.map(|q| q.1))
    };
    let labels = ("fraction of the stroke (-)", panel.y_label.as_str());
    let mut chart = panel_chart(area, &panel.title, labels, xr, yr)?;
    let several = panel.columns.len() > 1;
    for (i, (c, (large, linear))) in panel.columns.iter().zip(&drawn).enumerate() {
        let colour = COLOURS[i % COLOURS.len()];
        let name = if several { c.label.as_str() } else { "" };
        let solid = colour.stroke_width(2);
        chart
            .draw_series(LineSeries::new(large.iter().copied(), solid))?
            .label(format!("large {name}").trim_end().to_string())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], solid));
        let dashed = colour.mix(0.5).stroke_width(2);
        chart
            .draw_series(DashedLineSeries::new(linear.iter().copied(), 6, 4, dashed))?
            .label(format!("linear {name}").trim_end().to_string())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], dashed));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font((FAMILY, 12))
        .draw()?;
    Ok(())
}
