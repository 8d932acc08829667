//! The part's files: `part.dxf`, `part.svg`, `part.json`, `part.png`, the drawing a
//! designer checks before sending a file to the shop (the outline at equal scale on both
//! axes, the load faces in colour, the main dimensions annotated), and `part.step`, the
//! solid for mechanical CAD.

use std::path::{Path, PathBuf};

use plotters::prelude::*;
use serde::Serialize;

use super::folder::OutputSet;
use super::plot::{render_png, FAMILY};
use super::{write_atomic, write_json, WriteError};
use crate::model::part_rules::CAP;
use crate::part::{dxf, step, svg, Annotation, Part, PartMm, MM};
use crate::problem::part_rules::RuleCheck;

/// The names of the part's files, in the order they are written.
pub const PART_FILES: [&str; 5] = ["part.dxf", "part.svg", "part.json", "part.png", "part.step"];

/// `part.json`: the outline and faces (mm) and what they were made from.
#[derive(Debug, Serialize)]
struct PartJson<'a> {
    problem: &'a str,
    units: &'static str,
    /// The design in the problem file's units.
    design: &'a indexmap::IndexMap<String, f64>,
    #[serde(flatten)]
    part: PartMm,
}

/// Whose part a drawing shows, for its title.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PartOf {
    /// The design as given or the study's optimum.
    Design,
    /// The optimum refined against the finite elements.
    Refined,
}

/// Writes the five part files through `path` (which maps a file name to where it goes);
/// `rules`, the part's rules at the design, for the drawing to name the nearest its limit.
pub fn write_part(
    path: impl Fn(&str) -> PathBuf,
    problem: &str,
    design: &indexmap::IndexMap<String, f64>,
    part: &Part,
    of: PartOf,
    rules: &[RuleCheck],
) -> Result<Vec<PathBuf>, WriteError> {
    let files: Vec<PathBuf> = PART_FILES.iter().map(|f| path(f)).collect();
    let bytes = dxf::to_bytes(part).map_err(|e| WriteError {
        path: files[0].clone(),
        message: e,
    })?;
    write_atomic(&files[0], &bytes)?;
    write_atomic(&files[1], svg::document(part).to_string().as_bytes())?;
    write_json(
        &files[2],
        &PartJson {
            problem,
            units: "mm",
            design,
            part: part.in_mm(),
        },
    )?;
    drawing_png(&files[3], problem, part, of, closest(rules))?;
    write_atomic(&files[4], step::to_string(part, problem).as_bytes())?;
    Ok(files)
}

/// Writes the five part files into `dir` as one set in place of the folder's earlier one
/// ([`super::folder`]); returns the paths in place.
pub fn write_part_set(
    dir: &Path,
    problem: &str,
    design: &indexmap::IndexMap<String, f64>,
    part: &Part,
    rules: &[RuleCheck],
) -> Result<Vec<PathBuf>, WriteError> {
    let set = OutputSet::begin(dir)?;
    set.write(|set| {
        write_part(
            |name| set.path(name),
            problem,
            design,
            part,
            PartOf::Design,
            rules,
        )
    })?;
    set.commit(&PART_FILES)
}

/// The rule nearest its limit (the least margin), if the part states rules.
fn closest(rules: &[RuleCheck]) -> Option<&RuleCheck> {
    rules
        .iter()
        .min_by(|a, b| a.margin_mm.total_cmp(&b.margin_mm))
}

/// The label on the drawing's mark of the rule nearest its limit: its name and margin.
fn witness_label(r: &RuleCheck) -> String {
    format!("{}: margin {} mm", r.rule, margin_text(r.margin_mm))
}

/// A rule's margin (mm) as a designer reads it, to 0.1 um: on its limit it reads zero, not
/// the rounding it is within; a clearance at its cap, `>= 1.0000`, as no pair was worked
/// out beyond it (a size rule's margin is never capped, and reads what it is).
pub fn margin_text(margin_mm: f64) -> String {
    let cap_mm = CAP * MM;
    if margin_mm.abs() < 5e-5 {
        format!("{:.4}", 0.0)
    } else if margin_mm == cap_mm {
        format!(">= {cap_mm:.4}")
    } else {
        format!("{margin_mm:.4}")
    }
}

