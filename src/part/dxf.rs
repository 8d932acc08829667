//! `part.dxf`: DXF 2000, millimetres (the part, in metres, converted here), written with
//! the `dxf` crate.
//!
//! Every loop is one closed LWPOLYLINE on layer `OUTLINE` (the outer boundary and each
//! pocket, the actuator's among them), its arcs as bulges, so a CAM program sees closed
//! contours it can cut as they are. Each named face of the part is a LINE on a layer of its
//! own name in capitals (`FACE_INPUT_LEFT`, ...), for the load cases of an analysis.

use chrono::{Local, TimeZone, Utc};
use dxf::entities::{Entity, EntityType, Line, LwPolyline};
use dxf::enums::{AcadVersion, Units};
use dxf::tables::Layer;
use dxf::LwPolylineVertex;
use dxf::{Drawing, Point};

use super::Part;

/// The layer of the outline.
pub const OUTLINE: &str = "OUTLINE";

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
    for name in
        std::iter::once(OUTLINE.to_string()).chain(part.faces.iter().map(|f| face_layer(&f.name)))
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
    d
}

/// `part.dxf` as bytes.
pub fn to_bytes(part: &Part) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    drawing(part).save(&mut out).map_err(|e| e.to_string())?;
    Ok(out)
}
