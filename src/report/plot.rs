//! PNG plots with plotters, drawn with the DejaVu Sans font that ships in `assets/fonts`,
//! so no system font library is needed.

use std::path::Path;
use std::sync::Once;

use plotters::prelude::*;
use plotters::style::FontStyle;

use super::{write_with, WriteError};

const FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
/// The family the bundled font is registered under.
pub const FAMILY: &str = "sans-serif";

/// Registers the bundled font with plotters, once per process.
pub fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The bytes are a valid TrueType font checked in with the source; a failure here
        // is a broken build, caught by the plot tests.
        plotters::style::register_font(FAMILY, FontStyle::Normal, FONT).unwrap_or_else(|_| {
            panic!("the bundled font assets/fonts/DejaVuSans.ttf does not load")
        });
    });
}

/// One panel of a figure: a curve of `y` against `x`.
#[derive(Debug, Clone)]
pub struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub points: Vec<(f64, f64)>,
    /// Limits on `y` drawn across the panel (a constraint's).
    pub limits: Vec<f64>,
    /// A point marked on the curve (the design the sweep is taken around).
    pub marker: Option<(f64, f64)>,
}

/// The error a drawing closure of [`render_png`] returns.
pub type DrawError = Box<dyn std::error::Error>;

/// Draws a PNG of `size` pixels into `path`, whole or not at all: the bundled font is
/// registered, the area filled white and handed to `draw`, and the image presented.
pub fn render_png(
    path: &Path,
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<BitMapBackend, plotters::coord::Shift>) -> Result<(), DrawError>,
) -> Result<(), WriteError> {
    register_font();
    write_with(path, |tmp| {
        (|| -> Result<(), DrawError> {
            let root = BitMapBackend::new(tmp, size).into_drawing_area();
            root.fill(&WHITE)?;
            draw(&root)?;
            root.present()?;
            Ok(())
        })()
        .map_err(|e| std::io::Error::other(e.to_string()))
    })
}

/// Draws the legend of `chart`'s labelled series in a framed, half-clear box.
pub fn draw_legend<'a, CT: plotters::coord::CoordTranslate>(
    chart: &mut ChartContext<'a, BitMapBackend<'a>, CT>,
    font_size: u32,
) -> Result<(), DrawError> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font((FAMILY, font_size))
        .draw()?;
    Ok(())
}

/// Draws `panels` on a grid, `columns` wide, each `cell` pixels, into the PNG `path`.
pub fn line_panels(
    path: &Path,
    title: &str,
    panels: &[Panel],
    columns: usize,
    cell: (u32, u32),
) -> Result<(), WriteError> {
    let columns = columns.clamp(1, panels.len().max(1));
    let rows = panels.len().div_ceil(columns).max(1);
    let size = (cell.0 * columns as u32, cell.1 * rows as u32 + 40);
    render_png(path, size, |root| {
        let root = root.titled(title, (FAMILY, 22))?;
        for (panel, area) in panels.iter().zip(root.split_evenly((rows, columns))) {
            draw_panel(&area, panel)?;
        }
        Ok(())
    })
}

/// Padded range of finite values, never empty, and at least 1e-4 of their size wide: a spread
/// at the rounding level (100 starts ending at one optimum) is drawn flat, not magnified
/// into a curve whose tick labels all read the same.
pub fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let size = lo.abs().max(hi.abs());
    let pad = if hi > lo {
        (0.05 * (hi - lo)).max(1e-4 * size)
    } else {
        0.5 * size.max(1e-12)
    };
    (lo - pad, hi + pad)
}

/// A chart of one panel on `area`: its caption `title`, its axes over `xr` and `yr` with
/// their `labels` (x, y) and ticks, a light grid; drawn, for the caller's series.
pub fn panel_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    labels: (&str, &str),
    xr: (f64, f64),
    yr: (f64, f64),
) -> Result<Chart2d<'a, DB>, DrawError>
where
    DB::ErrorType: 'static,
{
    let mut chart = ChartBuilder::on(area)
        .caption(title, (FAMILY, 16))
        .margin(10)
        .x_label_area_size(44)
        .y_label_area_size(72)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)?;
    chart
        .configure_mesh()
        .x_desc(labels.0)
        .y_desc(labels.1)
        .label_style((FAMILY, 12))
        .axis_desc_style((FAMILY, 13))
        .x_labels(6)
        .y_labels(7)
        .light_line_style(TRANSPARENT)
        .bold_line_style(BLACK.mix(0.12))
        .y_label_formatter(&|v| axis_tick(*v, yr, 7))
        .x_label_formatter(&|v| axis_tick(*v, xr, 6))
        .draw()?;
    Ok(chart)
}