/// The drawing's line on the rule nearest its limit.
fn rule_line(r: &RuleCheck) -> String {
    let state = if !r.met {
        "broken"
    } else if r.active {
        "active"
    } else {
        "met"
    };
    format!(
        "nearest part rule: {} ({state}, margin {} mm): {}",
        r.rule,
        margin_text(r.margin_mm),
        r.description
    )
}

/// The colour of a named face in the drawing.
fn face_colour(k: usize) -> RGBColor {
    [RED, BLUE, GREEN, MAGENTA, CYAN][k % 5]
}

/// `part.png`: the outline at true proportions, the faces, the annotations (their labels
/// moved off the part where they would cover it), the plate's thickness in the title, and
/// below the drawing the part's rule nearest its limit, where it states rules, marked on the
/// drawing where the part says where it is measured.
fn drawing_png(
    path: &Path,
    problem: &str,
    part: &Part,
    of: PartOf,
    nearest: Option<&RuleCheck>,
) -> Result<(), WriteError> {
    let mm = part.in_mm();
    let [x0, y0, x1, y1] = mm.bounding_box;
    // room around the part for the dimension lines and labels
    let pad = 0.18 * (x1 - x0).max(y1 - y0);
    let (xr, yr) = ((x0 - pad, x1 + pad), (y0 - pad, y1 + pad));
    // equal scale on both axes: the plotting area takes the range's proportions
    let width = 1400u32;
    let (left, bottom, top, margin) = (60u32, 44u32, 40u32, 10u32);
    let plot_w = (width - left - 2 * margin) as f64;
    let plot_h = plot_w * (yr.1 - yr.0) / (xr.1 - xr.0);
    let footer = if nearest.is_some() { 26u32 } else { 0 };
    let height = (plot_h.round() as u32) + bottom + top + 2 * margin + footer;
    let per_mm = plot_w / (xr.1 - xr.0);
    let title = format!(
        "{problem}: the {}part (mm), plate {} mm thick; {}; faces in colour",
        if of == PartOf::Refined {
            "refined "
        } else {
            ""
        },
        crate::problem::display::human(part.width * MM),
        part.caption
    );
    let material = material(&mm.loops);
    render_png(path, (width, height), |root| {
        let root = root.titled(&title, (FAMILY, 22))?;
        let (_, area_height) = root.dim_in_pixel();
        let (root, foot) = root.split_vertically(area_height - footer);
        if let Some(r) = nearest {
            foot.draw_text(
                &rule_line(r),
                &(FAMILY, 15).into_text_style(&foot),
                (left as i32, 4),
            )?;
        }
        let mut chart = ChartBuilder::on(&root)
            .margin(margin)
            .x_label_area_size(bottom - 4)
            .y_label_area_size(left)
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("x (mm)")
            .y_desc("y (mm)")
            .label_style((FAMILY, 13))
            .draw()?;
        for l in &mm.loops {
            let pts: Vec<(f64, f64)> = l.points(24).iter().map(|p| (p[0], p[1])).collect();
            let fill = if l.outer {
                RGBColor(200, 208, 216).filled()
            } else {
                WHITE.filled()
            };
            chart.draw_series(std::iter::once(Polygon::new(pts.clone(), fill)))?;
            let mut closed = pts;
            closed.push(closed[0]);
            chart.draw_series(std::iter::once(PathElement::new(
                closed,
                BLACK.stroke_width(2),
            )))?;
        }
        draw_faces(&mut chart, &mm.faces)?;
        // the notes' labels stand where the model puts them; the dimensions' find room
        let mut placed = Vec::new();
        let overall = overall_size(part);
        let mut order: Vec<&Annotation> = part.annotations.iter().chain(&overall).collect();
        order.sort_by_key(|a| matches!(a, Annotation::Length { .. }));
        for a in order {
            draw_annotation(
                &mut chart,
                a,
                &Labels {
                    material: &material,
                    per_mm,
                },
                &mut placed,
            )?;
        }
        if let Some((r, w)) = nearest.and_then(|r| Some((r, r.witness_mm?))) {
            let labels = Labels {
                material: &material,
                per_mm,
            };
            draw_witness(&mut chart, w, &witness_label(r), &labels, &mut placed)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font((FAMILY, 14))
            .draw()?;
        Ok(())
    })
}

/// The part's overall width and height, below and left of it, where it gives no lengths.
fn overall_size(part: &Part) -> Vec<Annotation> {
    if part
        .annotations
        .iter()
        .any(|a| matches!(a, Annotation::Length { .. }))
    {
        return Vec::new();
    }
    let [x0, y0, x1, y1] = part.bounding_box;
    let gap = 0.04 * (x1 - x0).max(y1 - y0);
    vec![
        Annotation::Length {
            a: [x1, y0],
            b: [x0, y0],
            offset: gap,
            label: crate::part::mm::length(x1 - x0),
        },
        Annotation::Length {
            a: [x0, y0],
            b: [x0, y1],
            offset: gap,
            label: crate::part::mm::length(y1 - y0),
        },
    ]
}

/// The faces in colour: one colour and one legend entry per face name, however many
/// segments it spans.
fn draw_faces(
    chart: &mut Chart<'_, '_>,
    faces: &[crate::part::Face],
) -> Result<(), super::plot::DrawError> {
    let mut names: Vec<&str> = Vec::new();
    for f in faces {
        let k = names
            .iter()
            .position(|n| *n == f.name)
            .unwrap_or(names.len());
        let c = face_colour(k);
        let series = chart.draw_series(std::iter::once(PathElement::new(
            vec![(f.a[0], f.a[1]), (f.b[0], f.b[1])],
            c.stroke_width(5),
        )))?;
        if k == names.len() {
            names.push(&f.name);
            series.label(&f.name).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(5))
            });
        }
    }
    Ok(())
}

