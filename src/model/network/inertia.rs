//! What moves in a network's natural modes: each body's mass and inertia (a plate cut to its
//! outline, the share of it the described part holds), and the masses that move with a point
//! along one direction only (a stack's share of its own mass), which [`super::modes`] puts in
//! the mass matrix.

use super::structure::Body;
use crate::model::scalar::Scalar;

/// A body's mass (kg), its centroid (m) and its moment of inertia about the centroid
/// (kg m^2), for motion in the plane.
#[derive(Debug, Clone, Copy)]
pub struct Inertia<D> {
    pub mass: D,
    pub centroid: [D; 2],
    pub moment: D,
}

impl<D: Scalar> Inertia<D> {
    /// A plate of `density` and thickness `width` cut to the polygon `points` (either
    /// winding), by the polygon's area moments from its edges (Green's theorem; Steger, "On
    /// the calculation of arbitrary moments of polygons", TU Munich report FGBV-96-05, 1996,
    /// Eq. 6-8): with `c_i = x_i y_{i+1} - x_{i+1} y_i`,
    ///
    /// ```text
    /// A = 1/2 sum c_i,   A x_c = 1/6 sum (x_i + x_{i+1}) c_i,   A y_c likewise,
    /// J_O = 1/12 sum (x_i^2 + x_i x_{i+1} + x_{i+1}^2 + y_i^2 + y_i y_{i+1} + y_{i+1}^2) c_i
    /// ```
    ///
    /// and the moment about the centroid `J_O - A |c|^2` (Steiner).
    pub fn polygon(points: &[[D; 2]], density: f64, width: f64) -> Self {
        let zero = D::from(0.0);
        let (mut a, mut sx, mut sy, mut j) = (zero, zero, zero, zero);
        // about the first vertex, so that the sums do not cancel far from the origin
        let o = points[0];
        for (i, p) in points.iter().enumerate() {
            let q = points[(i + 1) % points.len()];
            let (x0, y0, x1, y1) = (p[0] - o[0], p[1] - o[1], q[0] - o[0], q[1] - o[1]);
            let c = x0 * y1 - x1 * y0;
            a = a + c;
            sx = sx + (x0 + x1) * c;
            sy = sy + (y0 + y1) * c;
            j = j + (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1) * c;
        }
        let area = a * 0.5;
        let (cx, cy) = (sx / (area * 6.0), sy / (area * 6.0));
        let polar = j / 12.0 - area * (cx * cx + cy * cy);
        // a clockwise polygon has its area and moments negative alike
        let sign = if area.re() < 0.0 { -1.0 } else { 1.0 };
        Inertia {
            mass: area * (sign * density * width),
            centroid: [cx + o[0], cy + o[1]],
            moment: polar * (sign * density * width),
        }
    }

    /// A link: the rectangle `thickness` wide around the segment `a b`, `J = m (L^2 + h^2)
    /// / 12` about its middle.
    pub fn link(a: [D; 2], b: [D; 2], thickness: D, density: f64, width: f64) -> Self {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let l2 = dx * dx + dy * dy;
        let mass = l2.sqrt() * thickness * (density * width);
        Inertia {
            mass,
            centroid: [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5],
            moment: mass * (l2 + thickness * thickness) / 12.0,
        }
    }

    /// Its image in the line `y = 0` (`flip_y`) or `x = 0`.
    pub fn reflected(self, flip_y: bool) -> Self {
        let [x, y] = self.centroid;
        Inertia {
            centroid: if flip_y { [x, -y] } else { [-x, y] },
            ..self
        }
    }

    /// This body joined to its image in the line `y = 0` (`flip_y`) or `x = 0`: twice the
    /// mass, the centroid on the line, the moment by Steiner's rule from each half's.
    pub fn doubled(self, flip_y: bool) -> Self {
        let k = usize::from(flip_y);
        let d = self.centroid[k];
        let mut centroid = self.centroid;
        centroid[k] = D::from(0.0);
        Inertia {
            mass: self.mass * 2.0,
            centroid,
            moment: (self.moment + self.mass * d * d) * 2.0,
        }
    }

    /// This body with a point mass `m` added at `at`: a constant (a payload) or one of the
    /// design (a beam's end's share).
    pub fn with_point_mass(self, m: impl Into<D>, at: [D; 2]) -> Self {
        let m: D = m.into();
        if m.re() == 0.0 {
            return self;
        }
        let mass = self.mass + m;
        let c = [
            (self.centroid[0] * self.mass + at[0] * m) / mass,
            (self.centroid[1] * self.mass + at[1] * m) / mass,
        ];
        let d2 = |p: [D; 2]| {
            let (x, y) = (p[0] - c[0], p[1] - c[1]);
            x * x + y * y
        };
        Inertia {
            mass,
            centroid: c,
            moment: self.moment + self.mass * d2(self.centroid) + d2(at) * m,
        }
    }
}

