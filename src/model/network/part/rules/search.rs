//! The rules' margins at a design: the pieces within reach of each rule found on `f64`
//! (bounding boxes, then the least clearance), the winning pair's feature evaluated over
//! dual numbers ([`Rules`]).

use super::*;
use crate::model::jet2::Jet2;

/// What gives a clearance rule's margin at a design: the pair of shapes, the feature of
/// their clearance and the slot asked.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Nearest {
    a: Shape,
    b: Shape,
    feature: Feature,
    need: f64,
}

const EMPTY: [f64; 4] = [
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::INFINITY,
    f64::NEG_INFINITY,
];

/// A piece's bounding box: least and largest `x`, then `y`. By comparisons, which pass over
/// a NaN as `f64::min` does, without its handling of one at every corner.
fn bounds(corners: &[Pt<f64>]) -> [f64; 4] {
    let mut b = EMPTY;
    for p in corners {
        if p[0] < b[0] {
            b[0] = p[0];
        }
        if p[0] > b[1] {
            b[1] = p[0];
        }
        if p[1] < b[2] {
            b[2] = p[1];
        }
        if p[1] > b[3] {
            b[3] = p[1];
        }
    }
    b
}

/// The box holding both boxes.
fn union(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0].min(b[0]),
        a[1].max(b[1]),
        a[2].min(b[2]),
        a[3].max(b[3]),
    ]
}

/// The boxes' gap along an axis: a lower bound of the clearance of what they hold.
fn gap(a: [f64; 4], b: [f64; 4]) -> f64 {
    (b[0] - a[1])
        .max(a[0] - b[1])
        .max((b[2] - a[3]).max(a[2] - b[3]))
}

/// Every segment between two of `n` corners: a hull's sides among them.
pub(super) fn all_pairs(n: usize) -> Vec<(usize, usize)> {
    (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .collect()
}

/// Each corner to the next, around.
pub(super) fn around(n: usize) -> Vec<(usize, usize)> {
    (0..n).map(|i| (i, (i + 1) % n)).collect()
}

/// The f64 geometry of a design for the search: the shapes, each flexure's three bands (by
/// flexure group) and the boxes of the pieces, the bands and the groups, the pieces by
/// group.
struct Search<'a> {
    layout: &'a Layout,
    shapes: &'a Shapes<f64>,
    slot: f64,
    boxes: Vec<[f64; 4]>,
    bands: Vec<Option<[[Pt<f64>; 4]; 3]>>,
    band_boxes: Vec<[[f64; 4]; 3]>,
    /// Each group's box: its pieces' and, for a flexure, its whole band's.
    group_boxes: Vec<[f64; 4]>,
    /// The pieces in order of their group, and where each group's begin.
    by_group: Vec<usize>,
    group_start: Vec<usize>,
}

const BANDS: [Band; 3] = [Band::Whole, Band::Start, Band::End];
const IN_ORDER: [(usize, usize); 4] = [(0, 1), (1, 2), (2, 3), (3, 0)];

impl<'a> Search<'a> {
    fn new(layout: &'a Layout, shapes: &'a Shapes<f64>, s: &PartSettings) -> Self {
        let slot_of = |site: &Site<f64>| site.fillet.max(s.min_slot);
        let boxes: Vec<[f64; 4]> = (0..shapes.pieces.len())
            .map(|k| bounds(shapes.corners(k)))
            .collect();
        let bands: Vec<Option<[[Pt<f64>; 4]; 3]>> = shapes
            .sites
            .iter()
            .map(|site| site.map(|site| BANDS.map(|b| keep_out(&site, slot_of(&site), b))))
            .collect();
        let band_boxes: Vec<[[f64; 4]; 3]> = bands
            .iter()
            .map(|b| {
                b.as_ref()
                    .map_or([EMPTY; 3], |b| b.each_ref().map(|c| bounds(c)))
            })
            .collect();
        let groups = layout.groups.len();
        let mut group_boxes: Vec<[f64; 4]> = band_boxes.iter().map(|b| b[0]).collect();
        group_boxes.resize(groups, EMPTY);
        let mut count = vec![0; groups + 1];
        for (p, &b) in shapes.pieces.iter().zip(&boxes) {
            group_boxes[p.group] = union(group_boxes[p.group], b);
            count[p.group + 1] += 1;
        }
        for g in 0..groups {
            count[g + 1] += count[g];
        }
        let group_start = count.clone();
        let mut by_group = vec![0; shapes.pieces.len()];
        for (k, p) in shapes.pieces.iter().enumerate() {
            by_group[count[p.group]] = k;
            count[p.group] += 1;
        }
        Search {
            layout,
            shapes,
            slot: s.min_slot,
            boxes,
            bands,
            band_boxes,
            group_boxes,
            by_group,
            group_start,
        }
    }

