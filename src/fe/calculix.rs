//! The analysis as CalculiX input decks, so that the open-source solver `ccx` can check it:
//! the 2D mesh as the element's own plane stress or plane strain element (CPS6 or CPE6 for
//! the six-node triangle), and the same mesh extruded through the width into the element's
//! prism (C3D15, 15-node wedges, for the triangle), the 3D model a designer would
//! otherwise build in another program; the names and node orders come from
//! [`Element`]. Units: mm, N, MPa, tonne/mm^3 (ccx takes any
//! consistent set).
//!
//! Each load case is a step of its own: the clamping face held, the forces of the case as
//! nodal loads in 2D (`*CLOAD`, the very consistent loads flexopt applies) and as pressures
//! on the wedges' faces in 3D (`*DLOAD`, so that ccx integrates them itself),
//! displacements printed for every node.
//! ccx expands 2D elements into one layer of 3D elements as thick as the section: plane
//! strain exactly (it holds the third direction), plane stress only when the section is thin
//! against the elements (see [`Deck::thickness_scale`]).

use std::fmt::Write as _;

use super::element::{Elastic, Element, Idealization, PartElement};
use super::mesh::{EdgeNodes, Mesh};
use super::solid::Layers;

/// A load case: its name, its nodal forces (N, two a node) for the 2D deck, and the same
/// loads as uniform tractions on boundary edges (Pa) for the 3D deck.
#[derive(Debug, Clone)]
pub struct LoadCase<E: Element = PartElement> {
    pub name: String,
    pub forces: Vec<f64>,
    pub tractions: Vec<(Vec<EdgeNodes<E>>, [f64; 2])>,
}

/// What a deck describes, in metres and newtons (written in mm).
pub struct Deck<'a, E: Element = PartElement> {
    pub title: String,
    pub mesh: &'a Mesh<E>,
    pub material: Elastic,
    pub width: f64,
    /// Node sets to write, by name (the faces).
    pub sets: Vec<(String, Vec<usize>)>,
    /// The nodes held in both directions.
    pub clamp: Vec<usize>,
    pub cases: Vec<LoadCase<E>>,
    /// The 2D section's thickness and the loads multiplied by this (1 for the part as it
    /// is): with a small factor ccx's one layer of 3D elements is plane stress and the
    /// displacements are unchanged.
    pub thickness_scale: f64,
}

const MM: f64 = 1e3;

fn node_line(out: &mut String, id: usize, x: f64, y: f64, z: Option<f64>) {
    match z {
        Some(z) => {
            let _ = writeln!(
                out,
                "{id}, {:.10e}, {:.10e}, {:.10e}",
                x * MM,
                y * MM,
                z * MM
            );
        }
        None => {
            let _ = writeln!(out, "{id}, {:.10e}, {:.10e}", x * MM, y * MM);
        }
    }
}

fn sets(out: &mut String, name: &str, ids: impl Iterator<Item = usize>) {
    let _ = writeln!(out, "*NSET, NSET={}", name.to_uppercase());
    let ids: Vec<String> = ids.map(|i| i.to_string()).collect();
    for chunk in ids.chunks(12) {
        let _ = writeln!(out, "{}", chunk.join(", "));
    }
}

fn material(out: &mut String, m: &Elastic) {
    let _ = writeln!(out, "*MATERIAL, NAME=PART");
    let _ = writeln!(out, "*ELASTIC");
    // Pa -> MPa; kg/m^3 -> tonne/mm^3
    let _ = writeln!(
        out,
        "{:.10e}, {:.10e}",
        m.youngs_modulus * 1e-6,
        m.poisson_ratio
    );
    let _ = writeln!(out, "*DENSITY");
    let _ = writeln!(out, "{:.10e}", m.density * 1e-12);
}

