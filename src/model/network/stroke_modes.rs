//! The network's natural frequencies about its equilibrium at stroke (issue 48): the linear
//! model's modes ([`NetworkModel::modal_families`]: each family's holds on the mirror axes,
//! the bodies' masses and inertias, the payload, the stack's masses, the part unfolded about
//! its mounting) on the tangent stiffness of the structure at stroke ([`super::stroke`])
//! in the place of the linear network's.
//!
//! The tangent of the driven structure (the stack in place as its spring, which is what the
//! linear model's modes stand on) is assembled at the equilibrium with the bodies' master
//! nodes released, and condensed statically onto them, the flexures' inner nodes massless as
//! the linear model's flexures (Guyan's reduction: R. J. Guyan, "Reduction of stiffness and
//! mass matrices", AIAA J. 3(2) (1965) 380). Its geometric stiffness (the flexures' axial
//! forces and the loads carried by the rigid offsets) is what makes the part stiffer or softer
//! at stroke. A family where the stack is not stretched leaves its spring out (and a stack
//! without a stiffness, which prescribes the input's motion, holds the input in the
//! stretched families only). The masses are the linear model's, carried with each body to
//! where it stands at the equilibrium; the holds are its holds at the points it holds, as
//! they move. `K phi = w^2 M phi` on the motions the holds leave, by a Cholesky factor of
//! `M` and a symmetric eigensolver (nalgebra), as [`super::modes`].

use nalgebra::{DMatrix, Matrix3, SymmetricEigen, Vector3};

use super::model::stroke::Built;
use super::model::{Family, NetworkModel};
use super::modes::{DirectedMass, Inertia};
use super::structure::{Body, Dof as NetDof, Network};
use crate::model::large::assemble::System;
use crate::model::large::Dof;

/// The `count` lowest natural frequencies (Hz) of the network `model` at the design `x`
/// (SI) about the equilibrium of `built` (its structure at that design) at the load factor
/// `lambda`, where every node has moved by `u` (`(u, v, theta)` a node, as
/// [`crate::model::large::PathPoint::displacement`]). At `u = 0` and `lambda = 0` they are
/// the linear model's `f1`, `f2`, ... (its modes of the same masses on the same stiffness).
/// A stack without a stiffness is rigid: it holds the input where it stretches, where the
/// linear model has no frequencies.
// the report at stroke (`super::at_stroke`) is to take it
#[cfg_attr(not(test), allow(dead_code))]
pub(super) fn frequencies_at(
    model: &NetworkModel,
    x: &[f64],
    built: &Built<f64>,
    u: &[f64],
    lambda: f64,
    count: usize,
) -> Result<Vec<f64>, String> {
    if let Some(g) = model.description().supports.first() {
        return Err(format!(
            "the natural frequencies of a network with supports ({}) are not modelled",
            g.key
        ));
    }
    if u.len() != 3 * built.driven.nodes.len() {
        return Err(format!(
            "{} displacements for {} nodes",
            u.len(),
            built.driven.nodes.len()
        ));
    }
    let families = model.modal_families(x)?;
    // the condensed tangent with the stack and without, each found once
    let mut condensed: [Option<DMatrix<f64>>; 2] = [None, None];
    let mut found = Vec::new();
    for f in &families {
        let slot = &mut condensed[usize::from(f.stretched)];
        if slot.is_none() {
            *slot = Some(condense(built, u, lambda, f.stretched)?);
        }
        let k = slot.as_ref().expect("found above");
        found.extend(family_frequencies(built, u, f, k)?);
    }
    if found.len() < count {
        return Err(format!(
            "the network has {} modes; {count} asked for",
            found.len()
        ));
    }
    found.sort_by(f64::total_cmp);
    found.truncate(count);
    Ok(found)
}

