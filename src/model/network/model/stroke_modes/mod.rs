//! The network's natural frequencies about its equilibrium at stroke (issue 48; the outputs
//! `nl_f1`, `nl_f2`, ... and the frequencies of `flexopt stroke`'s curves): the linear
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
//! they move ([`place`]). `K phi = w^2 M phi` on the motions the holds leave, `phi = T q`, by
//! a Cholesky factor of `M` and a symmetric eigensolver ([`eigenpairs`], the linear model's).
//!
//! Everything is computed over the scalar of the design. With the equilibrium's
//! displacement carrying its derivatives by the design
//! ([`crate::model::large::sensitivity::equilibrium_by_design`]), the condensed tangent
//! carries its own (the inner nodes' solve through [`Factored::solve_dual`]), as do the
//! masses (the linear model's, whose outlines move with the design, carried to the bodies'
//! places) and the basis `T` of the motions the holds leave. The eigenpairs are found on the
//! real parts, and each `w^2` is the Rayleigh quotient `q^T A q / q^T B q` of `A = T^T K T`
//! and `B = T^T M T` over the scalar at the real eigenvector `q` ([`rayleigh`], the linear
//! model's): for a simple eigenvalue its first derivative is the eigenvalue's, `d(w^2) =
//! q^T (dA - w^2 dB) q / q^T B q` (Fox and Kapoor, "Rates of change of eigenvalues and
//! eigenvectors", AIAA J. 6 (1968) 2426-2429, Eq. 9), exact to the equilibrium's tolerance.
//! A repeated eigenvalue has no derivative (its directional derivatives are the eigenvalues
//! of a problem on its eigenspace: R. B. Nelson, "Simplified calculation of eigenvector
//! derivatives", AIAA J. 14 (1976) 1201-1205, for the simple case it extends), so two
//! frequencies of one family within [`REPEATED`] of each other are refused, with the family
//! named. Modes of different families do not couple and each keeps its derivative where two
//! of them cross; the outputs take them in order of value, as the linear model's.

use nalgebra::DMatrix;

use super::stroke::Built;
use super::{Family, NetworkModel};
use crate::model::large::assemble::SystemOf;
use crate::model::large::sensitivity::Factored;
use crate::model::network::modes::{eigenpairs, rayleigh};
use crate::model::scalar::Scalar;

mod place;
#[cfg(test)]
mod tests;

use place::Placement;

/// Two `w^2` of one family closer than this, relative, are one repeated eigenvalue.
const REPEATED: f64 = 1e-9;

/// The `count` lowest natural frequencies (Hz) of the network `model` at the design `x`
/// (SI) about the equilibrium of `built` (its structure at that design) at the load factor
/// `lambda`, where every node has moved by `u` (`(u, v, theta)` a node, as
/// [`crate::model::large::PathPoint::displacement`]). Over the scalar of the design: `built`
/// built over it, `u` carrying its derivatives, each frequency carries its own (see the
/// module). At `u = 0` and `lambda = 0` they are the linear model's `f1`, `f2`, ... (its modes
/// of the same masses on the same stiffness). A stack without a stiffness is rigid: it holds
/// the input where it stretches, where the linear model has no frequencies.
pub(crate) fn frequencies_at<D: Scalar>(
    model: &NetworkModel,
    x: &[D],
    built: &Built<D>,
    u: &[D],
    lambda: f64,
    count: usize,
) -> Result<Vec<D>, String> {
    if count == 0 {
        return Ok(Vec::new());
    }
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
    let mut condensed: [Option<Vec<D>>; 2] = [None, None];
    let mut found = Vec::new();
    for f in &families {
        let slot = &mut condensed[usize::from(f.stretched)];
        if slot.is_none() {
            *slot = Some(condense(built, u, lambda, f.stretched)?);
        }
        let k = slot.as_ref().expect("found above");
        found.extend(family_frequencies(built, u, f, k, count)?);
    }
    if found.len() < count {
        return Err(format!(
            "the network has {} modes; {count} asked for",
            found.len()
        ));
    }
    // by value, the families' order breaking ties, as the linear model's
    found.sort_by(|a, b| a.re().total_cmp(&b.re()));
    found.truncate(count);
    Ok(found)
}

