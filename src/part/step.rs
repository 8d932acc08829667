//! `part.step`: the part as a solid for mechanical CAD, ISO 10303-21 in the AP214 schema
//! (`AUTOMOTIVE_DESIGN`), millimetres: the outline extruded from z = 0 through the plate's
//! thickness, one `MANIFOLD_SOLID_BREP` of one `CLOSED_SHELL`.
//!
//! The B-rep is the outline's own: the bottom and top faces are planes bounded by every loop
//! (the pocket an inner bound), and each edge of a loop gives one side face, a `PLANE` for a
//! straight edge and a `CYLINDRICAL_SURFACE` for an arc, so the arcs stay true circles
//! (`CIRCLE` edges), as in the DXF. Faces: 2 + the loops' edges; every edge is used by two
//! faces in opposite senses; outward normals.
//!
//! Written here rather than with a B-rep crate: the solid needs only planes, cylinders,
//! lines and circles, about 300 lines, while `truck-modeling` with `truck-stepio` (the
//! well-kept Rust STEP writer) brings its geometry, topology and STEP stacks to every build
//! (26 crates more, 50 s of CPU: `docs/performance.md`) and writes an extruded arc as a
//! rational B-spline surface rather than a cylinder. OpenCASCADE reads every committed file
//! back (`tests/part_and_fe/step.rs`); as it mends a face's orientation on reading, the same
//! test checks the senses of the edges here.
//!
//! Deterministic: the header's time stamp is a constant and the entities are numbered in the
//! order the loops give, so the same part gives the same bytes.

use std::fmt::Write as _;

use super::outline::{Arc, Loop};
use super::Part;

/// The header's time stamp: a constant, so that a file does not change with the time it was
/// written.
const TIME_STAMP: &str = "2000-01-01T00:00:00";

/// The entities of the file, numbered from 1 in the order they are added.
struct Data {
    lines: Vec<String>,
}

impl Data {
    fn add(&mut self, entity: String) -> usize {
        self.lines.push(entity);
        self.lines.len()
    }

    fn point(&mut self, p: [f64; 3]) -> usize {
        self.add(format!("CARTESIAN_POINT('',{})", triple(p)))
    }

    fn direction(&mut self, d: [f64; 3]) -> usize {
        self.add(format!("DIRECTION('',{})", triple(d)))
    }

    fn placement(&mut self, at: [f64; 3], axis: [f64; 3], reference: [f64; 3]) -> usize {
        let (p, a, r) = (
            self.point(at),
            self.direction(axis),
            self.direction(reference),
        );
        self.add(format!("AXIS2_PLACEMENT_3D('',#{p},#{a},#{r})"))
    }

    /// A line through `a` towards `b`.
    fn line(&mut self, a: [f64; 3], b: [f64; 3]) -> usize {
        let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let p = self.point(a);
        let u = self.direction(d.map(|c| c / length));
        let v = self.add(format!("VECTOR('',#{u},{})", real(length)));
        self.add(format!("LINE('',#{p},#{v})"))
    }
}

/// Three reals as a STEP list.
fn triple(v: [f64; 3]) -> String {
    format!("({},{},{})", real(v[0]), real(v[1]), real(v[2]))
}

/// A real as STEP writes it: digits, a point, and an exponent `E` where there is one; the
/// shortest that reads back to the same `f64`.
fn real(v: f64) -> String {
    let s = format!("{v:?}");
    let (mantissa, exponent) = match s.split_once('e') {
        Some((m, e)) => (m.to_string(), format!("E{e}")),
        None => (s, String::new()),
    };
    let mantissa = if mantissa.contains('.') {
        mantissa
    } else {
        format!("{mantissa}.")
    };
    format!("{mantissa}{exponent}")
}

/// A string as STEP writes it: quotes and backslashes doubled, every character outside
/// printable ASCII as its `\X2\` (or `\X4\`) hexadecimal code.
fn string(s: &str) -> String {
    let mut out = String::from("'");
    for c in s.chars() {
        match c {
            '\'' => out.push_str("''"),
            '\\' => out.push_str("\\\\"),
            ' '..='~' => out.push(c),
            c if (c as u32) <= 0xFFFF => {
                let _ = write!(out, "\\X2\\{:04X}\\X0\\", c as u32);
            }
            c => {
                let _ = write!(out, "\\X4\\{:08X}\\X0\\", c as u32);
            }
        }
    }
    out.push('\'');
    out
}

/// The edges of one loop: at each vertex the vertical edge, and from it to the next vertex
/// the bottom and top edges; each edge runs from its vertex to the next (the vertical one
/// upwards).
struct LoopEdges {
    bottom: Vec<usize>,
    top: Vec<usize>,
    vertical: Vec<usize>,
    /// The side face's surface and whether the face's outward normal is the surface's.
    sides: Vec<(usize, bool)>,
}

