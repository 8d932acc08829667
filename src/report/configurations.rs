//! `configurations.png`, the analogue of paper 004's Fig. 5: each zone's distinct optima drawn
//! to scale as the model's chain of members ([`crate::model::Depiction::skeleton`]), one row
//! per zone. Each optimum is drawn once and in the orientation the model reports (a start
//! that ended at the mirror image draws the same geometry, not a second one crossed over it);
//! a hinge whose part has a notch is drawn by the notch's outline, the others as a band of
//! their least thickness; rigid members as grey centre lines.

use std::path::Path;

use plotters::prelude::*;

use super::plot::{axis_tick, range, render_png, FAMILY};
use super::study_plots::colour;
use super::WriteError;
use crate::model::Skeleton;
use crate::part::Hinge;
use crate::problem::Problem;
use crate::study::Study;

/// The grey of rigid members, as the models' legends name it.
const GREY: RGBColor = RGBColor(150, 150, 150);

/// Points of an arc's polyline per radian.
const PER_RADIAN: f64 = 12.0;

/// A hinge's outline in its own frame (x along the centre line from its start, y across,
/// mm): the profile above the centre line, arcs as polylines, then its mirror image below.
fn outline(h: &Hinge) -> Vec<(f64, f64)> {
    let p: Vec<(f64, f64, f64)> = h
        .profile
        .iter()
        .map(|v| (v[0] * 1e3, v[1] * 1e3, v[2]))
        .collect();
    let mut top: Vec<(f64, f64)> = Vec::new();
    for (k, &(x, y, bulge)) in p.iter().enumerate() {
        top.push((x, y));
        let Some(&(qx, qy, _)) = p.get(k + 1) else {
            break;
        };
        if bulge.abs() < 1e-12 {
            continue;
        }
        // a bulge b: the arc's sweep is 4 atan(b), its centre off the chord's middle along
        // the chord's left normal by (1 - b^2) / (4 b) chords
        let (cx, cy) = (qx - x, qy - y);
        let off = (1.0 - bulge * bulge) / (4.0 * bulge);
        let centre = (x + cx / 2.0 - cy * off, y + cy / 2.0 + cx * off);
        let r = (x - centre.0).hypot(y - centre.1);
        let a0 = (y - centre.1).atan2(x - centre.0);
        let sweep = 4.0 * bulge.atan();
        let n = (sweep.abs() * PER_RADIAN).ceil().max(2.0) as usize;
        for i in 1..n {
            let a = a0 + sweep * i as f64 / n as f64;
            top.push((centre.0 + r * a.cos(), centre.1 + r * a.sin()));
        }
    }
    let bottom: Vec<(f64, f64)> = top.iter().rev().map(|&(x, y)| (x, -y)).collect();
    top.into_iter().chain(bottom).collect()
}

/// The member from `a` to `b` drawn as `shape` (its own frame, mm), or as a band of
/// thickness `t` about its centre line.
fn member(a: (f64, f64), b: (f64, f64), t: f64, shape: Option<&[(f64, f64)]>) -> Vec<(f64, f64)> {
    let len = (b.0 - a.0).hypot(b.1 - a.1).max(1e-12);
    let (u, n) = (
        ((b.0 - a.0) / len, (b.1 - a.1) / len),
        (-(b.1 - a.1) / len, (b.0 - a.0) / len),
    );
    let band = [
        (0.0, t / 2.0),
        (len, t / 2.0),
        (len, -t / 2.0),
        (0.0, -t / 2.0),
    ];
    shape
        .unwrap_or(&band)
        .iter()
        .map(|&(x, y)| (a.0 + u.0 * x + n.0 * y, a.1 + u.1 * x + n.1 * y))
        .collect()
}

/// A shape of the drawing: its zone, its outline (a polygon, or a rigid member's two ends),
/// and whether it is a flexible member (filled) or a rigid one (a line).
type Shape = (usize, Vec<(f64, f64)>, bool);

/// One drawn optimum: its skeleton and, for each member, the outline of the part's hinge
/// there if it is a notch.
struct Drawn {
    rank: usize,
    skeleton: Skeleton,
    notches: Vec<Option<Vec<(f64, f64)>>>,
}

