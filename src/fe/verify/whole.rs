//! The whole part's model at one level of a verification, for CalculiX and for checks.

use super::level::face_nodes;
use super::statement::{case_forces, measure, measure_solid, whole, Edges, Read};
use super::Verification;
use crate::fe::element::{Elastic, Idealization};
use crate::fe::geometry::Domain;
use crate::fe::mesh::{EdgeNodes, Mesh};
use crate::fe::solid::{self, Extruded, Layers};
use crate::fe::{loads, FeError};

/// The whole part's mesh at one level of a verification, with its faces and the static load
/// cases of its statement on it: the model the CalculiX decks describe.
pub struct FullModel {
    pub mesh: Mesh,
    pub domain: Domain,
    /// The nodes of each named face.
    pub sets: Vec<(String, Vec<usize>)>,
    pub clamp: Vec<usize>,
    pub cases: Vec<crate::fe::calculix::LoadCase>,
    /// The edges of every face the statement names.
    edges: Edges,
    /// Each measure's load case and terms.
    measures: Vec<(usize, Vec<Read>)>,
}

impl Verification {
    /// The whole part's model at `level`: the half mesh mirrored (or the whole part's mesh,
    /// where that was solved), each load case of the part's statement at the test force.
    pub fn full_model(&self, level: usize) -> Result<FullModel, FeError> {
        let domain = Domain::of_part(&self.part);
        let tol = 1e-9 * domain.size();
        let mesh = if self.whole_part {
            self.meshes[level].clone()
        } else {
            self.meshes[level].mirrored_about_y(tol)
        };
        let stated = whole(&self.analysis, self.test_force);
        let named = self.analysis.faces();
        let edges = Edges::of(&mesh, &domain, &named)?;
        let w = self.width;
        let f = self.test_force;
        let area = |e: &[EdgeNodes]| loads::length(&mesh, e) * w;
        let cases = self
            .analysis
            .cases
            .iter()
            .zip(&stated.cases)
            .map(|(case, applied)| crate::fe::calculix::LoadCase {
                name: format!("{f} N {}", case.name),
                forces: case_forces(&mesh, &edges, w, applied),
                tractions: applied
                    .iter()
                    .map(|a| {
                        let e = edges.get(&a.face);
                        (e.to_vec(), [a.total[0] / area(e), a.total[1] / area(e)])
                    })
                    .collect(),
            })
            .collect();
        // the named faces in the part's order
        let mut sets: Vec<(String, Vec<usize>)> = Vec::new();
        for face in &self.part.faces {
            if named.contains(&face.name.as_str()) && sets.iter().all(|(n, _)| *n != face.name) {
                sets.push((face.name.clone(), face_nodes(&mesh, &domain, &face.name)));
            }
        }
        let mut clamp: Vec<usize> = Vec::new();
        for name in &stated.clamped {
            clamp.extend(face_nodes(&mesh, &domain, name));
        }
        clamp.sort_unstable();
        clamp.dedup();
        Ok(FullModel {
            clamp,
            mesh,
            domain,
            sets,
            cases,
            edges,
            measures: stated.measures,
        })
    }
}

impl FullModel {
    /// The CalculiX deck of this model.
    pub fn deck(
        &self,
        title: &str,
        material: &Elastic,
        width: f64,
        thickness_scale: f64,
    ) -> crate::fe::calculix::Deck<'_> {
        crate::fe::calculix::Deck {
            title: title.to_string(),
            mesh: &self.mesh,
            material: *material,
            width,
            sets: self.sets.clone(),
            clamp: self.clamp.clone(),
            cases: self.cases.clone(),
            thickness_scale,
        }
    }

    /// The displacements (full vectors) of the load cases, by flexopt's own solve of this
    /// whole mesh, the clamped faces held.
    pub fn solve(
        &self,
        material: &Elastic,
        width: f64,
        idealization: Idealization,
    ) -> Result<Vec<Vec<f64>>, FeError> {
        let mut fixed = vec![false; 2 * self.mesh.nodes.len()];
        for &n in &self.clamp {
            fixed[2 * n] = true;
            fixed[2 * n + 1] = true;
        }
        let zero = vec![0.0; fixed.len()];
        let loads: Vec<Vec<f64>> = self.cases.iter().map(|c| c.forces.clone()).collect();
        crate::fe::solve_static(
            &self.mesh,
            material,
            width,
            idealization,
            &fixed,
            &zero,
            &loads,
        )
    }

    /// The displacements (full vectors, three a node of `ext`, this mesh extruded in
    /// `layers`) of the load cases in 3D, by flexopt's own solve: the half-width, the
    /// clamped faces held through it, the mid-width plane held in z, the loads as uniform
    /// tractions on their faces (the model of [`crate::fe::calculix::Deck::three_d`]).
    pub fn solve_3d(
        &self,
        material: &Elastic,
        layers: Layers,
    ) -> Result<(Extruded<'_>, Vec<Vec<f64>>), FeError> {
        let ext = Extruded::new(&self.mesh, layers);
        let fixed = solid::fixed(&ext, &self.clamp, &[]);
        let loads: Vec<Vec<f64>> = self
            .cases
            .iter()
            .map(|c| {
                let mut f = vec![0.0; 3 * ext.nodes.len()];
                for (edges, t) in &c.tractions {
                    let faces = ext.side_faces(edges);
                    for (s, v) in
                        f.iter_mut()
                            .zip(solid::traction_forces(&ext, &faces, [t[0], t[1], 0.0]))
                    {
                        *s += v;
                    }
                }
                f
            })
            .collect();
        let (u, _) = solid::solve(&ext, material, &fixed, &loads)?;
        Ok((ext, u))
    }

    /// The part's measures of 3D displacement fields on `ext` (as [`FullModel::measures`]:
    /// the faces' mean displacements, over their area through the half-width).
    pub fn measures_3d(&self, ext: &Extruded, u: &[Vec<f64>]) -> Vec<f64> {
        self.measures
            .iter()
            .map(|(case, terms)| measure_solid(ext, &self.edges, terms, &u[*case]))
            .collect()
    }

    /// The part's measures, in the statement's order, of the displacement fields of its
    /// load cases (full vectors, one a case).
    pub fn measures(&self, u: &[Vec<f64>]) -> Vec<f64> {
        self.measures
            .iter()
            .map(|(case, terms)| measure(&self.mesh, &self.edges, terms, &u[*case]))
            .collect()
    }
}