/// Adds the vertices, edges and side surfaces of `l` (mm) extruded through `thickness`.
fn loop_edges(data: &mut Data, l: &Loop, thickness: f64) -> LoopEdges {
    let n = l.vertices.len();
    let at = |i: usize, z: f64| [l.vertices[i].x, l.vertices[i].y, z];
    let bottom_vertices: Vec<usize> = (0..n)
        .map(|i| {
            let p = data.point(at(i, 0.0));
            data.add(format!("VERTEX_POINT('',#{p})"))
        })
        .collect();
    let top_vertices: Vec<usize> = (0..n)
        .map(|i| {
            let p = data.point(at(i, thickness));
            data.add(format!("VERTEX_POINT('',#{p})"))
        })
        .collect();
    let vertical = (0..n)
        .map(|i| {
            let line = data.line(at(i, 0.0), at(i, thickness));
            let (a, b) = (bottom_vertices[i], top_vertices[i]);
            data.add(format!("EDGE_CURVE('',#{a},#{b},#{line},.T.)"))
        })
        .collect();
    let mut edges = LoopEdges {
        bottom: Vec::with_capacity(n),
        top: Vec::with_capacity(n),
        vertical,
        sides: Vec::with_capacity(n),
    };
    for i in 0..n {
        let j = (i + 1) % n;
        let (a, b) = (l.vertices[i], l.vertices[j]);
        for (z, vertices, out) in [
            (0.0, &bottom_vertices, &mut edges.bottom),
            (thickness, &top_vertices, &mut edges.top),
        ] {
            let (va, vb) = (vertices[i], vertices[j]);
            let edge = match Arc::from_bulge(a, b) {
                // the circle turns counterclockwise about +z: an arc turning clockwise
                // runs against it
                Some(arc) => {
                    let axis = data.placement(
                        [arc.centre[0], arc.centre[1], z],
                        [0.0, 0.0, 1.0],
                        [1.0, 0.0, 0.0],
                    );
                    let circle = data.add(format!("CIRCLE('',#{axis},{})", real(arc.radius)));
                    let sense = if arc.sweep > 0.0 { ".T." } else { ".F." };
                    data.add(format!("EDGE_CURVE('',#{va},#{vb},#{circle},{sense})"))
                }
                None => {
                    let line = data.line(at(i, z), at(j, z));
                    data.add(format!("EDGE_CURVE('',#{va},#{vb},#{line},.T.)"))
                }
            };
            out.push(edge);
        }
        // the material lies left of the loop's way (seen from +z): the outward normal of
        // a side points to its right
        let side = match Arc::from_bulge(a, b) {
            Some(arc) => {
                let axis = data.placement(
                    [arc.centre[0], arc.centre[1], 0.0],
                    [0.0, 0.0, 1.0],
                    [1.0, 0.0, 0.0],
                );
                let cylinder = data.add(format!(
                    "CYLINDRICAL_SURFACE('',#{axis},{})",
                    real(arc.radius)
                ));
                // a counterclockwise arc has the material towards its centre, so the
                // outward normal is the cylinder's (away from the axis)
                (cylinder, arc.sweep > 0.0)
            }
            None => {
                let (dx, dy) = (b.x - a.x, b.y - a.y);
                let length = dx.hypot(dy);
                let axis = data.placement(
                    at(i, 0.0),
                    [dy / length, -dx / length, 0.0],
                    [dx / length, dy / length, 0.0],
                );
                (data.add(format!("PLANE('',#{axis})")), true)
            }
        };
        edges.sides.push(side);
    }
    edges
}

/// An `EDGE_LOOP` of `(edge, sense)`.
fn edge_loop(data: &mut Data, edges: &[(usize, bool)]) -> usize {
    let oriented: Vec<String> = edges
        .iter()
        .map(|&(e, sense)| {
            let s = if sense { ".T." } else { ".F." };
            format!("#{}", data.add(format!("ORIENTED_EDGE('',*,*,#{e},{s})")))
        })
        .collect();
    data.add(format!("EDGE_LOOP('',({}))", oriented.join(",")))
}

/// A face on `surface` bounded by `loops` (the first the outer bound).
fn face(data: &mut Data, loops: &[usize], surface: usize, same_sense: bool) -> usize {
    let bounds: Vec<String> = loops
        .iter()
        .enumerate()
        .map(|(k, &l)| {
            let kind = if k == 0 {
                "FACE_OUTER_BOUND"
            } else {
                "FACE_BOUND"
            };
            format!("#{}", data.add(format!("{kind}('',#{l},.T.)")))
        })
        .collect();
    let sense = if same_sense { ".T." } else { ".F." };
    data.add(format!(
        "ADVANCED_FACE('',({}),#{surface},{sense})",
        bounds.join(",")
    ))
}

