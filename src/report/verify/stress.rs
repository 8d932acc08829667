//! `stress.png`: the von Mises stress under the actuation, one row per idealization: the
//! whole part, then close-ups of the two hinges where the stress is highest (on the whole
//! part the hinges are a few pixels and the rest is one colour), on one colour scale whose
//! bar at the right has its ticks in MPa; each panel's largest value is marked and valued.

use std::path::Path;

use plotters::prelude::*;

use super::{cells, frame, panel, Chart};
use crate::fe::verify::Verification;
use crate::part::Hinge;
use crate::report::plot::{render_png, DrawError, FAMILY};
use crate::report::WriteError;

/// A colour of the scale from blue (low) through green to red (high), `t` in [0, 1].
fn heat(t: f64) -> RGBColor {
    let t = t.clamp(0.0, 1.0);
    let (r, g, b) = if t < 0.5 {
        let s = t / 0.5;
        (0.0, s, 1.0 - s)
    } else {
        let s = (t - 0.5) / 0.5;
        (s, 1.0 - s, 0.0)
    };
    RGBColor((255.0 * r) as u8, (255.0 * g) as u8, (255.0 * b) as u8)
}

/// The pixels of the colour bar's strip at the right, and of each close-up's width.
const BAR: u32 = 120;
const CLOSE_UP: u32 = 420;

/// A tick step of about a fifth of `top`: 1, 2 or 5 times a power of ten.
fn tick_step(top: f64) -> f64 {
    let raw = top / 5.0;
    let power = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * power)
        .find(|&s| s >= raw)
        .unwrap_or(10.0 * power)
}

/// The node of the largest von Mises stress (m), on the half mesh.
fn largest(v: &Verification, k: usize) -> ([f64; 2], f64) {
    let f = &v.results[k].fields;
    let (n, top) = f
        .von_mises
        .iter()
        .copied()
        .enumerate()
        .fold(
            (0, 0.0),
            |best, (n, s)| if s > best.1 { (n, s) } else { best },
        );
    (f.mesh.nodes[n], top)
}

/// The window (mm) a close-up of `h` shows: its thin section and the roots of the bodies it
/// joins, `aspect` (height over width) as the close-up's plot is, so that it is to scale.
fn window(h: &Hinge, aspect: f64) -> ((f64, f64), (f64, f64)) {
    let mid = [
        0.5 * (h.start[0] + h.end[0]) * 1e3,
        0.5 * (h.start[1] + h.end[1]) * 1e3,
    ];
    let length = (h.end[0] - h.start[0]).hypot(h.end[1] - h.start[1]) * 1e3;
    let half = 0.75 * length + (1.5 * h.thickness + h.fillet) * 1e3;
    let tall = half * aspect;
    (
        (mid[0] - half, mid[0] + half),
        (mid[1] - tall, mid[1] + tall),
    )
}

fn inside(p: (f64, f64), (xr, yr): ((f64, f64), (f64, f64))) -> bool {
    (xr.0..=xr.1).contains(&p.0) && (yr.0..=yr.1).contains(&p.1)
}

/// Whether `p` (mm) is on the hinge `h`: within its root's half-thickness and fillet of its
/// centre line (the window shows more: the bodies around it, and other hinges' ends).
fn on(h: &Hinge, p: (f64, f64)) -> bool {
    let (a, b) = (
        (h.start[0] * 1e3, h.start[1] * 1e3),
        (h.end[0] * 1e3, h.end[1] * 1e3),
    );
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let t =
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / (dx * dx + dy * dy).max(1e-30)).clamp(0.0, 1.0);
    let d = (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy);
    d <= (0.5 * h.root + h.fillet) * 1e3 + 1e-9
}

/// The largest nodal stress on each hinge, on the half mesh or its mirror image, and where
/// (mm).
fn hinge_peaks(v: &Verification, k: usize) -> Vec<(usize, f64, (f64, f64))> {
    let f = &v.results[k].fields;
    let mut peaks: Vec<(usize, f64, (f64, f64))> = v
        .part
        .hinges
        .iter()
        .enumerate()
        .map(|(i, h)| {
            let mut best = (i, 0.0, (0.0, 0.0));
            let images: &[f64] = if v.whole_part { &[1.0] } else { &[1.0, -1.0] };
            for (node, &s) in f.mesh.nodes.iter().zip(&f.von_mises) {
                for p in images.iter().map(|&k| (k * node[0] * 1e3, node[1] * 1e3)) {
                    if s > best.1 && on(h, p) {
                        best = (i, s, p);
                    }
                }
            }
            best
        })
        .collect();
    peaks.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    peaks
}

