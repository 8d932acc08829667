//! The `[refine]` section: whether and how `run` refines its analytic optimum against the
//! finite elements of the part (the algorithm is [`crate::refine`]).
//!
//! ```toml
//! [refine]
//! fidelity = "fe"                # or "none"; `run --refine fe|none` overrides it
//! idealization = "plane-strain"  # the FE that counts: "plane-strain" or "plane-stress"
//! stress = "peak"                # the FE stress that stands for `stress_max`: "peak" or "section"
//! tolerance = 1e-3               # relative change of the FE outputs that ends it
//! max_fe = 12                    # FE checks at most, per refined optimum
//! from = "optimum"               # or "zones": the best optimum of each zone
//! trust_radius = 0.05            # first step's bound, in design space scaled to the bounds
//! ```

use serde::{Deserialize, Serialize};

use super::reader::{k, Reader, Res};
use crate::fe::Idealization;
use crate::vocab::values::Number;

/// The `[refine]` section as written.
#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RawRefine {
    pub fidelity: Option<String>,
    pub idealization: Option<String>,
    pub stress: Option<String>,
    pub tolerance: Option<Number>,
    pub max_fe: Option<i64>,
    pub from: Option<String>,
    pub trust_radius: Option<Number>,
}

/// Which FE stress stands for the analytic `stress_max`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StressMeasure {
    /// The largest von Mises stress: the part's real peak, at a fillet (it does not converge
    /// at sharp roots).
    Peak,
    /// The beam stress from the section resultants at the hinges' roots: what the analytic
    /// model computes.
    Section,
}

/// Where refinements start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RefineFrom {
    /// The study's reported optimum.
    Optimum,
    /// The best optimum of each zone that has one.
    Zones,
}

/// A validated `[refine]` section.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RefineSettings {
    /// `run` refines (`fidelity = "fe"`).
    pub enabled: bool,
    pub idealization: Idealization,
    pub stress: StressMeasure,
    pub tolerance: f64,
    pub max_fe: usize,
    pub from: RefineFrom,
    pub trust_radius: f64,
}

impl Default for RefineSettings {
    fn default() -> Self {
        RefineSettings {
            enabled: false,
            idealization: Idealization::PlaneStrain,
            stress: StressMeasure::Peak,
            tolerance: 1e-3,
            max_fe: 12,
            from: RefineFrom::Optimum,
            trust_radius: 0.05,
        }
    }
}

/// The range of `refine.tolerance`: below 1e-6 the FE's own error (about 1e-5 on the
/// default meshes) decides; above 0.05 it stops before correcting anything.
pub const REFINE_TOLERANCE_RANGE: (f64, f64) = (1e-6, 0.05);

/// Reads `[refine]` (absent: refinement off, defaults for the rest).
pub(crate) fn settings(r: &Reader, raw: Option<&RawRefine>) -> Res<RefineSettings> {
    let mut s = RefineSettings::default();
    let Some(raw) = raw else {
        return Ok(s);
    };
    let path = |key: &str| [k("refine"), k(key)];
    let choice = |key: &str, v: &str, expected: &[&str]| {
        r.err(
            &path(key),
            format!(
                "unknown {key} \"{v}\"; expected {}",
                expected
                    .iter()
                    .map(|e| format!("\"{e}\""))
                    .collect::<Vec<_>>()
                    .join(" or ")
            ),
        )
    };
    s.enabled = match raw.fidelity.as_deref() {
        Some("fe") => true,
        Some("none") => false,
        Some(o) => return Err(choice("fidelity", o, &["fe", "none"])),
        None => {
            return Err(r.err(
                &path("fidelity"),
                "missing: say what the optimum is refined against, \"fe\" (or \"none\")",
            ))
        }
    };
    if let Some(v) = raw.idealization.as_deref() {
        s.idealization = match v {
            "plane-strain" => Idealization::PlaneStrain,
            "plane-stress" => Idealization::PlaneStress,
            o => return Err(choice("idealization", o, &["plane-strain", "plane-stress"])),
        };
    }
    if let Some(v) = raw.stress.as_deref() {
        s.stress = match v {
            "peak" => StressMeasure::Peak,
            "section" => StressMeasure::Section,
            o => return Err(choice("stress", o, &["peak", "section"])),
        };
    }
    if let Some(v) = raw.from.as_deref() {
        s.from = match v {
            "optimum" => RefineFrom::Optimum,
            "zones" => RefineFrom::Zones,
            o => return Err(choice("from", o, &["optimum", "zones"])),
        };
    }
    if let Some(n) = raw.tolerance {
        let t = r.finite(&path("tolerance"), n)?;
        let (lo, hi) = REFINE_TOLERANCE_RANGE;
        if !(lo..=hi).contains(&t) {
            return Err(r.err(
                &path("tolerance"),
                format!("must lie between {lo:e} and {hi}, got {t:e}"),
            ));
        }
        s.tolerance = t;
    }
    if let Some(n) = raw.max_fe {
        if !(2..=200).contains(&n) {
            return Err(r.err(
                &path("max_fe"),
                format!("must lie between 2 and 200 FE checks, got {n}"),
            ));
        }
        s.max_fe = n as usize;
    }
    if let Some(n) = raw.trust_radius {
        let t = r.finite(&path("trust_radius"), n)?;
        if !(t > 0.0 && t <= 1.0) {
            return Err(r.err(
                &path("trust_radius"),
                format!("must lie in (0, 1], a fraction of each variable's range, got {t}"),
            ));
        }
        s.trust_radius = t;
    }
    Ok(s)
}
