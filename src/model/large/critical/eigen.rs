//! The lowest eigenvalue of the tangent stiffness on the free degrees of freedom, under a
//! symmetric scaling to a unit diagonal, and its eigenvector: the test of definiteness the
//! critical load factor's search makes at each point ([`super::critical_load_factor`]).

use faer::{Mat, Side};

use crate::model::large::assemble::System;
use crate::model::large::solve::State;
use crate::model::large::LargeError;

/// The symmetric scaling `1 / sqrt(|K_ii|)` of the unloaded tangent's diagonal, under which
/// the lowest eigenvalue is looked for ([`lowest`]).
pub(super) fn scaling(system: &System) -> Result<Vec<f64>, LargeError> {
    let unloaded = system.at(&system.unloaded()).tangent;
    let scale: Vec<f64> = (0..unloaded.nrows())
        .map(|i| 1.0 / unloaded[(i, i)].abs().sqrt())
        .collect();
    if scale.iter().any(|s| !s.is_finite()) {
        return Err(LargeError::Singular { lambda: 0.0 });
    }
    Ok(scale)
}

/// The lowest eigenvalue of the tangent `k` on the free degrees of freedom, scaled
/// symmetrically by `scale` (a congruence: the signs of the eigenvalues are kept, by
/// Sylvester's law of inertia, while a strip's axial and bending stiffnesses, 1e9 apart,
/// are brought together so that an eigenvalue near zero is not lost in the round-off of
/// the largest), and its eigenvector carried back, `phi = S psi`: at a zero eigenvalue
/// `S K S psi = 0`, so `K phi = 0`, the null vector of the tangent itself.
pub(super) fn lowest_pair(k: &Mat<f64>, scale: &[f64]) -> Result<(f64, Vec<f64>), LargeError> {
    let n = scale.len();
    if n == 0 {
        return Err(LargeError::Invalid("no free degree of freedom".into()));
    }
    let scaled = Mat::from_fn(n, n, |i, j| scale[i] * k[(i, j)] * scale[j]);
    let eigen = scaled
        .self_adjoint_eigen(Side::Lower)
        .map_err(|_| LargeError::Eigen)?;
    let psi: Vec<f64> = (0..n).map(|i| eigen.U()[(i, 0)]).collect();
    // the eigenvalue as the unit eigenvector's Rayleigh quotient
    let value: f64 = (0..n)
        .map(|i| psi[i] * (0..n).map(|j| scaled[(i, j)] * psi[j]).sum::<f64>())
        .sum();
    let phi: Vec<f64> = (0..n).map(|i| scale[i] * psi[i]).collect();
    if !value.is_finite() || phi.iter().any(|v| !v.is_finite()) {
        return Err(LargeError::Eigen);
    }
    Ok((value, phi))
}

/// The lowest eigenvalue of the scaled tangent at `state` ([`lowest_pair`]).
pub(super) fn lowest(system: &System, state: &State, scale: &[f64]) -> Result<f64, LargeError> {
    let a = system.at(state);
    if a.tangent.nrows() == 0 {
        return Err(LargeError::Invalid("no free degree of freedom".into()));
    }
    let scaled = Mat::from_fn(scale.len(), scale.len(), |i, j| {
        scale[i] * a.tangent[(i, j)] * scale[j]
    });
    let values = scaled
        .self_adjoint_eigenvalues(Side::Lower)
        .map_err(|_| LargeError::Eigen)?;
    values
        .first()
        .copied()
        .filter(|v| v.is_finite())
        .ok_or(LargeError::Eigen)
}

/// The Illinois update of a bracket's values after a trial of value `fc` (Dowell and
/// Jarratt 1971): the trial takes the stable end's place (`fa`, where the value is positive)
/// or the other's (`fb`), and where the same end moves twice running the other end's value
/// is halved. True where the trial is the new stable end. `side` is the last end moved (-1
/// the stable one, 1 the other, 0 none yet).
pub(super) fn illinois_keeps(fc: f64, fa: &mut f64, fb: &mut f64, side: &mut i8) -> bool {
    if fc > 0.0 {
        *fa = fc;
        if *side == -1 {
            *fb *= 0.5;
        }
        *side = -1;
        true
    } else {
        *fb = fc;
        if *side == 1 {
            *fa *= 0.5;
        }
        *side = 1;
        false
    }
}
