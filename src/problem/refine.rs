//! The `[refine]` section: whether and how `run` refines its analytic optimum against the
//! finite elements of the part (the algorithm is [`crate::refine`]).
//!
//! ```toml
//! [refine]
//! fidelity = "fe"                # or "none"; `run --refine fe|none` overrides it
//! idealization = "3d"            # the FE that counts: "3d", "plane-strain" or "plane-stress"
//!                                # (absent: by the plate's width over its thinnest hinge,
//!                                # `fe::Fidelity::for_plate`)
//! stress = "peak"                # the FE stress that stands for `stress_max`: "peak" or "section"
//! tolerance = 1e-3               # relative change of the FE outputs that ends it
//! max_fe = 12                    # FE checks at most, per refined optimum
//! from = "optimum"               # or "zones": the best optimum of each zone
//! trust_radius = 0.05            # first step's bound, in design space scaled to the bounds
//! ```

use serde::{Deserialize, Serialize};

use super::reader::{k, Reader, Res};
use crate::fe::Fidelity;
use crate::vocab::values::{Choices, Number};

/// The `[refine]` section as written.
#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RawRefine {
    /// Required: a `[refine]` says what the optimum is refined against.
    #[schemars(required, extend("enum" = FIDELITIES.names()))]
    pub fidelity: Option<String>,
    #[schemars(extend("enum" = IDEALIZATIONS.names()))]
    pub idealization: Option<String>,
    #[schemars(extend("enum" = STRESSES.names()))]
    pub stress: Option<String>,
    #[schemars(extend(
        "minimum" = REFINE_TOLERANCE_RANGE.0,
        "maximum" = REFINE_TOLERANCE_RANGE.1
    ))]
    pub tolerance: Option<Number>,
    #[schemars(extend("minimum" = MAX_FE.0, "maximum" = MAX_FE.1))]
    pub max_fe: Option<i64>,
    #[schemars(extend("enum" = FROMS.names()))]
    pub from: Option<String>,
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 1))]
    pub trust_radius: Option<Number>,
}

/// `fidelity`, and `run --refine`: refined against the FE (`true`) or not.
pub const FIDELITIES: Choices<bool> = Choices(&[("fe", true), ("none", false)]);
pub const IDEALIZATIONS: Choices<Fidelity> = Choices(&[
    ("3d", Fidelity::Solid),
    ("plane-strain", Fidelity::PlaneStrain),
    ("plane-stress", Fidelity::PlaneStress),
]);
pub const STRESSES: Choices<StressMeasure> = Choices(&[
    ("peak", StressMeasure::Peak),
    ("section", StressMeasure::Section),
]);
pub const FROMS: Choices<RefineFrom> = Choices(&[
    ("optimum", RefineFrom::Optimum),
    ("zones", RefineFrom::Zones),
]);
/// The range of `max_fe`.
pub const MAX_FE: (i64, i64) = (2, 200);

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
    /// The FE that counts; `None`: by the plate's width over its thinnest hinge at each
    /// design ([`Fidelity::for_plate`]).
    pub idealization: Option<Fidelity>,
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
            idealization: None,
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
    s.enabled = match &raw.fidelity {
        Some(name) => r.choice(&path("fidelity"), name, &FIDELITIES)?,
        None => {
            return Err(r.err(
                &path("fidelity"),
                "missing: say what the optimum is refined against, \"fe\" (or \"none\")",
            ))
        }
    };
    if let Some(v) = &raw.idealization {
        s.idealization = Some(r.choice(&path("idealization"), v, &IDEALIZATIONS)?);
    }
    if let Some(v) = &raw.stress {
        s.stress = r.choice(&path("stress"), v, &STRESSES)?;
    }
    if let Some(v) = &raw.from {
        s.from = r.choice(&path("from"), v, &FROMS)?;
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
        let (lo, hi) = MAX_FE;
        if !(lo..=hi).contains(&n) {
            return Err(r.err(
                &path("max_fe"),
                format!("must lie between {lo} and {hi} FE checks, got {n}"),
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
