//! The part: the closed outline of a monolithic mechanism, built from the solids a model
//! describes, checked for what a wire-EDM shop cannot make, and exported.
//!
//! A model gives a [`PartSpec`] (SI, metres): convex solids (hinges, links, blocks), the
//! hinges' sites (where their thin sections start and end, for the fillets and the checks),
//! groups of solids that form separate arms, named faces for load cases, the finite-element
//! check stated on them ([`analysis`]), and annotations for the drawing. [`Part::build`]
//! joins the solids (georust `geo`'s Boolean union), restores the exact coordinates the
//! union snapped to its integer grid, rounds every hinge root with its fillet (an arc, kept
//! as an arc in every export), orders the loops and runs the checks.
//! A [`Part`] is in SI (metres), as its spec and the finite elements that read it: only the
//! writers turn it into millimetres, the unit of the exported files ([`Part::in_mm`]), so no
//! coordinate makes a round trip through another unit.
//!
//! Files: `analysis.rs` (the check a model asks of its part), `outline.rs` (union, exact
//! coordinates, fillets, loops), `checks.rs` (what cannot be made, on the solids),
//! `widths.rs` (bodies thinner than their hinges, on the outline), `mm.rs` (the part as
//! its files hold it), `dxf.rs`, `svg.rs`, `step.rs` (the writers).

pub mod analysis;
pub mod checks;
pub mod dxf;
pub mod half;
pub mod mm;
pub mod outline;
mod roots;
pub mod step;
pub mod svg;
mod widths;

use serde::Serialize;

pub use mm::PartMm;
pub use outline::{Loop, Vertex};

/// The convex hull of `points` (counterclockwise, each corner once): a solid around points
/// a model places.
pub fn convex_hull(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    use geo::{ConvexHull, MultiPoint, Point};
    let mp: MultiPoint<f64> = points.iter().map(|p| Point::new(p[0], p[1])).collect();
    let h = mp.convex_hull();
    let mut out: Vec<[f64; 2]> = h.exterior().0.iter().map(|c| [c.x, c.y]).collect();
    out.pop();
    out
}

/// A convex solid of the part, counterclockwise, in metres.
#[derive(Debug, Clone, PartialEq)]
pub struct Solid {
    pub name: String,
    pub points: Vec<[f64; 2]>,
}

/// A hinge: its centre line from `start` to `end` (the model's hinge), its least and root
/// thicknesses, its outline above the centre line in its own frame (`profile`: `(x, y,
/// bulge)` from `(0, root/2)` to `(length, root/2)`, metres; the kind's
/// [`crate::model::hinge::HingeKind::outline`]), and the part's fillet radius at its four
/// roots (a strip's; the solid of the hinge then runs `fillet` beyond both ends, where the
/// rigid bodies' faces are).
#[derive(Debug, Clone, PartialEq)]
pub struct HingeSite {
    pub name: String,
    pub start: [f64; 2],
    pub end: [f64; 2],
    pub thickness: f64,
    pub root: f64,
    pub fillet: f64,
    pub kind: &'static str,
    pub profile: Vec<[f64; 3]>,
    /// The index of the hinge's own solid among [`PartSpec::solids`].
    pub solid: usize,
}

/// A named straight face (a load case's surface), in metres.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Face {
    pub name: String,
    pub a: [f64; 2],
    pub b: [f64; 2],
}

/// A dimension for the drawing, in metres.
#[derive(Debug, Clone, PartialEq)]
pub enum Annotation {
    /// The distance from `a` to `b`, drawn offset by `offset` to the left of a->b.
    Length {
        a: [f64; 2],
        b: [f64; 2],
        offset: f64,
        label: String,
    },
    /// A label at `label_at` with a leader to the point `at` (thicknesses, angles).
    Note {
        at: [f64; 2],
        label_at: [f64; 2],
        label: String,
    },
}

/// The actuator's place: a rectangle `length` by `height` centred at the origin, along x
/// (its height unchecked when not given).
#[derive(Debug, Clone, PartialEq)]
pub struct Actuator {
    pub length: f64,
    pub height: Option<f64>,
}

/// How a model drives its part, for an analysis of it (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Actuation {
    /// The actuator's nominal stroke (m) and preload (N): the largest force on the part is
    /// [`Actuation::largest_force`] at the stiffness its analysis's actuation case names
    /// ([`analysis::ActuationCase`]).
    pub nominal_stroke: f64,
    pub preload: f64,
    /// The actuator's stiffness (N/m); `None` for one much stiffer than the part.
    pub stiffness: Option<f64>,
    /// The mass the output face carries (kg).
    pub payload_mass: f64,
    /// The stack's own mass (kg; 0 where the file gives none), carried on the faces it
    /// pushes by [`stack_mass_share`].
    pub stack_mass: f64,
}

impl Actuation {
    /// The largest force on the part whose input stiffness is `k`: the stroke the actuator
    /// makes against it (paper 004, Eq. 13: `X_nl k_a / (k + k_a)`, the nominal stroke for
    /// a rigid actuator) times `k`, plus the preload. The models state the same force.
    pub fn largest_force(&self, k: f64) -> f64 {
        let stroke = match self.stiffness {
            None => self.nominal_stroke,
            Some(k_a) => self.nominal_stroke * k_a / (k + k_a),
        };
        stroke * k + self.preload
    }
}