/// The two hinges to show close: the most stressed, and the most stressed of the others that
/// is not its mirror image (which shows the same).
fn close_ups(v: &Verification, k: usize) -> Vec<(usize, f64, (f64, f64))> {
    let peaks = hinge_peaks(v, k);
    let mut chosen: Vec<(usize, f64, (f64, f64))> = Vec::new();
    for p in peaks {
        let h = &v.part.hinges[p.0];
        let mirror_of_chosen = chosen.iter().any(|c| {
            let o = &v.part.hinges[c.0];
            let (a, b) = (h.start[0] + h.end[0], o.start[0] + o.end[0]);
            (a + b).abs() < 1e-9 && (h.start[1] + h.end[1] - o.start[1] - o.end[1]).abs() < 1e-9
        });
        if chosen.len() < 2 && !mirror_of_chosen {
            chosen.push(p);
        }
    }
    chosen
}

/// Marks `at` (mm) with a cross and its value in MPa beside it, inside the chart's range
/// `xr`.
fn mark(chart: &mut Chart, at: (f64, f64), value: f64, xr: (f64, f64)) -> Result<(), DrawError> {
    chart.draw_series(std::iter::once(Cross::new(at, 8, BLACK.stroke_width(3))))?;
    let label = format!("max {:.1} MPa", value * 1e-6);
    // the label to the left of a mark in the right half, so that it stays in the panel
    let (dx, anchor) = if at.0 > 0.5 * (xr.0 + xr.1) {
        (-10, plotters::style::text_anchor::HPos::Right)
    } else {
        (10, plotters::style::text_anchor::HPos::Left)
    };
    let style = TextStyle::from((FAMILY, 15).into_font()).color(&BLACK).pos(
        plotters::style::text_anchor::Pos::new(anchor, plotters::style::text_anchor::VPos::Center),
    );
    chart.draw_series(std::iter::once(
        EmptyElement::at(at) + Text::new(label, (dx, -14), style),
    ))?;
    Ok(())
}

/// Draws the cells of result `k` into `chart`, cut to the chart's range (the chart does not
/// clip what it draws), their colour on the scale up to `top`.
fn draw_cells(
    chart: &mut Chart,
    v: &Verification,
    k: usize,
    range: ((f64, f64), (f64, f64)),
    top: f64,
) -> Result<(), DrawError> {
    use geo::BooleanOps;
    let (xr, yr) = range;
    let frame = geo::Rect::new((xr.0, yr.0), (xr.1, yr.1)).to_polygon();
    let mut shapes: Vec<(Vec<(f64, f64)>, f64)> = Vec::new();
    for (corners, value) in cells(v, k, &|_| [0.0, 0.0]) {
        let within = corners.iter().filter(|&&p| inside(p, range)).count();
        if within == corners.len() {
            shapes.push((corners, value));
        } else if within > 0 {
            let cell = geo::Polygon::new(corners.into(), vec![]);
            for piece in cell.intersection(&frame) {
                let outline = piece.exterior().coords().map(|c| (c.x, c.y)).collect();
                shapes.push((outline, value));
            }
        }
    }
    chart.draw_series(
        shapes
            .into_iter()
            .map(|(outline, value)| Polygon::new(outline, heat(value / top).filled())),
    )?;
    Ok(())
}