impl<E: Element> Deck<'_, E> {
    /// The 2D deck (CPS6 or CPE6 for the six-node triangle).
    pub fn two_d(&self, idealization: Idealization) -> String {
        let mut out = String::new();
        let _ = writeln!(
            out,
            "*HEADING\n{} ({}, flexopt)",
            self.title,
            idealization.name()
        );
        let _ = writeln!(out, "*NODE, NSET=NALL");
        for (i, p) in self.mesh.nodes.iter().enumerate() {
            node_line(&mut out, i + 1, p[0], p[1], None);
        }
        let kind = E::calculix_name(idealization);
        let _ = writeln!(out, "*ELEMENT, TYPE={kind}, ELSET=EALL");
        for (e, el) in self.mesh.elements.iter().enumerate() {
            let ids: Vec<String> = el.as_ref().iter().map(|n| (n + 1).to_string()).collect();
            let _ = writeln!(out, "{}, {}", e + 1, ids.join(", "));
        }
        for (name, nodes) in &self.sets {
            sets(&mut out, name, nodes.iter().map(|n| n + 1));
        }
        sets(&mut out, "clamp", self.clamp.iter().map(|n| n + 1));
        material(&mut out, &self.material);
        let _ = writeln!(out, "*SOLID SECTION, ELSET=EALL, MATERIAL=PART");
        let _ = writeln!(out, "{:.10e}", self.width * self.thickness_scale * MM);
        let _ = writeln!(out, "*BOUNDARY\nCLAMP, 1, 2");
        for case in &self.cases {
            let _ = writeln!(out, "** load case: {}", case.name);
            let _ = writeln!(out, "*STEP\n*STATIC\n*CLOAD, OP=NEW");
            for (d, &f) in case.forces.iter().enumerate() {
                if f != 0.0 {
                    let _ = writeln!(
                        out,
                        "{}, {}, {:.10e}",
                        d / 2 + 1,
                        d % 2 + 1,
                        f * self.thickness_scale
                    );
                }
            }
            let _ = writeln!(out, "*NODE PRINT, NSET=NALL\nU\n*END STEP");
        }
        out
    }

    /// The 3D deck: the mesh extruded through the half-width (`z` from 0 to `w / 2`) in the
    /// graded `layers` of prisms, the mid-width plane `z = 0` held in z (the plane of
    /// symmetry), the clamping face held on its whole surface, the loads as pressures on the
    /// faces (the faces of a load must be normal to its traction, as the bridge's are):
    /// the whole plate's displacements, under half of its loads. Node `plane * n + k + 1`
    /// stands on the 2D node `k` (of `n`).
    pub fn three_d(&self, layers: &Layers) -> String {
        let mut out = String::new();
        let _ = writeln!(
            out,
            "*HEADING\n{} (3D, half of the width in {} graded layers of {}, flexopt)",
            self.title,
            layers.count,
            E::CALCULIX_EXTRUDED
        );
        let n2 = self.mesh.nodes.len();
        let planes = layers.planes();
        let id = |plane: usize, node: usize| plane * n2 + node + 1;
        // the nodes the prism has on its middle plane (corners) appear on every plane, the
        // others on the even planes
        let mut corner = vec![false; n2];
        for el in &self.mesh.elements {
            for &(plane, k) in E::EXTRUSION {
                if plane == 1 {
                    corner[el[k]] = true;
                }
            }
        }
        let used = |plane: usize, node: usize| plane.is_multiple_of(2) || corner[node];
        let _ = writeln!(out, "*NODE, NSET=NALL");
        for plane in 0..planes {
            for (i, p) in self.mesh.nodes.iter().enumerate() {
                if used(plane, i) {
                    node_line(&mut out, id(plane, i), p[0], p[1], Some(layers.z(plane)));
                }
            }
        }
        let _ = writeln!(out, "*ELEMENT, TYPE={}, ELSET=EALL", E::CALCULIX_EXTRUDED);
        let mut e3 = 0;
        for layer in 0..layers.count {
            for el in &self.mesh.elements {
                e3 += 1;
                let s: Vec<String> = E::EXTRUSION
                    .iter()
                    .map(|&(plane, k)| id(2 * layer + plane, el[k]).to_string())
                    .collect();
                // ccx reads at most 16 entries a line: the number and ten nodes, then the
                // rest by fifteen
                let (first, rest) = s.split_at(s.len().min(10));
                let mut line = format!("{e3}, {}", first.join(", "));
                for chunk in rest.chunks(15) {
                    line += ",\n";
                    line += &chunk.join(", ");
                }
                let _ = writeln!(out, "{line}");
            }
        }
        let through = |nodes: &[usize]| -> Vec<usize> {
            let mut ids = Vec::new();
            for plane in 0..planes {
                for &n in nodes {
                    if used(plane, n) {
                        ids.push(id(plane, n));
                    }
                }
            }
            ids
        };
        for (name, nodes) in &self.sets {
            sets(&mut out, name, through(nodes).into_iter());
        }
        sets(&mut out, "clamp", through(&self.clamp).into_iter());
        sets(&mut out, "midwidth", (0..n2).map(|n| id(0, n)));
        material(&mut out, &self.material);
        let _ = writeln!(out, "*SOLID SECTION, ELSET=EALL, MATERIAL=PART");
        let _ = writeln!(out, "*BOUNDARY\nCLAMP, 1, 3\nMIDWIDTH, 3, 3");
        // each boundary edge's element and its side
        let mut side = std::collections::HashMap::new();
        for (e, el) in self.mesh.elements.iter().enumerate() {
            for (k, &(i, j)) in E::SIDES.iter().enumerate() {
                let (a, b) = (el[i], el[j]);
                side.insert((a.min(b), a.max(b)), (e, k));
            }
        }
        let count = self.mesh.elements.len();
        for case in &self.cases {
            let _ = writeln!(out, "** load case: {}", case.name);
            let _ = writeln!(out, "*STEP\n*STATIC\n*DLOAD, OP=NEW");
            for (edges, traction) in &case.tractions {
                for edge in edges {
                    let (a, b) = (edge[0], edge[E::EDGE_NODES - 1]);
                    let Some(&(e, k)) = side.get(&(a.min(b), a.max(b))) else {
                        continue;
                    };
                    // the outward normal: the element's interior lies left of its sides
                    let el = self.mesh.elements[e];
                    let (i, j) = E::SIDES[k];
                    let (p, q) = (self.mesh.nodes[el[i]], self.mesh.nodes[el[j]]);
                    let len = (q[0] - p[0]).hypot(q[1] - p[1]);
                    let normal = [(q[1] - p[1]) / len, -(q[0] - p[0]) / len];
                    // a pressure pushes against the outward normal
                    let pressure = -(traction[0] * normal[0] + traction[1] * normal[1]);
                    for layer in 0..layers.count {
                        let _ = writeln!(
                            out,
                            "{}, P{}, {:.10e}",
                            layer * count + e + 1,
                            E::EXTRUDED_FACES[k],
                            pressure * 1e-6
                        );
                    }
                }
            }
            let _ = writeln!(out, "*NODE PRINT, NSET=NALL\nU\n*END STEP");
        }
        out
    }
}

/// The displacements of every step in a `.dat` file of ccx (mm, per node id), in metres:
/// for each step, `(node id, [ux, uy, uz])`.
pub fn read_displacements(dat: &str) -> Vec<Vec<(usize, [f64; 3])>> {
    let mut steps = Vec::new();
    let mut current: Option<Vec<(usize, [f64; 3])>> = None;
    for line in dat.lines() {
        if line.trim_start().starts_with("displacements") {
            if let Some(c) = current.take() {
                steps.push(c);
            }
            current = Some(Vec::new());
            continue;
        }
        let Some(c) = current.as_mut() else { continue };
        let f: Vec<&str> = line.split_whitespace().collect();
        if f.len() == 4 {
            if let (Ok(id), Ok(x), Ok(y), Ok(z)) = (
                f[0].parse::<usize>(),
                f[1].parse::<f64>(),
                f[2].parse::<f64>(),
                f[3].parse::<f64>(),
            ) {
                c.push((id, [x / MM, y / MM, z / MM]));
            }
        }
    }
    if let Some(c) = current {
        steps.push(c);
    }
    steps
}
