//! The whole part's model at one level of a verification, for CalculiX and for checks.

use super::level::{face_edges, face_nodes};
use super::Verification;
use crate::fe::element::{Elastic, Idealization};
use crate::fe::geometry::Domain;
use crate::fe::mesh::Mesh;
use crate::fe::{loads, FeError};

/// The whole part's mesh at one level of a verification, with its faces and the two static
/// load cases on it: the model the CalculiX decks describe.
pub struct FullModel {
    pub mesh: Mesh,
    pub domain: Domain,
    /// The nodes of each named face.
    pub sets: Vec<(String, Vec<usize>)>,
    pub clamp: Vec<usize>,
    pub cases: Vec<crate::fe::calculix::LoadCase>,
    /// The edges of the input faces (left, right) and of the output face.
    pub input: [Vec<[usize; 3]>; 2],
    pub output: Vec<[usize; 3]>,
}

impl Verification {
    /// The whole part's model at `level`: the half mesh mirrored, the test force on each
    /// input face (pushing them apart), then on the output face (pulling it outward).
    pub fn full_model(&self, level: usize) -> Result<FullModel, FeError> {
        let domain = Domain::of_part(&self.part);
        let tol = 1e-9 * domain.size();
        let mesh = self.meshes[level].mirrored_about_y(tol);
        let edges = |name: &str| face_edges(&mesh, &domain, name);
        let (left, right, output) = (
            edges("input_left")?,
            edges("input_right")?,
            edges("output_top")?,
        );
        let w = self.width;
        let f = self.test_force;
        let area = |e: &[[usize; 3]]| loads::length(&mesh, e) * w;
        let mut inputs = loads::uniform_force(&mesh, &left, w, [-f, 0.0]);
        for (a, b) in inputs
            .iter_mut()
            .zip(loads::uniform_force(&mesh, &right, w, [f, 0.0]))
        {
            *a += b;
        }
        let cases = vec![
            crate::fe::calculix::LoadCase {
                name: format!("{f} N on each input face, pushing them apart"),
                forces: inputs,
                tractions: vec![
                    (left.clone(), [-f / area(&left), 0.0]),
                    (right.clone(), [f / area(&right), 0.0]),
                ],
            },
            crate::fe::calculix::LoadCase {
                name: format!("{f} N on the output face, the input faces free"),
                forces: loads::uniform_force(&mesh, &output, w, [0.0, f]),
                tractions: vec![(output.clone(), [0.0, f / area(&output)])],
            },
        ];
        let sets = ["input_left", "input_right", "output_top", "clamp_bottom"]
            .iter()
            .map(|&name| (name.to_string(), face_nodes(&mesh, &domain, name)))
            .collect();
        Ok(FullModel {
            clamp: face_nodes(&mesh, &domain, "clamp_bottom"),
            mesh,
            domain,
            sets,
            cases,
            input: [left, right],
            output,
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

    /// The displacements (full vectors) of the two load cases, by flexopt's own solve of
    /// this whole mesh, the clamping face held.
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

    /// `x_in`, `y_out` (input case) and the output face's displacement (output case) of
    /// the displacement fields of the two cases (full vectors).
    pub fn face_outputs(&self, u_input: &[f64], u_output: &[f64]) -> [f64; 3] {
        let left = loads::mean_displacement(&self.mesh, &self.input[0], u_input);
        let right = loads::mean_displacement(&self.mesh, &self.input[1], u_input);
        [
            right[0] - left[0],
            -loads::mean_displacement(&self.mesh, &self.output, u_input)[1],
            loads::mean_displacement(&self.mesh, &self.output, u_output)[1],
        ]
    }
}