/// The hinge of `hinges` a skeleton's member of length `len` and least thickness `t` (mm)
/// is, if it is a notch (a profile with an arc): the one of that length and thickness.
fn notch_of(hinges: &[Hinge], len: f64, t: f64) -> Option<Vec<(f64, f64)>> {
    hinges
        .iter()
        .filter(|h| h.profile.iter().any(|p| p[2] != 0.0))
        .find(|h| {
            let l = (h.end[0] - h.start[0]).hypot(h.end[1] - h.start[1]) * 1e3;
            (l - len).abs() < 1e-6 && (h.thickness * 1e3 - t).abs() < 1e-6
        })
        .map(outline)
}

/// Each zone's distinct optima, oriented as the model reports them.
fn drawn(problem: &Problem, study: &Study) -> Vec<Drawn> {
    let depiction = problem.depiction();
    let mut out: Vec<Drawn> = Vec::new();
    for r in &study.runs {
        let Some(rank) = r.zone else { continue };
        let mut x = r.x_end.clone();
        if depiction.prefers_mirror(&x) {
            let mut m = x.clone();
            if problem.model().mirror(&mut m) {
                x = m;
            }
        }
        let Some(skeleton) = depiction.skeleton(&x) else {
            continue;
        };
        let same = |d: &Drawn| {
            d.rank == rank
                && d.skeleton.nodes_mm.len() == skeleton.nodes_mm.len()
                && d.skeleton
                    .nodes_mm
                    .iter()
                    .zip(&skeleton.nodes_mm)
                    .all(|(p, q)| {
                        (p.0.is_nan() && q.0.is_nan()) || (p.0 - q.0).hypot(p.1 - q.1) < 1e-3
                    })
        };
        if out.iter().any(same) {
            continue;
        }
        let hinges = match problem.mechanism().part(&x) {
            Some(Ok(part)) => part.hinges,
            _ => Vec::new(),
        };
        let notches = skeleton
            .nodes_mm
            .windows(2)
            .zip(&skeleton.thickness_mm)
            .map(|(seg, &t)| {
                let len = (seg[1].0 - seg[0].0).hypot(seg[1].1 - seg[0].1);
                notch_of(&hinges, len, t)
            })
            .collect();
        out.push(Drawn {
            rank,
            skeleton,
            notches,
        });
    }
    out
}

