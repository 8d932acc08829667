//! One hinge on its own: what `flexopt hinge` prints, the calculator designers otherwise
//! keep in a spreadsheet.

use indexmap::IndexMap;
use serde::Serialize;

use super::{Compliance, HingeKind, HingeLoads};
use crate::model::fit::{check_all, FitCheck};
use crate::model::material::Material;

/// The stiffnesses, inverses of the compliances.
#[derive(Debug, Clone, Serialize)]
pub struct Stiffness {
    /// Axial (N/m).
    pub k11: f64,
    /// Transverse, the free end's deflection per force with its slope free (N/m).
    pub k22: f64,
    /// Rotational, moment per slope with the free end's deflection free (N m/rad).
    pub k33: f64,
}

/// `flexopt hinge`'s report; SI unless a key says otherwise.
#[derive(Debug, Clone, Serialize)]
pub struct HingeReport {
    pub kind: HingeKind,
    pub dimensions_mm: IndexMap<String, f64>,
    pub width_mm: f64,
    pub material: Material,
    pub length_mm: f64,
    pub least_thickness_mm: f64,
    pub root_thickness_mm: f64,
    /// The closed forms (paper 004 Eq. 2 for the strip, the exact integrals of
    /// [`super::integrals`] for the notches).
    pub compliance: Compliance<f64>,
    /// The same by numerical integration of the thickness profile, the check.
    pub compliance_numerical: Compliance<f64>,
    pub stiffness: Stiffness,
    /// Slope per moment, c33 (rad/(N m)), and in the designer's units (mrad per N mm).
    pub rotation_per_moment: f64,
    pub rotation_per_moment_mrad_per_n_mm: f64,
    /// The stress limit (Pa) and where it came from.
    pub stress_limit: f64,
    pub stress_limit_from: String,
    /// The notch's stress concentration in bending, `K_t` (1 for the strip; see
    /// [`HingeKind::stress_concentration`]).
    pub stress_concentration: f64,
    /// The moment and the rotation under pure bending at which the largest surface
    /// stress, `K_t 6 M / (w t^2)` at the thinnest section, reaches the limit.
    pub max_moment: f64,
    pub max_rotation: f64,
    pub max_rotation_deg: f64,
    /// The ratios of the kind's ranges of fit ([`HingeKind::fit`]) at these dimensions,
    /// each against its range: outside one, the figures above are not to be trusted.
    pub fit_ranges: Vec<FitCheck>,
}

/// The report of one hinge (dimensions in SI, in the kind's order).
pub fn report(
    kind: HingeKind,
    dims: &[f64],
    width: f64,
    material: &Material,
    stress_limit: f64,
    stress_limit_from: String,
) -> HingeReport {
    let c = kind.compliance(dims, width, material);
    let t = kind.least_thickness(dims);
    let unit_moment = HingeLoads {
        axial: 0.0,
        shear: 0.0,
        moment: 1.0,
    };
    let max_moment = stress_limit / kind.max_stress(dims, width, &unit_moment);
    let max_rotation = c.c33 * max_moment;
    HingeReport {
        kind,
        dimensions_mm: kind
            .dimensions()
            .iter()
            .zip(dims)
            .map(|(d, &v)| (d.stem.to_string(), v * 1e3))
            .collect(),
        width_mm: width * 1e3,
        material: material.clone(),
        length_mm: kind.length(dims) * 1e3,
        least_thickness_mm: t * 1e3,
        root_thickness_mm: kind.root_thickness(dims) * 1e3,
        compliance: c,
        compliance_numerical: kind.compliance_numerical(dims, width, material),
        stiffness: Stiffness {
            k11: 1.0 / c.c11,
            k22: 1.0 / c.c22,
            k33: 1.0 / c.c33,
        },
        rotation_per_moment: c.c33,
        rotation_per_moment_mrad_per_n_mm: c.c33 * 1e3 * 1e-3,
        stress_limit,
        stress_limit_from,
        stress_concentration: kind.stress_concentration(dims),
        max_moment,
        max_rotation,
        max_rotation_deg: max_rotation.to_degrees(),
        fit_ranges: {
            let stems: Vec<&str> = kind.dimensions().iter().map(|d| d.stem).collect();
            let index: Vec<usize> = (0..stems.len()).collect();
            let owner = format!("the {} hinge", kind.name());
            check_all(&kind.fit_limits(&owner, &index, &stems), dims)
        },
    }
}

/// The report of the hinge `flexopt hinge` describes: its kind by name, the dimension flags
/// given by stem (`("r", 1.0)`; mm), width (mm), material preset and stress limit (MPa;
/// default a third of the ultimate strength); or the message naming the option at fault.
pub fn from_options(
    kind: &str,
    given: &[(&str, f64)],
    width: f64,
    material: &str,
    stress_limit: Option<f64>,
) -> Result<HingeReport, String> {
    let bad = |key: &str, m: String| format!("key `--{key}`: {m}");
    let kind = HingeKind::from_name(kind).ok_or_else(|| {
        bad(
            "kind",
            format!(
                "unknown hinge kind \"{kind}\"; expected one of {}",
                HingeKind::NAMES.join(", ")
            ),
        )
    })?;
    let stems: Vec<&str> = kind.dimensions().iter().map(|d| d.stem).collect();
    let dashed = stems
        .iter()
        .map(|s| format!("--{s}"))
        .collect::<Vec<_>>()
        .join(", ");
    if let Some((k, _)) = given.iter().find(|(k, _)| !stems.contains(k)) {
        return Err(bad(
            k,
            format!(
                "a {} hinge has no such dimension; it takes {dashed}",
                kind.name()
            ),
        ));
    }
    let positive_mm = |v: f64| v.is_finite() && v > 0.0 && v < 1e6;
    let mut dims = Vec::new();
    for stem in &stems {
        match given.iter().find(|(k, _)| k == stem).map(|(_, v)| *v) {
            Some(v) if positive_mm(v) => dims.push(v * 1e-3),
            Some(v) => {
                return Err(bad(
                    stem,
                    format!("must be a positive length in mm, got {v}"),
                ))
            }
            None => {
                return Err(bad(
                    stem,
                    format!("missing: a {} hinge takes {dashed}", kind.name()),
                ))
            }
        }
    }
    if !positive_mm(width) {
        return Err(bad(
            "width",
            format!("must be a positive length in mm, got {width}"),
        ));
    }
    let names: Vec<String> = stems.iter().map(|s| format!("--{s}")).collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    if let Some(why) = kind.domain_error(&dims, &names) {
        return Err(format!("not a hinge: {why}"));
    }
    let material = Material::preset(material).ok_or_else(|| {
        bad(
            "material",
            format!(
                "unknown material \"{material}\"; expected one of {}",
                Material::PRESETS.join(", ")
            ),
        )
    })?;
    let (limit, from) = match (stress_limit, material.ultimate_strength) {
        (Some(s), _) if s.is_finite() && s > 0.0 => (s * 1e6, "--stress-limit".to_string()),
        (Some(s), _) => {
            return Err(bad(
                "stress-limit",
                format!("must be a positive stress in MPa, got {s}"),
            ))
        }
        (None, Some(u)) => (
            u / 3.0,
            format!("a third of {}'s ultimate strength", material.name),
        ),
        (None, None) => {
            return Err(bad(
                "stress-limit",
                format!(
                    "missing: {} has no ultimate strength to take a third of",
                    material.name
                ),
            ))
        }
    };
    Ok(report(kind, &dims, width * 1e-3, &material, limit, from))
}
