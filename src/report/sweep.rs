//! `<variable>.json` and `<variable>.png`: the curves of a sweep of [`crate::sweep`].

use std::path::{Path, PathBuf};

use super::plot::{line_panels, Panel};
use super::{write_json, WriteError};
use crate::sweep::Sweep;

/// Writes `<variable>.json` and `<variable>.png` into `dir`.
pub fn write_sweep(dir: &Path, sweep: &Sweep) -> Result<Vec<PathBuf>, WriteError> {
    let json = dir.join(format!("{}.json", sweep.variable));
    let png = dir.join(format!("{}.png", sweep.variable));
    write_json(&json, sweep)?;
    let panels: Vec<Panel> = sweep
        .order
        .iter()
        .map(|name| Panel {
            title: name.clone(),
            x_label: format!("{} ({})", sweep.variable, sweep.unit),
            y_label: format!("{name} ({})", sweep.output_units[name]),
            points: sweep
                .values
                .iter()
                .zip(&sweep.outputs[name])
                .map(|(&x, y)| (x, y.unwrap_or(f64::NAN)))
                .collect(),
        })
        .collect();
    let columns = if panels.len() == 1 { 1 } else { 4 };
    let cell = if panels.len() == 1 {
        (720, 480)
    } else {
        (420, 300)
    };
    line_panels(
        &png,
        &format!("{}: outputs against {}", sweep.problem, sweep.variable),
        &panels,
        columns,
        cell,
    )?;
    Ok(vec![json, png])
}