type Chart<'a, 'b> = ChartContext<
    'a,
    BitMapBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// The part's material (mm): the outer loop less the inner ones, which labels keep off.
fn material(loops: &[crate::part::Loop]) -> geo::Polygon {
    let ring = |l: &crate::part::Loop| -> geo::LineString {
        l.points(24).iter().map(|p| (p[0], p[1])).collect()
    };
    let outer = loops
        .iter()
        .find(|l| l.outer)
        .map(ring)
        .unwrap_or_else(|| geo::LineString::new(vec![]));
    let inner = loops.iter().filter(|l| !l.outer).map(ring).collect();
    geo::Polygon::new(outer, inner)
}

/// What a label is placed against: the material, and the drawing's pixels per mm.
struct Labels<'a> {
    material: &'a geo::Polygon,
    per_mm: f64,
}

/// Where a dimension's label goes: beyond its line, off the part and off the labels placed
/// so far, at the first of a few steps outward that is free (else the last); whether it
/// moved from beside the line (then a leader joins them).
fn place_label(
    mid: (f64, f64),
    dir: (f64, f64),
    size: (f64, f64),
    labels: &Labels,
    placed: &[geo::Rect],
) -> ((f64, f64), geo::Rect, bool) {
    use geo::Intersects;
    let (w, h) = size;
    let reach = dir.0.abs() * w / 2.0 + dir.1.abs() * h / 2.0;
    let boxed = |k: usize| {
        let d = 0.2 + reach + 0.5 * k as f64;
        let c = (mid.0 + d * dir.0, mid.1 + d * dir.1);
        (
            c,
            geo::Rect::new(
                (c.0 - w / 2.0, c.1 - h / 2.0),
                (c.0 + w / 2.0, c.1 + h / 2.0),
            ),
        )
    };
    const STEPS: usize = 16;
    for k in 0..STEPS {
        let (c, r) = boxed(k);
        if !r.intersects(labels.material) && placed.iter().all(|p| !p.intersects(&r)) {
            return (c, r, k > 0);
        }
    }
    let (c, r) = boxed(0);
    (c, r, false)
}

