//! The finite element behind one interface, [`Element`], and what every element shares:
//! the material ([`Elastic`], its `D` matrix and von Mises stress) and the 2D idealization.
//!
//! The six-node triangle ([`Tri6`], in `tri6.rs`) is the one element today. Assembly
//! ([`super::assembly`]), stresses ([`super::stress`]), edge loads ([`super::loads`]), the
//! CalculiX decks ([`super::calculix`]) and the mesh's own operations are generic over
//! [`Element`], monomorphized, so that they compute what the element's own code would,
//! to the bit. Only mesh generation and refinement know the triangle: they are the
//! triangle's mesher ([`super::mesh::Mesher`], in `mesh/triangles.rs`), since a mesher
//! is bound to its element's shape.
//!
//! A second 2D element (a nine-node quadrilateral, say) is therefore one file here
//! implementing [`Element`], one mesher implementing [`super::mesh::Mesher`], and the
//! choice of it, [`PartElement`]: the element a [`super::mesh::Mesh`] holds when none is
//! named, as in the part's checks ([`super::verify`], [`super::hinge`]) and the stress
//! plot. Its node order must be CalculiX's for its 2D element, so that the decks write the
//! connectivity as it is.

use std::fmt::Debug;
use std::ops::{Index, IndexMut};

mod tri6;

pub use tri6::Tri6;

/// The element of the part's checks and of a hinge's: what a mesh, its edges and a deck
/// hold when no element is named ([`super::mesh::Mesh`]'s default). Choosing another
/// element is this line.
pub type PartElement = Tri6;

/// What an element's arrays hold: plain values, so that the arrays copy and compare as the
/// fixed-size arrays they are.
pub trait Item: Copy + Debug + PartialEq {}

impl<T: Copy + Debug + PartialEq> Item for T {}

/// An array of one of an element's sizes (its nodes, its degrees of freedom, an edge's
/// nodes): generic code indexes what an element returns, on the stack as today's arrays.
pub trait Array<T: Item>:
    Copy + Debug + PartialEq + Index<usize, Output = T> + IndexMut<usize> + AsRef<[T]>
{
    fn from_fn(f: impl FnMut(usize) -> T) -> Self;
}

impl<T: Item, const N: usize> Array<T> for [T; N] {
    fn from_fn(f: impl FnMut(usize) -> T) -> Self {
        std::array::from_fn(f)
    }
}

