//! `part.svg`: the outline at true scale (width and height in mm, the viewBox in mm; the
//! part, in metres, converted here), written with the `svg` crate.
//!
//! SVG's y axis points down: the part is drawn with y negated, so it looks as in the DXF.
//! The path data is formatted here with f64 coordinates: the crate's `path::Data` holds f32
//! (seven digits, 4e-6 mm on a 40 mm part), too coarse for a file that may be cut from.
//! The outline is one path with the even-odd rule, so the pockets are holes.

use std::fmt::Write as _;

use svg::node::element::Path;
use svg::Document;

use super::outline::Arc;
use super::Part;

/// The margin around the part in the viewBox (mm).
const MARGIN: f64 = 1.0;

/// The SVG document of `part`.
pub fn document(part: &Part) -> Document {
    let part = &part.in_mm();
    let mut d = String::new();
    for l in &part.loops {
        let n = l.vertices.len();
        for (i, v) in l.vertices.iter().enumerate() {
            let cmd = if i == 0 { 'M' } else { 'L' };
            if i == 0 || l.vertices[i - 1].bulge == 0.0 {
                let _ = write!(d, "{cmd}{} {} ", v.x, -v.y);
            }
            let next = l.vertices[(i + 1) % n];
            if let Some(arc) = Arc::from_bulge(*v, next) {
                // y negated: the sweep's sense flips
                let sweep = if arc.sweep > 0.0 { 0 } else { 1 };
                let large = if arc.sweep.abs() > std::f64::consts::PI {
                    1
                } else {
                    0
                };
                let _ = write!(
                    d,
                    "A{r} {r} 0 {large} {sweep} {} {} ",
                    next.x,
                    -next.y,
                    r = arc.radius
                );
            }
        }
        d.push_str("Z ");
    }
    let [x0, y0, x1, y1] = part.bounding_box;
    let (w, h) = (x1 - x0 + 2.0 * MARGIN, y1 - y0 + 2.0 * MARGIN);
    Document::new()
        .set(
            "viewBox",
            format!("{} {} {w} {h}", x0 - MARGIN, -y1 - MARGIN),
        )
        .set("width", format!("{w}mm"))
        .set("height", format!("{h}mm"))
        .add(
            Path::new()
                .set("d", d.trim_end().to_string())
                .set("fill", "#c8d0d8")
                .set("fill-rule", "evenodd")
                .set("stroke", "black")
                .set("stroke-width", 0.02),
        )
}