/// The tangent stiffness of the driven structure at `(u, lambda)` condensed onto the bodies'
/// master nodes (`3` rows a body, in their order), the masters' holds released (the modes
/// hold them), the stack's spring left out unless `stretched`.
fn condense(
    built: &Built<f64>,
    u: &[f64],
    lambda: f64,
    stretched: bool,
) -> Result<DMatrix<f64>, String> {
    let masters = &built.masters;
    let mut s = built.driven.clone();
    s.held.retain(|&(node, _, _)| !masters.contains(&node));
    if !stretched {
        s.springs.clear();
    }
    let large = |e: crate::model::large::LargeError| format!("the structure at stroke: {e}");
    let system = System::new(&s).map_err(large)?;
    let a = system.assemble(u, lambda);
    let position = |i: usize| system.free.iter().position(|&f| f == i);
    let outer: Vec<usize> = masters
        .iter()
        .flat_map(|&m| (0..3).map(move |j| 3 * m + j))
        .map(|i| position(i).ok_or("a body's master node is held"))
        .collect::<Result<_, _>>()?;
    let inner: Vec<usize> = (0..system.free.len())
        .filter(|p| !outer.contains(p))
        .collect();
    let pick = |r: &[usize], c: &[usize]| {
        DMatrix::from_fn(r.len(), c.len(), |i, j| a.tangent[(r[i], c[j])])
    };
    let mut k = pick(&outer, &outer);
    if !inner.is_empty() {
        let k_oi = pick(&outer, &inner);
        let solved = pick(&inner, &inner)
            .lu()
            .solve(&k_oi.transpose())
            .ok_or("the flexures' inner nodes have a singular tangent stiffness")?;
        k -= &k_oi * solved;
    }
    Ok((&k + k.transpose()) * 0.5)
}

/// The rows `[u, v, theta]` of a hold of `dof` at a point `r` from the body's master.
fn hold_row(dof: NetDof, r: [f64; 2]) -> [f64; 3] {
    match dof {
        NetDof::X => [1.0, 0.0, -r[1]],
        NetDof::Y => [0.0, 1.0, r[0]],
        NetDof::Rotation => [0.0, 0.0, 1.0],
    }
}

/// The rigid transfer `[u_p, v_p, theta] = T [u, v, theta]` to a point `r` from the master.
fn transfer(r: [f64; 2]) -> Matrix3<f64> {
    Matrix3::new(1.0, 0.0, -r[1], 0.0, 1.0, r[0], 0.0, 0.0, 1.0)
}

/// A basis of the motions of a body (`3` columns at most) that its hold rows leave free.
fn free_motions(rows: &[[f64; 3]]) -> Vec<[f64; 3]> {
    if rows.is_empty() {
        return vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    }
    let g = Matrix3::from_fn(|i, j| rows.iter().map(|r| r[i] * r[j]).sum::<f64>());
    let eigen = SymmetricEigen::new(g);
    let scale = eigen.eigenvalues.amax().max(f64::MIN_POSITIVE);
    (0..3)
        .filter(|&i| eigen.eigenvalues[i] <= 1e-12 * scale)
        .map(|i| {
            let c = eigen.eigenvectors.column(i);
            [c[0], c[1], c[2]]
        })
        .collect()
}

/// Where each body of the family stands at the equilibrium: the described body it is, and
/// whether it is its image across the line `y = 0` (`Some(true)`) or `x = 0`.
struct Placement<'a> {
    built: &'a Built<f64>,
    u: &'a [f64],
    source: Vec<(usize, bool)>,
    flip_y: Option<bool>,
}

impl Placement<'_> {
    fn reflect(&self, p: [f64; 2]) -> [f64; 2] {
        match self.flip_y {
            Some(true) => [p[0], -p[1]],
            _ => [-p[0], p[1]],
        }
    }

    /// Where the point `p` of body `i` (at its reference) stands at the equilibrium.
    fn moved(&self, i: usize, p: [f64; 2]) -> [f64; 2] {
        let (b, image) = self.source[i];
        let m = self.built.masters[b];
        let xm = self.built.driven.nodes[m];
        let q = if image { self.reflect(p) } else { p };
        let (s, c) = self.u[3 * m + 2].sin_cos();
        let r = [q[0] - xm[0], q[1] - xm[1]];
        let at = [
            xm[0] + self.u[3 * m] + c * r[0] - s * r[1],
            xm[1] + self.u[3 * m + 1] + s * r[0] + c * r[1],
        ];
        if image {
            self.reflect(at)
        } else {
            at
        }
    }

    /// Body `i`'s master point at the equilibrium, where its motions are measured.
    fn master(&self, i: usize) -> [f64; 2] {
        let (b, image) = self.source[i];
        let xm = self.built.driven.nodes[self.built.masters[b]];
        self.moved(i, if image { self.reflect(xm) } else { xm })
    }
}