pub(super) fn configurations_png(
    path: &Path,
    problem: &Problem,
    study: &Study,
) -> Result<(), WriteError> {
    let lines = drawn(problem, study);
    let ranks: Vec<usize> = study
        .clustering
        .zones
        .iter()
        .map(|z| z.rank)
        .filter(|&r| lines.iter().any(|l| l.rank == r))
        .collect();
    let shapes: Vec<Shape> = lines
        .iter()
        .flat_map(|d| {
            let s = &d.skeleton;
            s.nodes_mm
                .windows(2)
                .zip(&s.rigid)
                .zip(&s.thickness_mm)
                .zip(&d.notches)
                // a break in the chain ([`Skeleton::nodes_mm`])
                .filter(|(((seg, _), _), _)| seg[0].0.is_finite() && seg[1].0.is_finite())
                .map(move |(((seg, &rigid), &t), notch)| {
                    if rigid || t <= 0.0 {
                        (d.rank, vec![seg[0], seg[1]], false)
                    } else {
                        (d.rank, member(seg[0], seg[1], t, notch.as_deref()), true)
                    }
                })
        })
        .collect();
    let xr = range(shapes.iter().flat_map(|s| s.1.iter().map(|p| p.0)));
    let yr = range(shapes.iter().flat_map(|s| s.1.iter().map(|p| p.1)));
    let pad = 0.04 * (xr.1 - xr.0).max(yr.1 - yr.0);
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
    let notched = lines.iter().any(|d| d.notches.iter().any(Option::is_some));
    // the title, and the legend under it (a line of its own: it is as long as a model makes it)
    let title = format!("{}: configurations by zone", problem.name);
    let legend = format!(
        "{}{}",
        problem.depiction().skeleton_legend(),
        if notched {
            "; notches by their outline"
        } else {
            ""
        }
    );
    const HEAD: u32 = 52;
    let rows = ranks.len().max(1) as u32;
    render_png(path, (WIDTH, HEAD + row * rows), |root| {
        let (head, root) = root.split_vertically(HEAD);
        let centred = |size: u32| {
            TextStyle::from((FAMILY, size).into_font()).pos(plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Top,
            ))
        };
        let mid = (WIDTH / 2) as i32;
        head.draw_text(&title, &centred(17), (mid, 6))?;
        head.draw_text(&legend, &centred(13), (mid, 30))?;
        let panels = root.split_evenly((rows as usize, 1));
        for (&rank, area) in ranks.iter().zip(&panels) {
            let count = study.runs.iter().filter(|r| r.zone == Some(rank)).count();
            let optima = lines.iter().filter(|l| l.rank == rank).count();
            let caption = match optima {
                1 => format!("zone {rank}: {count} starts, one optimum"),
                n => format!("zone {rank}: {count} starts, {n} optima"),
            };
            let mut chart = ChartBuilder::on(area)
                .caption(caption, (FAMILY, 15).into_font().color(&colour(rank)))
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
                .x_label_formatter(&|v| axis_tick(*v, xr, 10))
                .y_label_formatter(&|v| axis_tick(*v, yr, 10))
                .draw()?;
            for (_, shape, flexible) in shapes.iter().filter(|s| s.0 == rank) {
                if *flexible {
                    chart.draw_series([Polygon::new(
                        shape.clone(),
                        colour(rank).mix(0.6).filled(),
                    )])?;
                } else {
                    chart.draw_series(LineSeries::new(
                        shape.iter().copied(),
                        GREY.stroke_width(2),
                    ))?;
                }
            }
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A right-circular notch of radius `r` and least thickness `t` (m), as the part states it:
    /// the profile's one arc, a half circle, from one root to the other.
    fn notch(r: f64, t: f64) -> Hinge {
        Hinge {
            name: "hinge b".into(),
            kind: "circular",
            start: [0.0, 0.0],
            end: [2.0 * r, 0.0],
            thickness: t,
            root: 2.0 * r + t,
            fillet: 0.0,
            profile: vec![[0.0, r + t / 2.0, 1.0], [2.0 * r, r + t / 2.0, 0.0]],
        }
    }

    #[test]
    fn a_notch_is_drawn_by_its_outline_thinnest_at_its_middle() {
        let (r, t) = (2.133e-3, 0.4e-3);
        let shape = outline(&notch(r, t));
        // the top half runs from root to root through the arc, the bottom mirrors it
        let half = shape.len() / 2;
        for (p, q) in shape[..half].iter().zip(shape[half..].iter().rev()) {
            assert_eq!((p.0, -p.1), *q);
        }
        let thinnest = shape[..half]
            .iter()
            .copied()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        assert!((thinnest.1 - 0.2).abs() < 1e-9, "{thinnest:?}");
        assert!((thinnest.0 - 2.133).abs() < 1e-9, "{thinnest:?}");
        let widest = shape.iter().map(|p| p.1).fold(0.0, f64::max);
        assert!((widest - 2.333).abs() < 1e-9, "{widest}");
        // every point of the arc at the radius from its centre, above the centre line
        for p in &shape[..half] {
            assert!(
                ((p.0 - 2.133).hypot(p.1 - 2.333) - 2.133).abs() < 1e-9,
                "{p:?}"
            );
        }
    }

    #[test]
    fn a_member_follows_its_two_nodes_and_a_strip_is_a_band_of_its_thickness() {
        let band = member((1.0, 1.0), (1.0, 3.0), 0.4, None);
        assert_eq!(band.len(), 4);
        let expected = [(0.8, 1.0), (0.8, 3.0), (1.2, 3.0), (1.2, 1.0)];
        for (p, q) in band.iter().zip(expected) {
            assert!(
                (p.0 - q.0).abs() < 1e-12 && (p.1 - q.1).abs() < 1e-12,
                "{band:?}"
            );
        }
        // a notch's outline laid along the member: its ends at the nodes' roots
        let shape = outline(&notch(1e-3, 0.2e-3));
        let laid = member((0.0, 0.0), (0.0, 2.0), 0.2, Some(&shape));
        assert!(
            (laid[0].0 + 1.1).abs() < 1e-9 && laid[0].1.abs() < 1e-9,
            "{:?}",
            laid[0]
        );
    }
}
