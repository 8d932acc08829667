//! The part as its files hold it: millimetres, the unit a drawing and a wire-EDM shop's CAM
//! program expect. The part itself stays in metres (SI, as the model and the finite
//! elements); the writers convert here, once, on the way out.

use serde::Serialize;

use super::{Face, Hinge, Loop, Part, Vertex, MM};

/// A [`Part`] in millimetres (areas in mm^2; bulges and angles unchanged), the fields in
/// the order `part.json` lists them.
#[derive(Debug, Clone, Serialize)]
pub struct PartMm {
    pub width: f64,
    pub loops: Vec<Loop>,
    pub faces: Vec<Face>,
    pub hinges: Vec<Hinge>,
    pub area: f64,
    pub bounding_box: [f64; 4],
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

fn mm(p: [f64; 2]) -> [f64; 2] {
    [p[0] * MM, p[1] * MM]
}

impl Part {
    /// The part in millimetres, for its files.
    pub fn in_mm(&self) -> PartMm {
        PartMm {
            width: self.width * MM,
            loops: self
                .loops
                .iter()
                .map(|l| Loop {
                    outer: l.outer,
                    vertices: l
                        .vertices
                        .iter()
                        .map(|v| Vertex {
                            x: v.x * MM,
                            y: v.y * MM,
                            bulge: v.bulge,
                        })
                        .collect(),
                })
                .collect(),
            faces: self
                .faces
                .iter()
                .map(|f| Face {
                    name: f.name.clone(),
                    a: mm(f.a),
                    b: mm(f.b),
                })
                .collect(),
            hinges: self
                .hinges
                .iter()
                .map(|h| Hinge {
                    start: mm(h.start),
                    end: mm(h.end),
                    thickness: h.thickness * MM,
                    root: h.root * MM,
                    fillet: h.fillet * MM,
                    profile: h
                        .profile
                        .iter()
                        .map(|v| [v[0] * MM, v[1] * MM, v[2]])
                        .collect(),
                    ..h.clone()
                })
                .collect(),
            area: self.area * MM * MM,
            bounding_box: self.bounding_box.map(|v| v * MM),
            warnings: self.warnings.clone(),
        }
    }
}

/// A length for a drawing or message: mm, at most three decimals.
pub fn length(v: f64) -> String {
    format!("{} mm", trimmed(v * 1e3, 3))
}

/// An angle (rad) for a drawing or message: degrees, at most two decimals.
pub fn angle(v: f64) -> String {
    format!("{}°", trimmed(v.to_degrees(), 2))
}

/// `v` with at most `decimals` decimals, no trailing zeros, and no sign on a zero.
fn trimmed(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}