/// A dimension line with arrows and extension lines, or a label with a leader.
fn draw_annotation(
    chart: &mut Chart<'_, '_>,
    a: &Annotation,
    labels: &Labels,
    placed: &mut Vec<geo::Rect>,
) -> Result<(), super::plot::DrawError> {
    let style = RGBColor(40, 40, 40);
    match a {
        Annotation::Length {
            a,
            b,
            offset,
            label,
        } => {
            let (a, b) = ([a[0] * MM, a[1] * MM], [b[0] * MM, b[1] * MM]);
            let len = (b[0] - a[0]).hypot(b[1] - a[1]);
            if len == 0.0 {
                return Ok(());
            }
            let u = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
            let n = [-u[1], u[0]];
            let off = offset * MM;
            let pa = (a[0] + off * n[0], a[1] + off * n[1]);
            let pb = (b[0] + off * n[0], b[1] + off * n[1]);
            if off != 0.0 {
                for (p, q) in [((a[0], a[1]), pa), ((b[0], b[1]), pb)] {
                    chart.draw_series(std::iter::once(PathElement::new(
                        vec![p, q],
                        style.mix(0.5).stroke_width(1),
                    )))?;
                }
            }
            chart.draw_series(std::iter::once(PathElement::new(
                vec![pa, pb],
                style.stroke_width(1),
            )))?;
            // arrowheads: short strokes 25 degrees off the line
            let head = 0.06 * len.min(4.0);
            for (tip, dir) in [(pa, u), (pb, [-u[0], -u[1]])] {
                for s in [1.0f64, -1.0] {
                    let (c, si) = (25f64.to_radians().cos(), s * 25f64.to_radians().sin());
                    let d = [dir[0] * c - dir[1] * si, dir[0] * si + dir[1] * c];
                    chart.draw_series(std::iter::once(PathElement::new(
                        vec![tip, (tip.0 + head * d[0], tip.1 + head * d[1])],
                        style.stroke_width(1),
                    )))?;
                }
            }
            let mid = (0.5 * (pa.0 + pb.0), 0.5 * (pa.1 + pb.1));
            let side = if off < 0.0 { -1.0 } else { 1.0 };
            let dir = (side * n[0], side * n[1]);
            draw_label(chart, label, (mid, dir), style, false, labels, placed)?;
        }
        Annotation::Note {
            at,
            label_at,
            label,
        } => {
            let p = (at[0] * MM, at[1] * MM);
            let q = (label_at[0] * MM, label_at[1] * MM);
            let (w, h) = label_size(chart, label, labels.per_mm)?;
            placed.push(geo::Rect::new(
                (q.0 - w / 2.0, q.1),
                (q.0 + w / 2.0, q.1 + h),
            ));
            chart.draw_series(std::iter::once(Circle::new(p, 3, style.filled())))?;
            chart.draw_series(std::iter::once(PathElement::new(
                vec![p, q],
                style.mix(0.5).stroke_width(1),
            )))?;
            chart.draw_series(std::iter::once(Text::new(
                label.clone(),
                q,
                (FAMILY, 14)
                    .into_font()
                    .color(&style)
                    .pos(plotters::style::text_anchor::Pos::new(
                        plotters::style::text_anchor::HPos::Center,
                        plotters::style::text_anchor::VPos::Bottom,
                    )),
            )))?;
        }
    }
    Ok(())
}

/// A label beside the point `from.0`, towards `from.1` (off the part and the labels
/// placed), on a white box in `colour`; a leader from the point where it was moved, or
/// always where `leader`.
fn draw_label(
    chart: &mut Chart<'_, '_>,
    label: &str,
    from: ((f64, f64), (f64, f64)),
    colour: RGBColor,
    leader: bool,
    labels: &Labels,
    placed: &mut Vec<geo::Rect>,
) -> Result<(), super::plot::DrawError> {
    let (mid, dir) = from;
    let size = label_size(chart, label, labels.per_mm)?;
    let (at, rect, moved) = place_label(mid, dir, size, labels, placed);
    if moved || leader {
        chart.draw_series(std::iter::once(PathElement::new(
            vec![mid, at],
            colour.mix(0.5).stroke_width(1),
        )))?;
    }
    chart.draw_series(std::iter::once(Rectangle::new(
        [(rect.min().x, rect.min().y), (rect.max().x, rect.max().y)],
        WHITE.mix(0.85).filled(),
    )))?;
    placed.push(rect);
    chart.draw_series(std::iter::once(Text::new(
        label.to_string(),
        at,
        (FAMILY, 14)
            .into_font()
            .color(&colour)
            .pos(plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Center,
            )),
    )))?;
    Ok(())
}

