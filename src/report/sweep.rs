//! `<variable>.json` and `<variable>.png`: the curves of a sweep of [`crate::sweep`].

use std::path::{Path, PathBuf};

use super::folder::OutputSet;
use super::plot::{line_panels, Panel};
use super::{write_json, WriteError};
use crate::sweep::Sweep;

/// Writes `<variable>.json` and `<variable>.png` into `dir`, added to the folder's set
/// ([`super::folder`]: the sweeps of other variables stay, an earlier sweep of this one is
/// replaced); returns the paths in place.
pub fn write_sweep(dir: &Path, sweep: &Sweep) -> Result<Vec<PathBuf>, WriteError> {
    let names = [
        format!("{}.json", sweep.variable),
        format!("{}.png", sweep.variable),
    ];
    super::folder::check_names(dir, &[&names[0], &names[1]])?;
    let set = OutputSet::begin(dir)?;
    set.write(|set| {
        write_json(&set.path(&names[0]), sweep)?;
        plot(&set.path(&names[1]), sweep)
    })?;
    set.commit_added(&[&names[0], &names[1]])
}

/// `<variable>.png`: a panel per output.
fn plot(png: &Path, sweep: &Sweep) -> Result<(), WriteError> {
    // the base design is marked where it lies within the swept range
    let (lo, hi) = sweep
        .values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
            (l.min(v), h.max(v))
        });
    let around = sweep
        .around
        .get(&sweep.variable)
        .copied()
        .filter(|v| (lo..=hi).contains(v));
    let panels: Vec<Panel> = sweep
        .order
        .iter()
        .map(|name| {
            // in the display unit: 60 MPa, not 6.000e7 Pa
            let scale = sweep.display_to_si.get(name).copied().unwrap_or(1.0);
            let shown = |v: f64| v / scale;
            let unit = &sweep.display_units[name];
            Panel {
                title: name.clone(),
                x_label: format!("{} ({})", sweep.variable, sweep.unit),
                y_label: if unit == "1" {
                    name.clone()
                } else {
                    format!("{name} ({unit})")
                },
                points: sweep
                    .values
                    .iter()
                    .zip(&sweep.outputs[name])
                    .map(|(&x, y)| (x, y.map_or(f64::NAN, shown)))
                    .collect(),
                limits: sweep
                    .limits
                    .get(name)
                    .map(|l| l.iter().flatten().map(|&v| shown(v)).collect())
                    .unwrap_or_default(),
                marker: around.zip(sweep.at_around.get(name).copied().flatten().map(shown)),
            }
        })
        .collect();
    let columns = if panels.len() == 1 { 1 } else { 4 };
    let cell = if panels.len() == 1 {
        (720, 480)
    } else {
        (420, 300)
    };
    line_panels(
        png,
        &format!("{}: outputs against {}", sweep.problem, sweep.variable),
        &panels,
        columns,
        cell,
    )
}