/// A chart of [`panel_chart`]: `f64` on both axes.
pub type Chart2d<'a, DB> = ChartContext<
    'a,
    DB,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    p: &Panel,
) -> Result<(), Box<dyn std::error::Error + 'static>>
where
    DB::ErrorType: 'static,
{
    let xr = range(p.points.iter().map(|q| q.0));
    // a limit far off the curve would squash it: only those within reach widen the range
    let ys: Vec<f64> = p
        .points
        .iter()
        .map(|q| q.1)
        .filter(|v| v.is_finite())
        .collect();
    let (lo, hi) = range(ys.iter().copied());
    let reach = 2.0 * (hi - lo);
    let near: Vec<f64> = p
        .limits
        .iter()
        .copied()
        .filter(|&l| l > lo - reach && l < hi + reach)
        .collect();
    let yr = range(ys.iter().copied().chain(near.iter().copied()));
    let mut chart = panel_chart(area, &p.title, (&p.x_label, &p.y_label), xr, yr)?;
    for &l in &near {
        chart.draw_series(DashedLineSeries::new(
            [(xr.0, l), (xr.1, l)],
            6,
            4,
            RED.mix(0.8).stroke_width(2),
        ))?;
    }
    // a gap where the model gives no finite value
    for run in p.points.split(|q| !q.1.is_finite()) {
        chart.draw_series(LineSeries::new(run.iter().copied(), BLUE.stroke_width(2)))?;
    }
    if let Some((x, y)) = p.marker.filter(|m| m.0.is_finite() && m.1.is_finite()) {
        chart.draw_series(DashedLineSeries::new(
            [(x, yr.0), (x, yr.1)],
            4,
            4,
            BLACK.mix(0.5).stroke_width(1),
        ))?;
        chart.draw_series([Circle::new((x, y), 5, BLACK.filled())])?;
    }
    Ok(())
}

/// Compact tick labels with up to 5 significant digits: 12.5, 0.01195, 7e6, 2.5e-4.
pub fn format_tick(v: f64) -> String {
    tick_label(v, None)
}

/// A tick's label on an axis spanning `range` with about `ticks` labels: [`format_tick`]'s
/// five significant digits, or as many more as ticks that close need to read apart (an
/// axis from 150.405 to 150.42 labels 150.406 and 150.408, not "150.41" for both); a tick
/// within round-off of zero reads 0.
pub fn axis_tick(v: f64, range: (f64, f64), ticks: usize) -> String {
    let step = (range.1 - range.0).abs() / ticks.max(1) as f64;
    if !(step > 0.0 && step.is_finite()) {
        return format_tick(v);
    }
    if v.abs() < 1e-9 * step {
        return "0".into();
    }
    tick_label(v, Some(-step.log10().floor() as i32))
}

/// `v` to 5 significant digits, or to `decimals` after the point where that is more
/// (scientific outside 1e-3 .. 1e5, its mantissa as long as the same resolution needs).
fn tick_label(v: f64, decimals: Option<i32>) -> String {
    let a = v.abs();
    let trim = |s: &str| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if a != 0.0 && !(1e-3..1e5).contains(&a) {
        let exponent = a.log10().floor() as i32;
        let mantissa = decimals.map_or(3, |d| (d + exponent).max(3)).min(15) as usize;
        let s = format!("{v:.mantissa$e}");
        return match s.split_once('e') {
            Some((m, e)) => format!("{}e{e}", trim(m)),
            None => s,
        };
    }
    let own = if a == 0.0 {
        0
    } else {
        4 - a.log10().floor() as i32
    };
    let decimals = own.max(decimals.unwrap_or(0)).clamp(0, 15) as usize;
    let s = trim(&format!("{v:.decimals$}"));
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// zones.png of a stroke near 150.41 um spread over 15 nm: ticks 2 nm apart, which five
    /// significant digits would all label "150.41".
    #[test]
    fn ticks_close_together_read_apart() {
        for (scale, lo, hi) in [(1.0, 150.405, 150.42), (1e-6, 150.405e-6, 150.42e-6)] {
            let ticks: Vec<f64> = (0..8)
                .map(|i| (150.406 + 0.002 * i as f64) * scale)
                .collect();
            let labels: Vec<String> = ticks.iter().map(|&t| axis_tick(t, (lo, hi), 10)).collect();
            let mut distinct = labels.clone();
            distinct.dedup();
            assert_eq!(distinct.len(), ticks.len(), "{labels:?}");
            for (t, l) in ticks.iter().zip(&labels) {
                let back: f64 = l.parse().unwrap();
                assert!((back - t).abs() <= 1e-9 * t.abs(), "{l} for {t}");
            }
            let five: Vec<String> = ticks.iter().map(|&t| format_tick(t)).collect();
            assert!(five.windows(2).any(|w| w[0] == w[1]), "{five:?}");
        }
        assert_eq!(axis_tick(150.408, (150.405, 150.42), 10), "150.408");
        assert_eq!(
            axis_tick(1.50408e-4, (1.50405e-4, 1.5042e-4), 10),
            "1.50408e-4"
        );
        // a wide axis keeps five digits, and a tick at round-off from zero reads 0
        assert_eq!(axis_tick(12.5, (0.0, 100.0), 10), format_tick(12.5));
        assert_eq!(axis_tick(2.8e-15, (-1.0, 1.0), 10), "0");
    }
}