/// The share of a stack's mass `m` that a face it pushes carries in a natural mode, along
/// the stack's axis and across it: `(along, across)`. The stack is a uniform rod whose
/// velocity varies linearly from one end to the other, as its own axial mode lies far above
/// the part's (Rayleigh's method, as for a spring's effective mass `m/3`: Thomson and Dahleh,
/// "Theory of Vibration with Applications", 5th ed., 1998, Sec. 2.4): its kinetic energy is
/// `m/6 (v1^2 + v1.v2 + v2^2)` for end velocities `v1`, `v2`, exactly for that field.
///
/// - `mirrored == false`: the far end stands on the ground, so the face carries `m/3`
///   whether the stack stretches or turns about its foot.
/// - `mirrored == true`: the stack runs from the face to its mirror image, and the face
///   carries the half it holds. In a mode symmetric about the mirror (`stretched`) the
///   stack's middle stays put along its axis, so the face carries `m/6` along it, and the
///   whole half `m/2` across it (both ends move alike). In an antisymmetric mode the roles
///   swap: `m/2` along the axis (it translates), `m/6` across (it turns about its middle).
pub fn stack_mass_share(m: f64, mirrored: bool, stretched: bool) -> (f64, f64) {
    match (mirrored, stretched) {
        (false, _) => (m / 3.0, m / 3.0),
        (true, true) => (m / 6.0, m / 2.0),
        (true, false) => (m / 2.0, m / 6.0),
    }
}

/// What a model gives to build its part.
#[derive(Debug, Clone, PartialEq)]
pub struct PartSpec {
    /// The plate's width, through which the outline is cut (m): the out-of-plane size of an
    /// analysis.
    pub width: f64,
    pub actuation: Option<Actuation>,
    /// The finite-element check the model asks of the part; `None` for a part that is only
    /// drawn.
    pub analysis: Option<analysis::Analysis>,
    /// Convex solids, counterclockwise (metres).
    pub solids: Vec<Solid>,
    /// The pairs of solids (indices) that are joined; every other pair keeps `min_slot`
    /// apart.
    pub joints: Vec<(usize, usize)>,
    pub hinges: Vec<HingeSite>,
    pub faces: Vec<Face>,
    pub annotations: Vec<Annotation>,
    /// A line for the drawing's title: the sizes the annotations do not show.
    pub caption: String,
    /// The narrowest slot the wire can cut (m).
    pub min_slot: f64,
    pub actuator: Option<Actuator>,
    /// What the part can be made with but a designer should know.
    pub warnings: Vec<String>,
}

/// A hinge of a [`Part`] (metres), as [`HingeSite`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Hinge {
    pub name: String,
    pub kind: &'static str,
    pub start: [f64; 2],
    pub end: [f64; 2],
    /// The least thickness.
    pub thickness: f64,
    /// The thickness at its ends.
    pub root: f64,
    pub fillet: f64,
    /// The outline above the centre line in the hinge's own frame: `(x, y, bulge)`.
    pub profile: Vec<[f64; 3]>,
}

/// A part: its outline loops and faces in metres.
#[derive(Debug, Clone)]
pub struct Part {
    /// The plate's width (m).
    pub width: f64,
    /// The outer loop first (counterclockwise), then the inner ones (clockwise), each
    /// starting at its lowest, then leftmost vertex.
    pub loops: Vec<Loop>,
    pub faces: Vec<Face>,
    /// The hinges' thin sections: their centre lines, thicknesses and fillets.
    pub hinges: Vec<Hinge>,
    /// Area of the outline (m^2), arcs included.
    pub area: f64,
    /// Bounding box `[x_min, y_min, x_max, y_max]` (m), arcs included.
    pub bounding_box: [f64; 4],
    pub warnings: Vec<String>,
    pub annotations: Vec<Annotation>,
    pub caption: String,
}

/// Why a design gives no part that can be made.
#[derive(Debug, Clone, PartialEq)]
pub struct PartError {
    /// Every problem found, each naming what collides with what.
    pub problems: Vec<String>,
}

/// How many problems a message lists; the rest are counted.
const SHOWN: usize = 6;

impl std::fmt::Display for PartError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let shown = self.problems.len().min(SHOWN);
        write!(f, "{}", self.problems[..shown].join("; "))?;
        if self.problems.len() > shown {
            write!(f, "; and {} more", self.problems.len() - shown)?;
        }
        Ok(())
    }
}

impl std::error::Error for PartError {}

/// Millimetres per metre: the part's files are in mm, its spec and the part in metres.
pub const MM: f64 = 1e3;

impl Part {
    /// Joins, rounds and checks the solids of `spec`.
    pub fn build(spec: &PartSpec) -> Result<Part, PartError> {
        let problems = checks::before_union(spec);
        if !problems.is_empty() {
            return Err(PartError { problems });
        }
        let loops = outline::outline(spec).map_err(|problems| PartError { problems })?;
        let problems = widths::too_thin(spec, &loops);
        if !problems.is_empty() {
            return Err(PartError { problems });
        }
        let area = loops.iter().map(Loop::signed_area).sum();
        let bounding_box = loops.iter().map(Loop::bounding_box).fold(
            [
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ],
            |a, b| {
                [
                    a[0].min(b[0]),
                    a[1].min(b[1]),
                    a[2].max(b[2]),
                    a[3].max(b[3]),
                ]
            },
        );
        Ok(Part {
            width: spec.width,
            loops,
            faces: spec.faces.clone(),
            hinges: spec
                .hinges
                .iter()
                .map(|h| Hinge {
                    name: h.name.clone(),
                    kind: h.kind,
                    start: h.start,
                    end: h.end,
                    thickness: h.thickness,
                    root: h.root,
                    fillet: h.fillet,
                    profile: h.profile.clone(),
                })
                .collect(),
            area,
            bounding_box,
            warnings: spec.warnings.clone(),
            annotations: spec.annotations.clone(),
            caption: spec.caption.clone(),
        })
    }
}