/// The faces of the solid: bottom, top, then each loop's sides in the loop's order.
fn faces(data: &mut Data, part: &super::PartMm) -> Vec<usize> {
    let t = part.width;
    let loops: Vec<LoopEdges> = part.loops.iter().map(|l| loop_edges(data, l, t)).collect();
    // the bottom is seen from -z: each loop backwards
    let bottom_loops: Vec<usize> = loops
        .iter()
        .map(|l| {
            let edges: Vec<(usize, bool)> = l.bottom.iter().rev().map(|&e| (e, false)).collect();
            edge_loop(data, &edges)
        })
        .collect();
    let bottom_plane = data.placement([0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]);
    let bottom_plane = data.add(format!("PLANE('',#{bottom_plane})"));
    let mut out = vec![face(data, &bottom_loops, bottom_plane, true)];
    let top_loops: Vec<usize> = loops
        .iter()
        .map(|l| {
            let edges: Vec<(usize, bool)> = l.top.iter().map(|&e| (e, true)).collect();
            edge_loop(data, &edges)
        })
        .collect();
    let top_plane = data.placement([0.0, 0.0, t], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let top_plane = data.add(format!("PLANE('',#{top_plane})"));
    out.push(face(data, &top_loops, top_plane, true));
    for l in &loops {
        let n = l.bottom.len();
        for i in 0..n {
            // seen from outside: along the bottom, up at the next vertex, back along the
            // top, down at this vertex
            let side = edge_loop(
                data,
                &[
                    (l.bottom[i], true),
                    (l.vertical[(i + 1) % n], true),
                    (l.top[i], false),
                    (l.vertical[i], false),
                ],
            );
            let (surface, same_sense) = l.sides[i];
            out.push(face(data, &[side], surface, same_sense));
        }
    }
    out
}

/// `part.step` of `part`, named `name` (the problem's name) in the file's product.
pub fn to_string(part: &Part, name: &str) -> String {
    let part = part.in_mm();
    let mut data = Data { lines: Vec::new() };
    let name = string(name);
    // the product, its definition and the shape it has
    let application = data.add("APPLICATION_CONTEXT('automotive_design')".into());
    data.add(format!(
        "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{application})"
    ));
    let context = data.add(format!("PRODUCT_CONTEXT('',#{application},'mechanical')"));
    let product = data.add(format!("PRODUCT({name},{name},'',(#{context}))"));
    data.add(format!(
        "PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{product}))"
    ));
    let formation = data.add(format!("PRODUCT_DEFINITION_FORMATION('','',#{product})"));
    let definition_context = data.add(format!(
        "PRODUCT_DEFINITION_CONTEXT('part definition',#{application},'design')"
    ));
    let definition = data.add(format!(
        "PRODUCT_DEFINITION('design','',#{formation},#{definition_context})"
    ));
    let shape = data.add(format!("PRODUCT_DEFINITION_SHAPE('','',#{definition})"));
    // millimetres, radians, and the precision of the coordinates
    let mm = data.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))".into());
    let radian = data.add("(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))".into());
    let steradian = data.add("(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())".into());
    let uncertainty = data.add(format!(
        "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#{mm},'distance_accuracy_value','confusion accuracy')"
    ));
    let geometry = data.add(format!(
        "(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{uncertainty}))GLOBAL_UNIT_ASSIGNED_CONTEXT((#{mm},#{radian},#{steradian}))REPRESENTATION_CONTEXT('',''))"
    ));
    let faces = faces(&mut data, &part)
        .iter()
        .map(|f| format!("#{f}"))
        .collect::<Vec<_>>()
        .join(",");
    let shell = data.add(format!("CLOSED_SHELL('',({faces}))"));
    let solid = data.add(format!("MANIFOLD_SOLID_BREP({name},#{shell})"));
    let origin = data.placement([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let representation = data.add(format!(
        "ADVANCED_BREP_SHAPE_REPRESENTATION({name},(#{origin},#{solid}),#{geometry})"
    ));
    data.add(format!(
        "SHAPE_DEFINITION_REPRESENTATION(#{shape},#{representation})"
    ));
    let mut out = String::new();
    out.push_str("ISO-10303-21;\nHEADER;\n");
    let _ = writeln!(
        out,
        "FILE_DESCRIPTION(('the part: its outline extruded through the plate thickness {} mm'),'2;1');",
        real(part.width)
    );
    let _ = writeln!(
        out,
        "FILE_NAME({name},'{TIME_STAMP}',(''),(''),'flexopt','flexopt','');"
    );
    out.push_str("FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n");
    for (k, line) in data.lines.iter().enumerate() {
        let _ = writeln!(out, "#{}={line};", k + 1);
    }
    out.push_str("ENDSEC;\nEND-ISO-10303-21;\n");
    out
}

#[cfg(test)]
mod tests {
    use super::{real, string};

    #[test]
    fn reals_are_written_with_a_point_and_read_back_exactly() {
        for (v, s) in [
            (23.0, "23.0"),
            (1e-7, "1.E-7"),
            (-1.5e20, "-1.5E20"),
            (0.1, "0.1"),
        ] {
            assert_eq!(real(v), s);
            let back: f64 = s.replace(".E", ".0E").parse().unwrap();
            assert_eq!(back, v, "{s}");
        }
    }

    #[test]
    fn strings_double_quotes_and_encode_what_is_not_ascii() {
        assert_eq!(string("it's"), "'it''s'");
        assert_eq!(string("a\\b"), "'a\\\\b'");
        assert_eq!(string("Ti-6Al-4V µ"), "'Ti-6Al-4V \\X2\\00B5\\X0\\'");
    }
}