/// A 2D isoparametric element of plane elasticity: two degrees of freedom a node,
/// `(u0, v0, u1, v1, ...)`. The element is a type without values; its methods take the
/// coordinates of its nodes (`x`, in node order) so that a mesh stores only numbers; its
/// bounds let the mesh, its edges and the decks derive theirs.
pub trait Element: Copy + Debug + PartialEq + 'static {
    /// Nodes of one element.
    const NODES: usize;
    /// Nodes of one edge on the outline, in order along it (ends first and last).
    const EDGE_NODES: usize;
    /// `[T; NODES]`.
    type PerNode<T: Item>: Array<T>;
    /// `[T; 2 * NODES]`.
    type PerDof<T: Item>: Array<T>;
    /// `[T; EDGE_NODES]`.
    type PerEdge<T: Item>: Array<T>;
    /// A point of the reference element (area coordinates for a triangle).
    type Reference: Item;
    /// The reference element's area: quadrature weights sum to one, times this.
    const REFERENCE_AREA: f64;
    /// The reference element's centre.
    const CENTRE: Self::Reference;
    /// The element's sides as pairs of its corner nodes, counterclockwise: the interior
    /// lies left of each.
    const SIDES: &'static [(usize, usize)];
    /// CalculiX's element for the mesh extruded through the width.
    const CALCULIX_EXTRUDED: &'static str;
    /// The extruded element's nodes: `(plane, node)` with plane 0, 1, 2 the bottom, middle
    /// and top of a layer; a node on the middle plane appears on every plane.
    const EXTRUSION: &'static [(usize, usize)];
    /// The extruded element's face (its ccx load label `P<n>`) standing on each side.
    const EXTRUDED_FACES: &'static [usize];

    /// The reference coordinates of the nodes.
    fn node_coordinates() -> Self::PerNode<Self::Reference>;
    /// The integration rule: points and weights (summing to one).
    fn quadrature() -> &'static [(Self::Reference, f64)];
    /// The shape functions at `l`.
    fn shape(l: Self::Reference) -> Self::PerNode<f64>;
    /// The shape functions' derivatives with respect to x and y at `l`, and the Jacobian's
    /// determinant; `None` where the element is inverted.
    fn gradients(
        x: &Self::PerNode<[f64; 2]>,
        l: Self::Reference,
    ) -> Option<([Self::PerNode<f64>; 2], f64)>;
    /// The stiffness matrix for the constitutive matrix `d` and the out-of-plane width;
    /// `None` for an inverted element.
    fn stiffness(
        x: &Self::PerNode<[f64; 2]>,
        d: &[[f64; 3]; 3],
        width: f64,
    ) -> Option<Self::PerDof<Self::PerDof<f64>>>;
    /// The consistent mass matrix per direction (the same for u and v).
    fn mass(
        x: &Self::PerNode<[f64; 2]>,
        rho: f64,
        width: f64,
    ) -> Option<Self::PerNode<Self::PerNode<f64>>>;
    /// The stresses `(xx, yy, xy)` at `l` for nodal displacements `u`.
    fn stress(
        x: &Self::PerNode<[f64; 2]>,
        d: &[[f64; 3]; 3],
        u: &Self::PerDof<f64>,
        l: Self::Reference,
    ) -> [f64; 3];
    /// The reference coordinates of the physical point `p`; `None` if not found.
    fn locate(x: &Self::PerNode<[f64; 2]>, p: [f64; 2]) -> Option<Self::Reference>;
    /// Whether `l` lies in the reference element (within `tol`).
    fn contains(l: Self::Reference, tol: f64) -> bool;
    /// The node order of the mirror image of an element, counterclockwise again: its node
    /// `k` is the image of node `mirror_order()[k]`.
    fn mirror_order() -> Self::PerNode<usize>;
    /// The edge's shape functions at `s` in [0, 1] and their derivatives.
    fn edge_shape(s: f64) -> (Self::PerEdge<f64>, Self::PerEdge<f64>);
    /// The rule for integrals along an edge: points in [0, 1] and weights summing to one.
    fn edge_quadrature() -> &'static [(f64, f64)];
    /// CalculiX's 2D element in plane stress or plane strain.
    fn calculix_name(idealization: Idealization) -> &'static str;

    /// The point at `l`.
    fn point(x: &Self::PerNode<[f64; 2]>, l: Self::Reference) -> [f64; 2] {
        let n = Self::shape(l);
        let mut p = [0.0; 2];
        for (ni, xi) in n.as_ref().iter().zip(x.as_ref()) {
            p[0] += ni * xi[0];
            p[1] += ni * xi[1];
        }
        p
    }

    /// The area (curved edges included).
    fn area(x: &Self::PerNode<[f64; 2]>) -> f64 {
        Self::quadrature()
            .iter()
            .map(|&(l, w)| {
                Self::gradients(x, l).map_or(0.0, |(_, det)| w * Self::REFERENCE_AREA * det)
            })
            .sum()
    }

    /// The stresses at the nodes, each from this element alone.
    fn nodal_stresses(
        x: &Self::PerNode<[f64; 2]>,
        d: &[[f64; 3]; 3],
        u: &Self::PerDof<f64>,
    ) -> Self::PerNode<[f64; 3]> {
        let l = Self::node_coordinates();
        Self::PerNode::from_fn(|k| Self::stress(x, d, u, l[k]))
    }
}

/// The 2D idealizations of a plate of width `w` loaded in its plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Idealization {
    /// No stress through the width: a thin plate.
    PlaneStress,
    /// No strain through the width: a wide one (a hinge 25 times wider than thick bends
    /// with `E / (1 - nu^2)`, as this gives).
    PlaneStrain,
}

impl Idealization {
    pub const BOTH: [Idealization; 2] = [Idealization::PlaneStress, Idealization::PlaneStrain];

    pub fn name(self) -> &'static str {
        match self {
            Idealization::PlaneStress => "plane stress",
            Idealization::PlaneStrain => "plane strain",
        }
    }
}

/// What a value of the FE check stands for: the plate in one of the 2D idealizations, or
/// the part itself in 3D (its mesh extruded through the width, [`crate::fe::solid`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Fidelity {
    #[serde(rename = "plane_stress")]
    PlaneStress,
    #[serde(rename = "plane_strain")]
    PlaneStrain,
    #[serde(rename = "3d")]
    Solid,
}