/// The colour bar: the scale from 0 to `top` (Pa), ticks in MPa at its right, each
/// idealization's largest value (`marks`, Pa) a line across it.
fn colour_bar(
    area: &DrawingArea<BitMapBackend, plotters::coord::Shift>,
    top: f64,
    marks: &[f64],
) -> Result<(), DrawError> {
    let top_mpa = top * 1e-6;
    let (w, h) = area.dim_in_pixel();
    // the bar 28 px wide, its labels in the margin at its right (drawn by hand: the axis's
    // own labels run into the bar)
    let mut chart = ChartBuilder::on(area)
        .margin_top(40)
        .margin_bottom(60)
        .margin_left(12)
        .margin_right(w as i32 - 12 - 28)
        .caption("MPa", (FAMILY, 15))
        .build_cartesian_2d(0.0..1.0, 0.0..top_mpa)?;
    let steps = (h / 2).max(50);
    chart.draw_series((0..steps).map(|s| {
        let (a, b) = (s as f64 / steps as f64, (s + 1) as f64 / steps as f64);
        Rectangle::new(
            [(0.0, a * top_mpa), (1.0, b * top_mpa)],
            heat(0.5 * (a + b)).filled(),
        )
    }))?;
    let step = tick_step(top_mpa);
    let style =
        TextStyle::from((FAMILY, 14).into_font()).pos(plotters::style::text_anchor::Pos::new(
            plotters::style::text_anchor::HPos::Left,
            plotters::style::text_anchor::VPos::Center,
        ));
    let ticks = (0..).map(|i| i as f64 * step).take_while(|&t| t <= top_mpa);
    for t in ticks {
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(1.0, t), (1.35, t)],
            BLACK.stroke_width(1),
        )))?;
        chart.draw_series(std::iter::once(
            EmptyElement::at((1.0, t)) + Text::new(format!("{t:.0}"), (14, 0), style.clone()),
        ))?;
    }
    for value in marks {
        let y = value * 1e-6;
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(0.0, y), (1.0, y)],
            BLACK.stroke_width(2),
        )))?;
    }
    Ok(())
}

/// The pixels a panel's plot loses to its caption, axes and margins ([`panel`]): across, and
/// down.
const PANEL_FRAME: (u32, u32) = (44 + 20, 36 + 20 + 26);

/// `stress.png`.
pub(super) fn stress_png(path: &Path, problem: &str, v: &Verification) -> Result<(), WriteError> {
    let rows = v.results.len();
    let (xr, yr, (part_w, part_h)) = frame(v, 1);
    let size = (part_w + 2 * CLOSE_UP + BAR, part_h * rows as u32 + 40);
    let row_h = (size.1 - 40) / rows as u32;
    let aspect = f64::from(row_h - PANEL_FRAME.1) / f64::from(CLOSE_UP - PANEL_FRAME.0);
    let tops: Vec<([f64; 2], f64)> = (0..rows).map(|k| largest(v, k)).collect();
    let top = tops.iter().map(|t| t.1).fold(f64::MIN_POSITIVE, f64::max);
    let title = format!(
        "{problem}: von Mises stress under the actuation, the whole part and its most \
         stressed hinges (boxed)"
    );
    render_png(path, size, |root| {
        let root = root.titled(&title, (FAMILY, 20))?;
        let (main, bar) = root.split_horizontally(size.0 - BAR);
        let marks: Vec<f64> = tops.iter().map(|t| t.1).collect();
        colour_bar(&bar, top, &marks)?;
        for (k, row) in main.split_evenly((rows, 1)).iter().enumerate() {
            let name = v.results[k].idealization.name();
            let (whole, near) = row.split_horizontally(part_w);
            let (node, value) = tops[k];
            let caption = format!("{name}: whole part, max {:.1} MPa (x)", value * 1e-6);
            let mut part = panel(&whole, &caption, xr, yr)?;
            draw_cells(&mut part, v, k, (xr, yr), top)?;
            let at = (node[0] * 1e3, node[1] * 1e3);
            part.draw_series(
                [at, (-at.0, at.1)]
                    .into_iter()
                    .map(|p| Cross::new(p, 8, BLACK.stroke_width(3))),
            )?;
            for (area, (i, peak, spot)) in near.split_evenly((1, 2)).iter().zip(close_ups(v, k)) {
                let h = &v.part.hinges[i];
                let w = window(h, aspect);
                let mut chart = panel(area, &format!("{name}: {}", h.name), w.0, w.1)?;
                draw_cells(&mut chart, v, k, w, top)?;
                mark(&mut chart, spot, peak, w.0)?;
                part.draw_series(std::iter::once(Rectangle::new(
                    [(w.0 .0, w.1 .0), (w.0 .1, w.1 .1)],
                    BLACK.stroke_width(1),
                )))?;
            }
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::tick_step;

    #[test]
    fn the_colour_bar_ticks_a_fifth_of_the_range_in_round_steps() {
        for (top, step) in [
            (155.7, 50.0),
            (149.0, 50.0),
            (99.0, 20.0),
            (0.9, 0.2),
            (1000.0, 200.0),
        ] {
            assert_eq!(tick_step(top), step, "{top}");
        }
    }
}