    /// The pieces of group `g`, in their order among the pieces.
    fn of(&self, g: usize) -> &[usize] {
        &self.by_group[self.group_start[g]..self.group_start[g + 1]]
    }

    fn corners(&self, shape: Shape) -> &[Pt<f64>] {
        match shape {
            Shape::Solid(k) => self.shapes.corners(k),
            Shape::Band(f, b) => &self.bands[f].as_ref().expect("a flexure's band")[b as usize],
        }
    }

    fn solid(&self, shape: Shape) -> (Solid<'_>, [f64; 4]) {
        match shape {
            Shape::Solid(k) => {
                let p = self.shapes.pieces[k];
                let n = p.end - p.start;
                let sides = if p.ordered {
                    &self.layout.rings[n]
                } else {
                    &self.layout.pairs[n]
                };
                (
                    Solid {
                        corners: self.shapes.corners(k),
                        sides,
                    },
                    self.boxes[k],
                )
            }
            Shape::Band(f, b) => (
                Solid {
                    corners: self.corners(shape),
                    sides: &IN_ORDER,
                },
                self.band_boxes[f][b as usize],
            ),
        }
    }

    /// The end of the flexure `f` at which the piece `k` meets it: the one whose face is
    /// nearer, as the check's `joint` has it.
    fn joint(&self, f: usize, k: usize) -> Band {
        let site = self.shapes.sites[f].expect("a flexure's site");
        let d = [site.end[0] - site.start[0], site.end[1] - site.start[1]];
        let len = d[0].hypot(d[1]);
        let u = [d[0] / len, d[1] / len];
        let face = |p: Pt<f64>, along: f64| [p[0] + along * u[0], p[1] + along * u[1]];
        let (piece, _) = self.solid(Shape::Solid(k));
        let to = |p: Pt<f64>| {
            let point = Solid {
                corners: &[p],
                sides: &[],
            };
            clearance(point, piece).0.max(0.0)
        };
        if to(face(site.start, -site.fillet)) <= to(face(site.end, site.fillet)) {
            Band::Start
        } else {
            Band::End
        }
    }

    /// The least margin below `least` of the rule `(i, j)`'s terms (each pair of shapes it
    /// compares, with the slot asked), and what gives it. A term whose boxes are at least
    /// `least` beyond its slot apart cannot give it and is passed over (its group's pair
    /// first): its value would be the same.
    fn nearest(&self, (i, j): (usize, usize), mut least: f64) -> Option<(f64, Nearest)> {
        if gap(self.group_boxes[i], self.group_boxes[j]) >= least + 1e-12 {
            return None;
        }
        let mut best = None;
        let mut term = |a: Shape, b: Shape, need: f64, least: &mut f64| {
            let ((sa, ba), (sb, bb)) = (self.solid(a), self.solid(b));
            if gap(ba, bb) >= *least + need + 1e-12 {
                return;
            }
            if let Some((c, feature)) = clearance_below(sa, sb, *least + need) {
                if c - need < *least {
                    *least = c - need;
                    best = Some(Nearest {
                        a,
                        b,
                        feature,
                        need,
                    });
                }
            }
        };
        let layout = self.layout;
        let (gi, gj) = (layout.groups[i], layout.groups[j]);
        let joined = layout.joins(gi, gj) || layout.joins(gj, gi);
        if !joined {
            for &a in self.of(i) {
                for &b in self.of(j) {
                    term(Shape::Solid(a), Shape::Solid(b), self.slot, &mut least);
                }
            }
        }
        for (f, other) in [(i, j), (j, i)] {
            if !matches!(layout.groups[f], Group::Flexure(..)) {
                continue;
            }
            for &k in self.of(other) {
                let band = if joined {
                    // the shortened band lies within the whole one's box
                    if gap(self.band_boxes[f][0], self.boxes[k]) >= least + 1e-12 {
                        continue;
                    }
                    self.joint(f, k)
                } else {
                    Band::Whole
                };
                term(Shape::Band(f, band), Shape::Solid(k), 0.0, &mut least);
            }
        }
        best.map(|b| (least, b))
    }
}