/// A label's box (mm), a little larger than its text.
fn label_size(
    chart: &Chart<'_, '_>,
    label: &str,
    per_mm: f64,
) -> Result<(f64, f64), super::plot::DrawError> {
    let font = TextStyle::from((FAMILY, 14).into_font());
    let (w, h) = chart.plotting_area().estimate_text_size(label, &font)?;
    Ok(((f64::from(w) + 6.0) / per_mm, (f64::from(h) + 4.0) / per_mm))
}

/// The mark of the rule nearest its limit: a line between the two points where the part
/// measures it, each a dot, and its label with a leader from the line's middle (off the
/// part and the other labels, as theirs are: the witness often stands in a narrow slot).
fn draw_witness(
    chart: &mut Chart<'_, '_>,
    [a, b]: [[f64; 2]; 2],
    label: &str,
    labels: &Labels,
    placed: &mut Vec<geo::Rect>,
) -> Result<(), super::plot::DrawError> {
    let colour = RGBColor(230, 110, 0);
    let (pa, pb) = ((a[0], a[1]), (b[0], b[1]));
    chart.draw_series(std::iter::once(PathElement::new(
        vec![pa, pb],
        colour.stroke_width(3),
    )))?;
    for p in [pa, pb] {
        chart.draw_series(std::iter::once(Circle::new(p, 4, colour.filled())))?;
    }
    let mid = (0.5 * (pa.0 + pb.0), 0.5 * (pa.1 + pb.1));
    // across the line, or upwards where its ends coincide
    let len = (pb.0 - pa.0).hypot(pb.1 - pa.1);
    let dir = if len > 0.0 {
        let n = (-(pb.1 - pa.1) / len, (pb.0 - pa.0) / len);
        if n.1 < 0.0 {
            (-n.0, -n.1)
        } else {
            n
        }
    } else {
        (0.0, 1.0)
    };
    draw_label(chart, label, (mid, dir), colour, true, labels, placed)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::Intersects;

    /// A 10 mm square of material with a dimension along its top edge: a label too wide for
    /// the space beside the line moves out, off the material and off a label already there.
    #[test]
    fn the_drawing_names_the_rule_nearest_its_limit() {
        let rule = |name: &str, margin_mm: f64, met: bool, active: bool| RuleCheck {
            witness_mm: None,
            rule: name.into(),
            description: format!("what {name} asks"),
            margin_mm,
            met,
            active,
        };
        let rules = [
            rule("slot", 0.8, true, false),
            rule("link_width", -3e-16, true, true),
            rule("pocket", 2.0, true, false),
        ];
        let nearest = closest(&rules).unwrap();
        assert_eq!(nearest.rule, "link_width");
        assert_eq!(
            rule_line(nearest),
            "nearest part rule: link_width (active, margin 0.0000 mm): what link_width asks"
        );
        let broken = rule("slot", -0.25, false, false);
        assert!(rule_line(&broken).contains("(broken, margin -0.2500 mm)"));
        assert!(closest(&[]).is_none());
        // a clearance no pair comes near reads its cap: at least that, not that
        let far = rule("slot", CAP * MM, true, false);
        assert!(rule_line(&far).contains("(met, margin >= 1.0000 mm)"));
        assert_eq!(margin_text(0.25), "0.2500");
        assert_eq!(margin_text(2.5), "2.5000");
    }

    #[test]
    fn a_label_that_would_cover_the_part_moves_off_it_and_off_the_other_labels() {
        let material = geo::Polygon::new(
            vec![(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)].into(),
            vec![],
        );
        let labels = Labels {
            material: &material,
            per_mm: 20.0,
        };
        // the line 0.1 mm above the top edge, its label 0.6 mm tall
        let (mid, up) = ((5.0, 10.1), (0.0, 1.0));
        let (at, rect, moved) = place_label(mid, up, (4.0, 0.6), &labels, &[]);
        assert!(!moved && !rect.intersects(&material), "{at:?}");
        // a label already where this one would go
        let taken = [rect];
        let (at, second, moved) = place_label(mid, up, (4.0, 0.6), &labels, &taken);
        assert!(moved && !second.intersects(&taken[0]), "{at:?}");
        // the line on the material's edge, pointing into it: the label finds room past it
        let (at, rect, moved) = place_label((5.0, 9.0), up, (4.0, 3.0), &labels, &[]);
        assert!(moved && !rect.intersects(&material), "{at:?}");
    }
}
