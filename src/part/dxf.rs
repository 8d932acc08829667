//! `part.dxf`: DXF 2000, millimetres (the part, in metres, converted here), written with
//! the `dxf` crate.
//!
//! Every loop is one closed LWPOLYLINE on layer `OUTLINE` (the outer boundary and each
//! pocket, the actuator's among them), its arcs as bulges, so a CAM program sees closed
//! contours it can cut as they are. Each named face of the part is a LINE on a layer of its
//! own name in capitals, all beginning `FACE_` (`FACE_INPUT_LEFT`, ...), for the load cases
//! of an analysis: a CAM user hides them at once with `FACE_*`. The plate's thickness (the
//! part's width through which the outline is cut) is a TEXT below the part on layer
//! `PLATE`, and the header's `$THICKNESS`; `$EXTMIN` and `$EXTMAX` hold the outline's
//! extents, arcs included.
//!
//! The `dxf` crate writes each symbol table's head without a handle, which readers such as
//! ezdxf repair on opening (an "invalid table head handle" a table); [`to_bytes`] gives each
//! head a handle of its own, owned by the drawing (`330` 0), and moves `$HANDSEED` past
//! them, so that the file opens with nothing to fix.

use chrono::{Local, TimeZone, Utc};
use dxf::entities::{Entity, EntityType, Line, LwPolyline};
use dxf::enums::{AcadVersion, Units};
use dxf::tables::Layer;
use dxf::LwPolylineVertex;
use dxf::{Drawing, Point};

use super::Part;

/// The layer of the outline.
pub const OUTLINE: &str = "OUTLINE";

/// The layer of the note of the plate's thickness.
pub const PLATE: &str = "PLATE";

/// The layer of a face.
pub fn face_layer(name: &str) -> String {
    format!("FACE_{}", name.to_uppercase())
}

/// The DXF drawing of `part`.
pub fn drawing(part: &Part) -> Drawing {
    let part = &part.in_mm();
    let mut d = Drawing::new();
    d.header.version = AcadVersion::R2000;
    d.header.default_drawing_units = Units::Millimeters;
    // no time stamp and no random identifiers: the same part gives the same bytes (the
    // dates are DXF's epoch, whatever the time zone; the identifiers nil)
    let epoch_local = Local.with_ymd_and_hms(1900, 1, 1, 0, 0, 0).single();
    let epoch_utc = Utc.with_ymd_and_hms(1900, 1, 1, 0, 0, 0).single();
    if let (Some(local), Some(utc)) = (epoch_local, epoch_utc) {
        d.header.creation_date = local;
        d.header.update_date = local;
        d.header.creation_date_universal = utc;
        d.header.update_date_universal = utc;
    }
    d.header.fingerprint_guid = uuid::Uuid::nil();
    d.header.version_guid = uuid::Uuid::nil();
    let [x0, y0, x1, y1] = part.bounding_box;
    d.header.minimum_drawing_extents = Point::new(x0, y0, 0.0);
    d.header.maximum_drawing_extents = Point::new(x1, y1, 0.0);
    d.header.thickness = part.width;
    for name in std::iter::once(OUTLINE.to_string())
        .chain(part.faces.iter().map(|f| face_layer(&f.name)))
        .chain(std::iter::once(PLATE.to_string()))
    {
        d.add_layer(Layer {
            name,
            ..Default::default()
        });
    }
    for l in &part.loops {
        let mut p = LwPolyline {
            vertices: l
                .vertices
                .iter()
                .map(|v| LwPolylineVertex {
                    x: v.x,
                    y: v.y,
                    bulge: v.bulge,
                    ..Default::default()
                })
                .collect(),
            ..Default::default()
        };
        p.set_is_closed(true);
        let mut e = Entity::new(EntityType::LwPolyline(p));
        e.common.layer = OUTLINE.into();
        d.add_entity(e);
    }
    for f in &part.faces {
        let line = Line::new(
            Point::new(f.a[0], f.a[1], 0.0),
            Point::new(f.b[0], f.b[1], 0.0),
        );
        let mut e = Entity::new(EntityType::Line(line));
        e.common.layer = face_layer(&f.name);
        d.add_entity(e);
    }
    // the plate's thickness, below the part, in letters a tenth of the part's height
    let height = (0.04 * (y1 - y0)).max(0.5);
    let note = dxf::entities::Text {
        location: Point::new(x0, y0 - 2.0 * height, 0.0),
        text_height: height,
        value: format!("plate thickness {} mm", significant(part.width)),
        ..Default::default()
    };
    let mut e = Entity::new(EntityType::Text(note));
    e.common.layer = PLATE.into();
    d.add_entity(e);
    d
}

/// `v` with at most six significant digits, no trailing zeros.
fn significant(v: f64) -> String {
    let s = format!(
        "{:.*}",
        (5 - v.abs().log10().floor() as i32).max(0) as usize,
        v
    );
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Gives each symbol table's head (`0 TABLE`, `2 <name>`) a handle (`5`) and its owner
/// (`330 0`), the handles numbered from `$HANDSEED` on, and moves `$HANDSEED` past them.
fn table_handles(text: &str) -> Result<String, String> {
    let lines: Vec<&str> = text.split("\r\n").collect();
    let seed_at = lines
        .iter()
        .position(|l| l.trim() == "$HANDSEED")
        .ok_or("the DXF has no $HANDSEED")?;
    let mut next = u64::from_str_radix(lines[seed_at + 2].trim(), 16)
        .map_err(|e| format!("$HANDSEED: {e}"))?;
    let mut out: Vec<String> = Vec::with_capacity(lines.len() + 64);
    let mut k = 0;
    while k < lines.len() {
        out.push(lines[k].to_string());
        // a table's head: code 0 `TABLE`, then code 2 and its name
        if lines[k] == "TABLE" && k >= 1 && lines[k - 1].trim() == "0" && k + 2 < lines.len() {
            out.push(lines[k + 1].to_string());
            out.push(lines[k + 2].to_string());
            out.push("  5".into());
            out.push(format!("{next:X}"));
            out.push("330".into());
            out.push("0".into());
            next += 1;
            k += 3;
            continue;
        }
        k += 1;
    }
    out[seed_at + 2] = format!("{next:X}");
    Ok(out.join("\r\n"))
}

/// `part.dxf` as bytes.
pub fn to_bytes(part: &Part) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    drawing(part).save(&mut out).map_err(|e| e.to_string())?;
    let text = String::from_utf8(out).map_err(|e| e.to_string())?;
    Ok(table_handles(&text)?.into_bytes())
}