/// What gives each clearance rule's margin at a design, found on the real parts.
struct Selection {
    nearest: Vec<Option<Nearest>>,
}

impl Layout {
    /// Each rule's margin (m) at the design whose real geometry is `shapes`, into `out`
    /// (the first `out.len()` rules), with what gives each clearance.
    fn find(&self, shapes: &Shapes<f64>, s: &PartSettings, out: &mut [f64]) -> Selection {
        let first = self.first.min(out.len());
        out[..first].copy_from_slice(&shapes.sizes[..first]);
        if out.len() == first {
            return Selection {
                nearest: Vec::new(),
            };
        }
        let search = Search::new(self, shapes, s);
        let mut nearest = Vec::new();
        for (o, &row) in out[first..].iter_mut().zip(&self.rows) {
            let chosen = search.nearest(row, CAP).map(|(_, n)| n);
            *o = chosen.map_or(CAP, |n| {
                n.feature.value(search.corners(n.a), search.corners(n.b)) - n.need
            });
            nearest.push(chosen);
        }
        Selection { nearest }
    }
}

impl Selection {
    /// The margins over `D` at `shapes` (the design the selection was found at).
    fn margins<D: Scalar>(
        &self,
        layout: &Layout,
        shapes: &Shapes<D>,
        s: &PartSettings,
        out: &mut [D],
    ) {
        let first = layout.first.min(out.len());
        out[..first].copy_from_slice(&shapes.sizes[..first]);
        let band = |f: usize, b: Band| {
            let site = shapes.sites[f].expect("a flexure's site");
            keep_out(&site, site.fillet.max(s.min_slot), b)
        };
        for (o, n) in out[first..].iter_mut().zip(&self.nearest) {
            *o = n.map_or(D::from(CAP), |n| {
                let (band_a, band_b);
                let a = match n.a {
                    Shape::Solid(k) => shapes.corners(k),
                    Shape::Band(f, b) => {
                        band_a = band(f, b);
                        &band_a
                    }
                };
                let b = match n.b {
                    Shape::Solid(k) => shapes.corners(k),
                    Shape::Band(f, b) => {
                        band_b = band(f, b);
                        &band_b
                    }
                };
                n.feature.value(a, b) - n.need
            });
        }
    }

    /// Whether the piece `k` is among the shapes the margins read.
    fn reads(&self, k: usize) -> bool {
        self.nearest
            .iter()
            .flatten()
            .any(|n| n.a == Shape::Solid(k) || n.b == Shape::Solid(k))
    }
}

/// The network part's rules at a design: its layout, the description and the settings.
pub struct Rules<'a> {
    pub layout: &'a Layout,
    pub d: &'a Description,
    pub s: &'a PartSettings,
}