/// The frequencies (Hz) of one family: the condensed tangent `k` of the described part,
/// with its image's where the family is unfolded, the family's masses and holds.
fn family_frequencies(
    built: &Built<f64>,
    u: &[f64],
    f: &Family<f64>,
    k: &DMatrix<f64>,
) -> Result<Vec<f64>, String> {
    let nb = built.masters.len();
    let mut source: Vec<(usize, bool)> = (0..nb).map(|b| (b, false)).collect();
    for (b, im) in f.images.iter().enumerate() {
        if let Body::Rigid(i) = *im {
            if i != b {
                debug_assert_eq!(i, source.len());
                source.push((b, true));
            }
        }
    }
    let place = Placement {
        built,
        u,
        source,
        flip_y: f.unfolded,
    };
    let n = place.source.len();
    if f.network.references.len() != n || f.inertia.len() != n {
        return Err("the linear model's bodies are not the structure's".into());
    }
    let masters: Vec<[f64; 2]> = (0..n).map(|i| place.master(i)).collect();
    let stiffness = unfold(&place, f, k, &masters);
    let mass = {
        let inertia: Vec<Inertia<f64>> = (f.inertia.iter().enumerate())
            .map(|(i, m)| Inertia {
                centroid: place.moved(i, m.centroid),
                ..*m
            })
            .collect();
        let directed: Vec<DirectedMass<f64>> = (f.directed.iter())
            .map(|d| DirectedMass {
                point: place.moved(d.body, d.point),
                ..*d
            })
            .collect();
        let at = Network {
            references: masters.clone(),
            flexures: Vec::new(),
            springs: Vec::new(),
            held: Vec::new(),
            guides: Vec::new(),
        };
        DMatrix::from_row_slice(3 * n, 3 * n, &at.mass_matrix_with(&inertia, &directed))
    };
    let basis = free_basis(built, f, &place, &masters);
    solve(&stiffness, &mass, &basis)
}

/// The condensed tangent on the family's bodies: the described part's, and on a part
/// unfolded its image's, `S K S` (the reflection's signs) carried to each image's master.
fn unfold(
    place: &Placement,
    f: &Family<f64>,
    k: &DMatrix<f64>,
    masters: &[[f64; 2]],
) -> DMatrix<f64> {
    let (nb, n) = (place.built.masters.len(), place.source.len());
    let mut out = DMatrix::zeros(3 * n, 3 * n);
    out.view_mut((0, 0), (3 * nb, 3 * nb)).copy_from(k);
    let Some(flip_y) = f.unfolded else {
        return out;
    };
    let signs = if flip_y {
        Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, -1.0))
    } else {
        Matrix3::from_diagonal(&Vector3::new(-1.0, 1.0, -1.0))
    };
    // each described body's image and the map from its motions to the image copy's
    let maps: Vec<Option<(usize, Matrix3<f64>)>> = (0..nb)
        .map(|b| match f.images[b] {
            Body::Ground => None,
            Body::Rigid(i) => {
                let at = place.reflect(masters[b]);
                let r = [at[0] - masters[i][0], at[1] - masters[i][1]];
                Some((i, signs * transfer(r)))
            }
        })
        .collect();
    for (b, mb) in maps.iter().enumerate() {
        for (c, mc) in maps.iter().enumerate() {
            if let (Some((i, ti)), Some((j, tj))) = (mb, mc) {
                let block: Matrix3<f64> = k.fixed_view::<3, 3>(3 * b, 3 * c).into_owned();
                let add = ti.transpose() * block * tj;
                let mut target = out.fixed_view_mut::<3, 3>(3 * i, 3 * j);
                target += add;
            }
        }
    }
    out
}