/// The piece of a body's outline that the described part holds of it, for a body that lies
/// across mirror axes: about each axis (`true` the line `y = 0`, `false` the line `x = 0`),
/// the larger of the outline's two sides. The whole body is the outline joined to its
/// images about those axes, of which the described part carries one share per axis: half of
/// an outline drawn across the axis (symmetric about it), all of one drawn to the axis.
/// Each side is cut by the Sutherland-Hodgman rule (Sutherland and Hodgman, "Reentrant
/// polygon clipping", Comm. ACM 17 (1974) 32-42), generic over the scalar so that the mass
/// keeps its derivatives.
pub fn described_piece<D: Scalar>(points: &[[D; 2]], across_y0: &[bool]) -> Vec<[D; 2]> {
    let mut piece = points.to_vec();
    for &y0 in across_y0 {
        let k = usize::from(y0);
        let sides = [1.0, -1.0].map(|sign| clip(&piece, k, sign));
        let area = |p: &[[D; 2]]| {
            let mut a = 0.0;
            for (i, u) in p.iter().enumerate() {
                let v = p[(i + 1) % p.len()];
                a += u[0].re() * v[1].re() - v[0].re() * u[1].re();
            }
            a.abs()
        };
        let [a, b] = sides;
        piece = if area(&b) > area(&a) { b } else { a };
    }
    piece
}

/// The part of the polygon where `sign * p[k] >= 0`.
fn clip<D: Scalar>(points: &[[D; 2]], k: usize, sign: f64) -> Vec<[D; 2]> {
    let mut out = Vec::with_capacity(points.len() + 2);
    for (i, &p) in points.iter().enumerate() {
        let q = points[(i + 1) % points.len()];
        let (cp, cq) = (p[k] * sign, q[k] * sign);
        if cp.re() >= 0.0 {
            out.push(p);
        }
        // only an edge that crosses the line strictly adds a point: a vertex on it is kept
        // as a vertex, not doubled
        if (cp.re() > 0.0 && cq.re() < 0.0) || (cp.re() < 0.0 && cq.re() > 0.0) {
            let t = cp / (cp - cq);
            let mut x = [p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t];
            x[k] = D::from(0.0);
            out.push(x);
        }
    }
    out
}

/// A mass that moves with a body's point along one direction only (kg): what a stack
/// carries onto the face it pushes, which differs along its axis and across it
/// ([`crate::part::stack_mass_share`]).
#[derive(Debug, Clone, Copy)]
pub struct DirectedMass<D> {
    pub body: usize,
    pub point: [D; 2],
    /// A unit vector.
    pub direction: [D; 2],
    pub mass: f64,
}

impl<D: Scalar> DirectedMass<D> {
    /// The stack's mass `mass` on the input port's `point` of `body`, the stack along
    /// `direction`: its share along the stack and across it in one family of modes
    /// ([`crate::part::stack_mass_share`]), `mirrored` for a stack between the port and its
    /// image across a mirror axis, `stretched` in the family where the stack stretches.
    pub fn stack(
        mass: f64,
        (mirrored, stretched): (bool, bool),
        body: usize,
        point: [D; 2],
        direction: [D; 2],
    ) -> [Self; 2] {
        let (along, across) = crate::part::stack_mass_share(mass, mirrored, stretched);
        let length = (direction[0] * direction[0] + direction[1] * direction[1]).sqrt();
        let n = [direction[0] / length, direction[1] / length];
        [(n, along), ([-n[1], n[0]], across)].map(|(direction, mass)| DirectedMass {
            body,
            point,
            direction,
            mass,
        })
    }

    /// `masses` on the described part carried onto the part unfolded about the line `y = 0`
    /// (`flip_y`) or `x = 0` ([`Network::unfolded`], whose `image` of each body it takes): a
    /// mass on a body across the line is its own image (twice the mass), one on another body
    /// gets its image on the body's image.
    pub fn unfolded(masses: &[Self], image: &[Body], flip_y: bool) -> Vec<Self> {
        let reflect = |p: [D; 2]| if flip_y { [p[0], -p[1]] } else { [-p[0], p[1]] };
        let mut out = Vec::new();
        for m in masses {
            match image[m.body] {
                Body::Rigid(b) if b == m.body => out.push(DirectedMass {
                    mass: 2.0 * m.mass,
                    ..*m
                }),
                Body::Rigid(b) => out.extend([
                    *m,
                    DirectedMass {
                        body: b,
                        point: reflect(m.point),
                        direction: reflect(m.direction),
                        mass: m.mass,
                    },
                ]),
                Body::Ground => out.push(*m),
            }
        }
        out
    }
}