impl Rules<'_> {
    /// Each rule's margin (m) at the design `x` (SI), the first `out.len()` of them; NaN
    /// where an expression has no value at `x`.
    pub fn margins(&self, x: &[f64], out: &mut [f64]) {
        if out.is_empty() {
            return;
        }
        match self
            .layout
            .shapes(self.d, self.s, x, |_| self.searched(out.len()))
        {
            Some(shapes) => {
                self.layout.find(&shapes, self.s, out);
            }
            None => out.fill(f64::NAN),
        }
    }

    /// As [`Rules::margins`], with their gradients over every parameter, row-major.
    pub fn margins_with_gradient(&self, x: &[f64], out: &mut [f64], jacobian: &mut [f64]) {
        if out.is_empty() {
            return;
        }
        let searched = self.searched(out.len());
        let Some(real) = self.layout.shapes(self.d, self.s, x, |_| searched) else {
            out.fill(f64::NAN);
            jacobian.fill(f64::NAN);
            return;
        };
        // the values as `margins` computes them, and the nearest pairs found once, on them
        let selection = self.layout.find(&real, self.s, out);
        let rows = out.len();
        with_count!(x.len(), |N| self
            .gradients::<N>(x, &selection, rows, jacobian));
    }

    /// As [`Rules::margins_with_gradient`], with each margin's Hessian over every parameter
    /// (`x.len()^2` a rule, row-major), over [`Jet2`]: for the spreads of a robust study's
    /// rules.
    pub fn margins_with_hessian(
        &self,
        x: &[f64],
        out: &mut [f64],
        jacobian: &mut [f64],
        hessian: &mut [f64],
    ) {
        if out.is_empty() {
            return;
        }
        let searched = self.searched(out.len());
        let Some(real) = self.layout.shapes(self.d, self.s, x, |_| searched) else {
            out.fill(f64::NAN);
            jacobian.fill(f64::NAN);
            hessian.fill(f64::NAN);
            return;
        };
        let selection = self.layout.find(&real, self.s, out);
        with_count!(x.len(), |N| self
            .second_derivatives::<N>(x, &selection, jacobian, hessian));
    }

    /// The first `rows` margins over `D` at `seeded`, the design `selection` was found at
    /// over dual numbers: only the pieces the winning pairs read are built over `D` (the
    /// others' corners over dual numbers were most of an evaluation with gradients).
    fn margins_over<D: Scalar>(&self, seeded: &[D], selection: &Selection, rows: usize) -> Vec<D> {
        let dual = self
            .layout
            .shapes(self.d, self.s, seeded, |k| selection.reads(k))
            .expect("the expressions have values where their real parts do");
        let mut y = vec![D::from(0.0); rows];
        selection.margins(self.layout, &dual, self.s, &mut y);
        y
    }

    /// The rows' gradients and Hessians over `Jet2<N>`, `N` the count of parameters.
    fn second_derivatives<const N: usize>(
        &self,
        x: &[f64],
        selection: &Selection,
        jacobian: &mut [f64],
        hessian: &mut [f64],
    ) {
        let seeded: Vec<Jet2<N>> = x
            .iter()
            .enumerate()
            .map(|(i, &v)| Jet2::variable(v, i))
            .collect();
        let y = self.margins_over(&seeded, selection, jacobian.len() / N);
        for (k, yk) in y.iter().enumerate() {
            jacobian[k * N..(k + 1) * N].copy_from_slice(&yk.grad);
            yk.hessian(&mut hessian[k * N * N..(k + 1) * N * N]);
        }
    }

    /// Whether the first `rows` rules take clearances, not only the size rules: a study's
    /// first stage asks for the size rules alone (none for a network without beams), and
    /// the solids were built and searched at each of its evaluations for nothing.
    fn searched(&self, rows: usize) -> bool {
        rows > self.layout.first
    }

    /// The rows' gradients over `Jet<N>`, `N` the count of parameters.
    fn gradients<const N: usize>(
        &self,
        x: &[f64],
        selection: &Selection,
        rows: usize,
        jacobian: &mut [f64],
    ) {
        let seeded: Vec<Jet<N>> = x
            .iter()
            .enumerate()
            .map(|(i, &v)| Jet::variable(v, i))
            .collect();
        let y = self.margins_over(&seeded, selection, rows);
        for (row, yi) in jacobian.chunks_exact_mut(N).zip(&y) {
            row.copy_from_slice(&yi.grad);
        }
    }

    /// Where each rule is measured at `x` (SI): the nearest pair's witness points, the slot
    /// asked the limit; none for the size rules and where no pair is near.
    pub fn witnesses(&self, x: &[f64], out: &mut [Option<Witness>]) {
        out.fill(None);
        let Some(shapes) = self.layout.shapes(self.d, self.s, x, |_| true) else {
            return;
        };
        let mut values = vec![0.0; out.len()];
        let selection = self.layout.find(&shapes, self.s, &mut values);
        let search = Search::new(self.layout, &shapes, self.s);
        let first = self.layout.first.min(out.len());
        for (o, n) in out[first..].iter_mut().zip(&selection.nearest) {
            *o = n.map(|n| Witness {
                points: n.feature.witness(search.corners(n.a), search.corners(n.b)),
                limit: n.need,
            });
        }
    }
}