/// The motions the family's holds leave, as columns: each body's free motions at its master.
/// The family's holds at their points as they stand; a stack without a stiffness holds its
/// input (and the input's image) along the stack where it is stretched.
fn free_basis(
    built: &Built<f64>,
    f: &Family<f64>,
    place: &Placement,
    masters: &[[f64; 2]],
) -> DMatrix<f64> {
    let n = masters.len();
    let mut rows: Vec<Vec<[f64; 3]>> = vec![Vec::new(); n];
    for &(i, dof) in &f.network.held {
        let p = place.moved(i, f.network.references[i]);
        rows[i].push(hold_row(dof, [p[0] - masters[i][0], p[1] - masters[i][1]]));
    }
    let input = built.ports[0].node;
    let driven = built
        .driven
        .held
        .iter()
        .filter(|h| h.0 == input && h.2 != 0.0);
    for &(_, dof, _) in driven.filter(|_| f.stretched) {
        let dof = match dof {
            Dof::X => NetDof::X,
            Dof::Y => NetDof::Y,
            Dof::Rotation => NetDof::Rotation,
        };
        let b = built.masters.iter().position(|&m| m == input);
        let image = b.and_then(|b| match f.images.get(b) {
            Some(&Body::Rigid(i)) => Some(i),
            _ => None,
        });
        for i in b.into_iter().chain(image) {
            rows[i].push(hold_row(dof, [0.0, 0.0]));
        }
    }
    let columns: Vec<(usize, [f64; 3])> = (0..n)
        .flat_map(|i| free_motions(&rows[i]).into_iter().map(move |c| (i, c)))
        .collect();
    let mut t = DMatrix::zeros(3 * n, columns.len());
    for (col, (i, c)) in columns.iter().enumerate() {
        for j in 0..3 {
            t[(3 * i + j, col)] = c[j];
        }
    }
    t
}

