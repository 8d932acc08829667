//! The layout of a network's part that does not depend on the design ([`Layout::new`]): the
//! groups, the pairs the rules look at and their names, the expressions that place the
//! solids compiled into the layout's tape.

use super::search::{all_pairs, around};
use super::*;

/// Every expression the solids are placed by, in the order [`Layout::shapes`] reads them.
fn placing(d: &mut Description) -> Vec<&mut Keyed> {
    let mut all: Vec<&mut Keyed> = Vec::new();
    for h in &mut d.hinges {
        all.extend(h.dimensions.iter_mut());
        all.push(&mut h.angle);
        all.extend(h.start.iter_mut());
    }
    for b in &mut d.beams {
        all.extend(b.start.iter_mut().chain(b.end.iter_mut()));
        all.push(&mut b.thickness);
    }
    all.extend(d.ground.iter_mut().flatten());
    for b in &mut d.bodies {
        all.extend(b.points.iter_mut().flatten());
        all.extend(b.link_width.iter_mut());
    }
    all
}

/// The most corners each body's pieces can have together (by slot, the ground first): its
/// outline, its link's band or the hull of its pads (six corners each), with its images
/// where it lies across an axis.
fn body_corners(d: &Description, ends: &[(usize, usize)]) -> Vec<usize> {
    let bodies = d.bodies.iter().enumerate().map(|(b, body)| {
        let own = match (&body.link_width, body.points.len()) {
            (Some(_), 2) => 4,
            (_, 0) => {
                6 * ends
                    .iter()
                    .filter(|&&(f, t)| f == b + 1 || t == b + 1)
                    .count()
            }
            // an outline's pieces: itself, or at most n - 2 triangles
            (_, n) => n.max(3 * n.saturating_sub(2)),
        };
        own << body.on_axis.len()
    });
    let ground = d.ground.len().max(3 * d.ground.len().saturating_sub(2));
    std::iter::once(ground).chain(bodies).collect()
}

impl Layout {
    /// The layout of the description's part; the expressions it reads are given their
    /// slots in the layout's own tape (the part's copy of the description).
    pub fn new(d: &mut Description) -> Layout {
        let tape = {
            let names = d.parameters.len() + 1;
            let mut all = placing(d);
            for (slot, e) in all.iter_mut().enumerate() {
                e.slot = slot;
            }
            Tape::compile(all.iter().map(|e| &e.expression), names)
        };
        let d = &*d;
        let slot = |b: Option<usize>| b.map_or(0, |b| b + 1);
        let own: Vec<Vec<Axis>> = std::iter::once(Vec::new())
            .chain(d.bodies.iter().map(|b| b.on_axis.clone()))
            .collect();
        let ends: Vec<(usize, usize)> = d
            .hinges
            .iter()
            .map(|h| (slot(h.from), slot(h.to)))
            .chain(d.beams.iter().map(|b| (slot(b.from), slot(b.to))))
            .collect();
        let images = Image::all(&d.mirror);
        let mut groups = Vec::new();
        for &t in &images {
            groups.extend((0..ends.len()).map(|c| Group::Flexure(c, t)));
        }
        let grounded = d.ground.len() >= 3 || ends.iter().any(|&(a, b)| a == 0 || b == 0);
        if grounded {
            groups.push(Group::Body(0, Image::IDENTITY));
        }
        for b in 1..own.len() {
            for &t in &images {
                let k = key(&own, b, t);
                if !groups.contains(&k) {
                    groups.push(k);
                }
            }
        }
        let index = |g: Group| groups.iter().position(|&h| h == g);
        let mut rows = Vec::new();
        for i in 0..groups.len() {
            for j in i + 1..groups.len() {
                // the first of the pair's images stands for them all
                let first = images
                    .iter()
                    .filter_map(|&s| {
                        let a = index(groups[i].under(s, &own))?;
                        let b = index(groups[j].under(s, &own))?;
                        Some((a.min(b), a.max(b)))
                    })
                    .min();
                let body_pair =
                    matches!((groups[i], groups[j]), (Group::Body(..), Group::Body(..)));
                // a body's images are one solid where it lies across the axis; two images of
                // one body are apart by what the description draws
                if first == Some((i, j)) || (body_pair && first.is_none()) {
                    rows.push((i, j));
                }
            }
        }
        let bodies = body_corners(d, &ends);
        let most = bodies.iter().copied().chain([6]).max().unwrap_or(6);
        let drawn_corners: usize = bodies.iter().sum::<usize>() * 2;
        let selves = own.iter().map(|axes| Image::all(axes)).collect();
        let corners = images.len() * (16 * ends.len() + drawn_corners);
        let mut layout = Layout {
            groups,
            rows,
            rules: Vec::new(),
            first: 2 * d.beams.len(),
            own,
            ends,
            tape,
            rings: (0..=most).map(around).collect(),
            pairs: (0..=most).map(all_pairs).collect(),
            selves,
            corners,
            drawn_corners,
            images,
        };
        layout.rules = layout.names(d);
        layout
    }

    pub fn rules(&self) -> &[PartRule] {
        &self.rules
    }

    pub fn first_rules(&self) -> usize {
        self.first
    }

    fn name(&self, d: &Description, g: Group) -> String {
        match g {
            Group::Flexure(c, t) if c < d.hinges.len() => {
                format!("hinge {}{}", d.hinges[c].name, t.suffix())
            }
            Group::Flexure(c, t) => {
                format!("beam {}{}", d.beams[c - d.hinges.len()].name, t.suffix())
            }
            Group::Body(0, _) => "the ground".to_string(),
            Group::Body(b, t) => format!("body {}{}", d.bodies[b - 1].name, t.suffix()),
        }
    }

    /// Whether the flexure group `f` joins the body group `b`.
    pub(super) fn joins(&self, f: Group, b: Group) -> bool {
        let Group::Flexure(c, t) = f else {
            return false;
        };
        let (from, to) = self.ends[c];
        key(&self.own, from, t) == b || key(&self.own, to, t) == b
    }

    fn names(&self, d: &Description) -> Vec<PartRule> {
        let mut out = Vec::new();
        for b in &d.beams {
            out.push(PartRule {
                name: format!("beam {}'s length", b.name).into(),
                description: format!("beam {}'s length ({}) positive", b.name, b.key).into(),
            });
            out.push(PartRule {
                name: format!("beam {}'s thickness", b.name).into(),
                description: format!("beam {}'s thickness ({}.thickness) positive", b.name, b.key)
                    .into(),
            });
        }
        for &(i, j) in &self.rows {
            let (a, b) = (self.groups[i], self.groups[j]);
            let (na, nb) = (self.name(d, a), self.name(d, b));
            let (name, description) = if self.joins(a, b) || self.joins(b, a) {
                let (f, body) = if self.joins(a, b) { (na, nb) } else { (nb, na) };
                (
                    format!("{f}'s band, {body}"),
                    format!(
                        "{body} behind the faces of {f}, out of its keep-out band (part.min_slot \
                         or the fillet beside its thin section)"
                    ),
                )
            } else if matches!(a, Group::Flexure(..)) || matches!(b, Group::Flexure(..)) {
                (
                    format!("slot, {na}, {nb}"),
                    format!(
                        "{na} and {nb} at least part.min_slot apart, and out of each other's \
                         keep-out bands (part.min_slot or the fillet beside a thin section)"
                    ),
                )
            } else {
                (
                    format!("slot, {na}, {nb}"),
                    format!("{na} and {nb} at least part.min_slot apart"),
                )
            };
            out.push(PartRule {
                name: name.into(),
                description: description.into(),
            });
        }
        out
    }
}