impl Fidelity {
    pub fn name(self) -> &'static str {
        match self {
            Fidelity::PlaneStress => "plane stress",
            Fidelity::PlaneStrain => "plane strain",
            Fidelity::Solid => "3D",
        }
    }

    /// The 2D idealization, for a 2D one.
    pub fn plane(self) -> Option<Idealization> {
        match self {
            Fidelity::PlaneStress => Some(Idealization::PlaneStress),
            Fidelity::PlaneStrain => Some(Idealization::PlaneStrain),
            Fidelity::Solid => None,
        }
    }

    /// The fidelity a plate `width` wide over hinges at least `thinnest` thick needs: a 2D
    /// idealization where it is within [`SOLID_RULE_ERROR`] of the 3D part, 3D between.
    /// The bounds are measured on wei2017's optimum, its width varied (the 3D check against
    /// the nearer bound, docs/guide/src/fe-check.md): `k_in` and `k_out` in 3D are 0.01 %
    /// and 0.15 % above plane stress at `w / t` = 0.5 and 1, 3 % at 4; 2.3 %, 0.9 % and
    /// 0.5 % below plane strain at 25, 100 and 250.
    pub fn for_plate(width: f64, thinnest: f64) -> Fidelity {
        let ratio = width / thinnest;
        if ratio < SOLID_RULE.0 {
            Fidelity::PlaneStress
        } else if ratio > SOLID_RULE.1 {
            Fidelity::PlaneStrain
        } else {
            Fidelity::Solid
        }
    }
}

impl From<Idealization> for Fidelity {
    fn from(i: Idealization) -> Self {
        match i {
            Idealization::PlaneStress => Fidelity::PlaneStress,
            Idealization::PlaneStrain => Fidelity::PlaneStrain,
        }
    }
}

/// The range of `width / thinnest hinge` in which [`Fidelity::for_plate`] asks for 3D.
pub const SOLID_RULE: (f64, f64) = (1.0, 250.0);
/// What the 2D idealizations outside [`SOLID_RULE`] may differ from 3D by, at most.
pub const SOLID_RULE_ERROR: f64 = 0.005;

/// An isotropic linear elastic material, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    pub density: f64,
}

impl Elastic {
    /// The matrix `D` with `sigma = D epsilon`, for `(xx, yy, xy)` and engineering shear
    /// strain.
    pub fn d_matrix(&self, idealization: Idealization) -> [[f64; 3]; 3] {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        match idealization {
            Idealization::PlaneStress => {
                let c = e / (1.0 - nu * nu);
                [
                    [c, c * nu, 0.0],
                    [c * nu, c, 0.0],
                    [0.0, 0.0, c * 0.5 * (1.0 - nu)],
                ]
            }
            Idealization::PlaneStrain => {
                let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
                [
                    [c * (1.0 - nu), c * nu, 0.0],
                    [c * nu, c * (1.0 - nu), 0.0],
                    [0.0, 0.0, c * 0.5 * (1.0 - 2.0 * nu)],
                ]
            }
        }
    }

    /// The von Mises stress of the in-plane stresses `s = (xx, yy, xy)`: with `zz = 0` in
    /// plane stress and `zz = nu (xx + yy)` in plane strain.
    pub fn von_mises(&self, s: [f64; 3], idealization: Idealization) -> f64 {
        let zz = match idealization {
            Idealization::PlaneStress => 0.0,
            Idealization::PlaneStrain => self.poisson_ratio * (s[0] + s[1]),
        };
        let (a, b, c) = (s[0] - s[1], s[1] - zz, zz - s[0]);
        (0.5 * (a * a + b * b + c * c) + 3.0 * s[2] * s[2]).sqrt()
    }
}

/// Gauss-Legendre, three points on [0, 1]: exact for a quadratic edge's straight length
/// times a quartic.
pub const QUADRATIC_EDGE_GAUSS: [(f64, f64); 3] = [
    (0.112_701_665_379_258_3, 5.0 / 18.0),
    (0.5, 8.0 / 18.0),
    (0.887_298_334_620_741_7, 5.0 / 18.0),
];

/// The quadratic edge's shape functions at `s` in [0, 1] (nodes: start, middle, end) and
/// their derivatives: the edge of every quadratic element.
pub fn quadratic_edge_shape(s: f64) -> ([f64; 3], [f64; 3]) {
    (
        [
            (1.0 - s) * (1.0 - 2.0 * s),
            4.0 * s * (1.0 - s),
            s * (2.0 * s - 1.0),
        ],
        [4.0 * s - 3.0, 4.0 - 8.0 * s, 4.0 * s - 1.0],
    )
}