/// The frequencies (Hz) of `K phi = w^2 M phi` on the motions `phi = T q`.
fn solve(k: &DMatrix<f64>, m: &DMatrix<f64>, t: &DMatrix<f64>) -> Result<Vec<f64>, String> {
    let kr = t.transpose() * k * t;
    let mr = t.transpose() * m * t;
    let mr = (&mr + mr.transpose()) * 0.5;
    let chol = mr
        .cholesky()
        .ok_or("a body has no mass or no inertia where it can move")?;
    let l = chol.l();
    let y = l
        .solve_lower_triangular(&kr)
        .ok_or("a singular mass matrix")?;
    let a = l
        .solve_lower_triangular(&y.transpose())
        .ok_or("a singular mass matrix")?;
    let a = (&a + a.transpose()) * 0.5;
    let eigen = SymmetricEigen::new(a);
    let mut w2: Vec<f64> = eigen.eigenvalues.iter().copied().collect();
    w2.sort_by(f64::total_cmp);
    if let Some(&low) = w2.first().filter(|&&v| v < 0.0) {
        return Err(format!(
            "the tangent stiffness is not positive definite there (w^2 = {low:e}): the \
             structure is past a critical point"
        ));
    }
    Ok(w2
        .into_iter()
        .map(|v| v.sqrt() / (2.0 * std::f64::consts::PI))
        .collect())
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::super::file::describe;
    use super::super::model::stroke::{build, Drive};
    use super::super::raw::RawNetwork;
    use super::*;
    use crate::model::actuator::{Actuator, RawActuator};
    use crate::model::large::solve::{continuation, Options};
    use crate::model::material::{Material, RawMaterial};
    use crate::model::Model;
    use crate::vocab::error::Locator;
    use crate::vocab::sections::Sections;

    const NETWORKS: [&str; 6] = [
        "bridge_lever",
        "guide",
        "lever",
        "rhombus",
        "scott_russell",
        "wei2017",
    ];

    /// The shipped network `name`'s model and the design of its `optimum.json`.
    fn shipped(name: &str) -> (NetworkModel, Vec<f64>) {
        let file = format!("problems/{name}_network.toml");
        let text = std::fs::read_to_string(&file).unwrap();
        let loc = Locator::new(Path::new(&file), &text);
        let s = Sections::new(&loc, &text, "network");
        let m: RawMaterial = s.required("material").unwrap();
        let n: RawNetwork = s.required("network").unwrap();
        let a: RawActuator = s.required("actuator").unwrap();
        let model = NetworkModel::new(
            describe(&s, &n).unwrap(),
            Material::from_section(&s, &m).unwrap(),
            Actuator::read(&s, &a).unwrap(),
        );
        // the optimum's design (SI) by parameter, read as its file writes it
        let optimum = format!("results/{name}_network/optimum.json");
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(optimum).unwrap()).unwrap();
        let x = model
            .parameters()
            .iter()
            .map(|p| json["design_si"][p.name.as_ref()].as_f64().unwrap())
            .collect();
        (model, x)
    }

    fn linear(model: &NetworkModel, x: &[f64], name: &str) -> f64 {
        let i = model.output_index(name).unwrap();
        let mut out = [0.0];
        model.evaluate(x, &[i], &mut out);
        out[0]
    }

    /// The first `count` frequencies at the unloaded state and at the full stroke, with
    /// `elements` a flexure.
    fn unloaded_and_stroke(name: &str, elements: usize, count: usize) -> [Vec<f64>; 2] {
        let (model, x) = shipped(name);
        let built = build(&model, &x, elements, Drive::Stack).unwrap();
        let zero = vec![0.0; 3 * built.driven.nodes.len()];
        let unloaded = frequencies_at(&model, &x, &built, &zero, 0.0, count).unwrap();
        let opts = Options {
            steps: 8,
            ..Options::default()
        };
        let path = continuation(&built.driven, 1.0, &opts).unwrap();
        let end = path.points.last().unwrap();
        let at = frequencies_at(&model, &x, &built, &end.displacement, end.lambda, count);
        [unloaded, at.unwrap()]
    }

    /// Unloaded, the frequencies are the linear model's `f1` and `f2` on every shipped
    /// network that has them, with 1 and 4 elements a flexure (the structure's unloaded
    /// stiffness is the linear network's for any number).
    #[test]
    fn unloaded_they_are_the_linear_models() {
        let mut compared = 0;
        for name in NETWORKS {
            let (model, x) = shipped(name);
            let f1 = model.output_index("f1").unwrap();
            if model.unavailable(f1).is_some() {
                continue;
            }
            let expected = [linear(&model, &x, "f1"), linear(&model, &x, "f2")];
            for elements in [1, 4] {
                let built = build(&model, &x, elements, Drive::Stack).unwrap();
                let zero = vec![0.0; 3 * built.driven.nodes.len()];
                let got = frequencies_at(&model, &x, &built, &zero, 0.0, 2).unwrap();
                for (g, e) in got.iter().zip(expected) {
                    let rel = (g - e).abs() / e;
                    eprintln!("{name} n {elements}: {g} Hz against {e} Hz, {rel:.1e}");
                    assert!(rel < 1e-8, "{name} n {elements}: {g} against {e}");
                }
            }
            compared += 1;
        }
        assert_eq!(compared, 3, "bridge_lever, lever and scott_russell have f1");
    }

    /// wei2017's network at its optimum, its stack rigid (the file gives it no stiffness):
    /// the first frequency rises at the full stroke, the part stiffer there; 8 and 16
    /// elements a flexure agree.
    #[test]
    fn wei2017_stiffens_at_its_stroke() {
        let [unloaded, at] = unloaded_and_stroke("wei2017", 8, 2);
        let [_, finer] = unloaded_and_stroke("wei2017", 16, 2);
        let ratio = at[0] / unloaded[0];
        let n_2n = (finer[0] - at[0]).abs() / finer[0];
        eprintln!(
            "wei2017: f1 {} Hz unloaded, {} Hz at stroke ({ratio}), {} Hz with 16 elements \
             ({n_2n:.1e}); f2 {} -> {}",
            unloaded[0], at[0], finer[0], unloaded[1], at[1]
        );
        assert!(ratio > 1.0, "{ratio}");
        assert!(n_2n < 1e-3, "{n_2n}");
    }
}