/// The tangent stiffness of the driven structure at `(u, lambda)` condensed onto the bodies'
/// master nodes (`3` rows a body, in their order, row-major), the masters' holds released
/// (the modes hold them), the stack's spring left out unless `stretched`: `K_oo - K_oi
/// K_ii^-1 K_io`, the inner solve on the real factors of `K_ii` with its derivative
/// ([`Factored::solve_dual`]).
fn condense<D: Scalar>(
    built: &Built<D>,
    u: &[D],
    lambda: f64,
    stretched: bool,
) -> Result<Vec<D>, String> {
    let masters = &built.masters;
    let mut s = built.driven.clone();
    s.held.retain(|&(node, _, _)| !masters.contains(&node));
    if !stretched {
        s.springs.clear();
    }
    let large = |e: crate::model::large::LargeError| format!("the structure at stroke: {e}");
    let system = SystemOf::new(&s).map_err(large)?;
    let full = &system.assemble_full(u, lambda).k;
    let m = u.len();
    let outer: Vec<usize> = masters
        .iter()
        .flat_map(|&b| (0..3).map(move |j| 3 * b + j))
        .collect();
    if !outer.iter().all(|i| system.free.contains(i)) {
        return Err("a body's master node is held".into());
    }
    let inner: Vec<usize> = (system.free.iter().copied())
        .filter(|i| !outer.contains(i))
        .collect();
    let pick = |r: &[usize], c: &[usize]| -> Vec<D> {
        r.iter()
            .flat_map(|&i| c.iter().map(move |&j| full[i * m + j]))
            .collect()
    };
    let (no, ni) = (outer.len(), inner.len());
    let mut k = pick(&outer, &outer);
    if ni > 0 {
        let k_ii = pick(&inner, &inner);
        let factored = Factored::of_real_parts(&k_ii, ni);
        if !factored.is_regular() {
            return Err("the flexures' inner nodes have a singular tangent stiffness".into());
        }
        let (k_io, k_oi) = (pick(&inner, &outer), pick(&outer, &inner));
        for c in 0..no {
            let column: Vec<D> = (0..ni).map(|r| k_io[r * no + c]).collect();
            let z = factored.solve_dual(&k_ii, &column);
            for r in 0..no {
                let row = &k_oi[r * ni..(r + 1) * ni];
                let sum = row
                    .iter()
                    .zip(&z)
                    .fold(D::from(0.0), |s, (&a, &b)| s + a * b);
                k[r * no + c] = k[r * no + c] - sum;
            }
        }
    }
    let symmetric = (0..no * no)
        .map(|i| (k[i] + k[(i % no) * no + i / no]) * 0.5)
        .collect();
    Ok(symmetric)
}

/// The `count` lowest frequencies (Hz; fewer where the family has fewer modes) of one
/// family: the condensed tangent `k` of the described part, with its image's where the
/// family is unfolded, the family's masses and holds, all where the bodies stand.
fn family_frequencies<D: Scalar>(
    built: &Built<D>,
    u: &[D],
    f: &Family<D>,
    k: &[D],
    count: usize,
) -> Result<Vec<D>, String> {
    let place = Placement::new(built, u, f);
    let n = place.source.len();
    if f.network.references.len() != n || f.inertia.len() != n {
        return Err("the linear model's bodies are not the structure's".into());
    }
    let masters = place.masters();
    let stiffness = place.unfold(f, k, &masters);
    let mass = place.mass(f, &masters);
    let basis = place.free_basis(f, &masters);
    let [a, b] = [&stiffness, &mass].map(|full| reduced(full, &basis));
    lowest(&a, &b, basis.len(), count).map_err(|why| {
        if f.anti.is_empty() {
            why
        } else {
            let axes: Vec<&str> = f.anti.iter().map(|a| a.name()).collect();
            format!(
                "{why}, in the modes antisymmetric about the {} axis",
                axes.join(" and ")
            )
        }
    })
}

/// `T^T A T` (row-major, `r x r`) of the row-major `A` on the columns `T`.
fn reduced<D: Scalar>(a: &[D], t: &[Vec<D>]) -> Vec<D> {
    let n = t.first().map_or(0, Vec::len);
    let at: Vec<Vec<D>> = t
        .iter()
        .map(|c| {
            (0..n)
                .map(|i| (0..n).fold(D::from(0.0), |s, j| s + a[i * n + j] * c[j]))
                .collect()
        })
        .collect();
    t.iter()
        .flat_map(|ci| {
            at.iter().map(move |acj| {
                ci.iter()
                    .zip(acj)
                    .fold(D::from(0.0), |s, (&x, &y)| s + x * y)
            })
        })
        .collect()
}

/// The `count` lowest frequencies (Hz) of `A q = w^2 B q` (row-major, `r x r`): the real
/// parts' eigenpairs, each `w^2` the Rayleigh quotient over the scalar at its eigenvector.
fn lowest<D: Scalar>(a: &[D], b: &[D], r: usize, count: usize) -> Result<Vec<D>, String> {
    let real = |m: &[D]| DMatrix::from_fn(r, r, |i, j| m[i * r + j].re());
    let pairs = eigenpairs(&real(a), &real(b))
        .map_err(|_| "a body has no mass or no inertia where it can move".to_string())?;
    let w2: Vec<f64> = pairs.iter().map(|p| p.0).collect();
    if let Some(&low) = w2.first().filter(|&&v| v < 0.0) {
        return Err(format!(
            "the tangent stiffness is not positive definite there (w^2 = {low:e}): the \
             structure is past a critical point"
        ));
    }
    let close = |i: usize, j: usize| {
        j < w2.len() && (w2[i] - w2[j]).abs() <= REPEATED * w2[i].abs().max(w2[j].abs())
    };
    let mut out = Vec::new();
    for (i, (_, q)) in pairs.iter().enumerate().take(count) {
        if close(i, i + 1) || (i > 0 && close(i - 1, i)) {
            return Err(format!(
                "the family's mode {} has a repeated natural frequency ({:e} Hz), whose \
                 derivative by the design is not defined",
                i + 1,
                w2[i].sqrt() / (2.0 * std::f64::consts::PI)
            ));
        }
        let q: Vec<f64> = q.iter().copied().collect();
        out.push(rayleigh(a, b, &q).sqrt() / (2.0 * std::f64::consts::PI));
    }
    Ok(out)
}
