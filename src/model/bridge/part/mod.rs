//! The whole bridge as a part: four quarters mirrored about the input (x) and output (y)
//! axes as in paper 004's Fig. 1 and 3, two input blocks the actuator pushes apart, two
//! output blocks (the upper one carries the output, the lower one is clamped). The origin is
//! the part's centre, x along the actuator, y along the output.
//!
//! The model's quarter (nodes 2 to 5) is the upper left one: hinge b from the left input
//! block to the middle link c, hinge d from c to the upper output block. Where each solid
//! starts and ends (r the fillet radius, u a hinge's direction from node 2 or 4 onwards):
//!
//! - hinge b's thin section runs from node 2 to node 3, exactly the model's `l2`; the rigid
//!   bodies' faces stand `r` beyond its ends, perpendicular to it: the input block's at node
//!   2 - r u, the link's at node 3 + r u. Each face is `2 h = max(link_thickness, t + 2 r)`
//!   wide, centred on the hinge, so the fillets (radius r, tangent to the hinge where its thin
//!   section ends and to the face) land on it. Hinge d likewise between the link's face at
//!   node 4 - r u and the output block's at node 5 + r u. The hinge's solid runs from face
//!   to face; its corners are vertices of the faces too, so that the union joins them
//!   exactly.
//! - the middle link is the convex hull of its two faces: `link_thickness` wide (or `t + 2 r`
//!   where that is wider), rigid between the hinges as the model has it. The fillets take
//!   `r` of its length at each end: the part's link between the faces is `l3 - 2 r` long
//!   along the model's line, where the model has a rigid link of `l3` from node 3 to node 4.
//! - the left input block: its outer side `input_block_width` from the centre of hinge b's
//!   face, `input_block_height` tall, centred on the actuator's axis; the faces of the upper
//!   and lower hinges b on its inner side, each with its centre `h` below the block's top (or
//!   above its bottom). Between them, the inner side is the face the actuator pushes
//!   (`input_left`; `input_right` on the other block).
//! - the upper output block: `output_block_width` between the centres of the faces of the
//!   left and right hinges d, which stand on its sides (its sides continue the faces: a
//!   trapezoid when they are tilted); its inner side flush with the faces' lower ends, and
//!   `output_block_height` tall from there outward, away from the actuator. Its top is the
//!   output face (`output_top`); the bottom of the lower block is where the part is clamped
//!   (`clamp_bottom`).
//!
//! So the part's overall width is twice `output_block_width / 2 + span_x +
//! r (cos d2 + cos d4) + input_block_width`, and its height the larger of the input blocks'
//! and the output blocks' extents (or of an arm's, where one rises above both).

use serde::Serialize;

pub mod clearances;
mod drawing;
pub mod fe_cases;
pub mod footprint;
mod pieces;
pub mod rules;

use super::geometry::{Geometry, Layout};
use super::BridgeSettings;
use crate::model::part_rules::broken;
use crate::model::scalar::{max, Scalar};
use crate::part::{convex_hull, Actuation, Actuator, Face, HingeSite, PartSpec, Solid};
use drawing::{annotations, deg, mm};

/// The `[part]` settings of a bridge (SI).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PartSettings {
    /// In-plane thickness of the middle links (m); the dynamics' link mass uses it too.
    pub link_thickness: f64,
    /// Radius of the fillets at the hinge roots (m).
    pub fillet_radius: f64,
    pub input_block_width: f64,
    pub input_block_height: f64,
    pub output_block_width: f64,
    pub output_block_height: f64,
    /// The narrowest slot the wire cuts (m): solids not joined keep at least this apart.
    pub min_slot: f64,
    /// The actuator's length and height, if given (`[actuator] length`, `height`): the
    /// pocket between the blocks must hold it.
    pub actuator_length: Option<f64>,
    pub actuator_height: Option<f64>,
    /// Whether the study keeps to the part's rules ([`rules`]): `[part] enforce`.
    pub enforce: bool,
}

impl Default for PartSettings {
    /// Wire EDM with a 0.25 mm wire and a spark gap of about 0.04 mm cuts inner corners of
    /// about 0.17 mm radius and slots of about 0.33 mm: 0.2 mm fillets and 0.4 mm slots
    /// leave a margin. Links 3 mm wide are 7.5 times as thick as Table 1's 0.4 mm hinges,
    /// so about 400 times as stiff in bending per length; blocks of 6 x 12 mm (input) and
    /// 10 x 6 mm (output) are the size of a small stage's.
    fn default() -> Self {
        PartSettings {
            link_thickness: 3e-3,
            fillet_radius: 0.2e-3,
            input_block_width: 6e-3,
            input_block_height: 12e-3,
            output_block_width: 10e-3,
            output_block_height: 6e-3,
            min_slot: 0.4e-3,
            actuator_length: None,
            actuator_height: None,
            enforce: true,
        }
    }
}

impl PartSettings {
    /// The masses (kg) of an input block and of an output block, each its rectangle of
    /// `[part]`'s sizes through a plate `width` thick of `density`: what the dynamics takes
    /// for a link's mass the file leaves out. The hinges' pads and the output block's
    /// trapezoid where the faces of hinges d tilt are left out: at Table 1's optimum the cut
    /// blocks are 0.86 % (input) and 2.14 % (output) heavier (tests/models/bridge_dynamics.rs).
    pub fn block_masses(&self, width: f64, density: f64) -> [f64; 2] {
        let rho_w = density * width;
        [
            rho_w * self.input_block_width * self.input_block_height,
            rho_w * self.output_block_width * self.output_block_height,
        ]
    }
}

type P<D = f64> = [D; 2];

fn add<D: Scalar>(a: P<D>, b: P<D>) -> P<D> {
    [a[0] + b[0], a[1] + b[1]]
}

fn scale<D: Scalar>(a: P<D>, k: D) -> P<D> {
    [a[0] * k, a[1] * k]
}

fn mirror_x(p: P) -> P {
    [-p[0], p[1]]
}

fn mirror_y(p: P) -> P {
    [p[0], -p[1]]
}

fn mirror_xy(p: P) -> P {
    [-p[0], -p[1]]
}

/// A polygon mirrored: its points mirrored and reversed, so it stays counterclockwise.
fn mirrored(points: &[P], m: fn(P) -> P) -> Vec<P> {
    points.iter().rev().map(|&p| m(p)).collect()
}

/// `polygon` with each of `points` inserted into the edge it lies on (within 1e-15 m of
/// the edge's line, between its ends): the corners of a hinge on a body's face.
fn on_edges(mut polygon: Vec<P>, points: &[P]) -> Vec<P> {
    for &p in points {
        let n = polygon.len();
        let found = (0..n).find(|&i| {
            let (a, b) = (polygon[i], polygon[(i + 1) % n]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let len = d[0].hypot(d[1]);
            let along = ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len;
            let off = ((p[0] - a[0]) * d[1] - (p[1] - a[1]) * d[0]).abs() / len;
            off < 1e-15 && along > 0.0 && along < len
        });
        if let Some(i) = found {
            polygon.insert(i + 1, p);
        }
    }
    polygon
}

/// The upper left quarter placed in the part: its nodes, the faces at the hinges' ends, the
/// hinges' directions and normals, and the half widths of the faces. Over [`Scalar`], so
/// that the part's rules ([`clearances`]) place the solids as [`spec`] does.
struct Quarter<D = f64> {
    n: [P<D>; 4],
    /// Centres of the faces: input block, link (b end), link (d end), output block.
    f: [P<D>; 4],
    nb: P<D>,
    ud: P<D>,
    nd: P<D>,
    hb: D,
    hd: D,
}

impl<D: Scalar> Quarter<D> {
    /// `tb`, `td`: the hinges' root thicknesses; `rb`, `rd`: their root fillets (a
    /// strip's; a notch meets its bodies smoothly and has none).
    fn new(g: &Geometry<D>, s: &PartSettings, [tb, td]: [D; 2], [rb, rd]: [f64; 2]) -> Self {
        let t = g.trig();
        let (ub, ud) = ([t.c[0], t.s[0]], [t.c[2], t.s[2]]);
        let (nb, nd) = ([-ub[1], ub[0]], [-ud[1], ud[0]]);
        let half = D::from(0.5 * s.link_thickness);
        let hb = max(half, tb * 0.5 + rb);
        let hd = max(half, td * 0.5 + rd);
        let nodes = g.nodes();
        // hinge d's face on the output block's side, hinge b's face centre `hb` below the
        // input block's top
        let offset = [
            D::from(-0.5 * s.output_block_width) - (nodes[3][0] + ud[0] * rd),
            D::from(0.5 * s.input_block_height) - hb + ub[1] * rb,
        ];
        let n = nodes.map(|p| add(p, offset));
        let f = [
            add(n[0], scale(ub, D::from(-rb))),
            add(n[1], scale(ub, D::from(rb))),
            add(n[2], scale(ud, D::from(-rd))),
            add(n[3], scale(ud, D::from(rd))),
        ];
        Quarter {
            n,
            f,
            nb,
            ud,
            nd,
            hb,
            hd,
        }
    }
}

/// The two ends of a face of half width `half` centred at `c`, across direction `dir`.
fn across<D: Scalar>(c: P<D>, dir: P<D>, half: D) -> [P<D>; 2] {
    [add(c, scale(dir, -half)), add(c, scale(dir, half))]
}

/// A rectangle from `a` to `b`, `half` to each side along `dir`, counterclockwise when
/// `dir` is the left normal of `a -> b`.
fn band<D: Scalar>(a: P<D>, b: P<D>, dir: P<D>, half: D) -> [P<D>; 4] {
    [
        add(a, scale(dir, -half)),
        add(b, scale(dir, -half)),
        add(b, scale(dir, half)),
        add(a, scale(dir, half)),
    ]
}

/// The part of design `x`, or what makes it impossible before any solid is joined.
pub fn spec(
    settings: &BridgeSettings,
    layout: &Layout,
    x: &[f64],
) -> Result<PartSpec, Vec<String>> {
    let s = &settings.part;
    let g: Geometry<f64> = layout.geometry(x);
    let tb = layout.hinge_b.root_thickness(g.b.dims());
    let td = layout.hinge_d.root_thickness(g.d.dims());
    let (rb, rd) = (
        rules::fillet(s, layout.hinge_b),
        rules::fillet(s, layout.hinge_d),
    );
    let q = Quarter::new(&g, s, [tb, td], [rb, rd]);
    let least = layout
        .hinge_b
        .least_thickness(g.b.dims())
        .max(layout.hinge_d.least_thickness(g.d.dims()));
    let mut problems = size_problems(s, &q, least);
    let [f2, f3, f4, f5] = q.f;

    // each hinge's solid runs from face to face; its corners are vertices of the bodies'
    // faces too, the very same numbers, so that the union joins them exactly
    let hinge_b = band(f2, f3, q.nb, 0.5 * tb).to_vec();
    let hinge_d = band(f4, f5, q.nd, 0.5 * td).to_vec();
    let [l3a, l3b] = across(f3, q.nb, q.hb);
    let [l4a, l4b] = across(f4, q.nd, q.hd);
    let link = on_edges(
        convex_hull(&[l3a, l3b, l4a, l4b]),
        &[hinge_b[1], hinge_b[2], hinge_d[0], hinge_d[3]],
    );

    // the left input block: the faces of the upper and lower hinges b on its inner side
    let [a, b] = across(f2, q.nb, q.hb); // a: the face's lower end, b: its upper end
    let (in_h, in_far) = (0.5 * s.input_block_height, f2[0] - s.input_block_width);
    let input_left = vec![
        [in_far, -in_h],
        mirror_y(b),
        mirror_y(hinge_b[3]),
        mirror_y(hinge_b[0]),
        mirror_y(a),
        a,
        hinge_b[0],
        hinge_b[3],
        b,
        [in_far, in_h],
    ];
    // the upper output block: the faces of the left and right hinges d on its sides
    // flush with the lower ends of the faces, extending outward
    let out_bottom = f5[1] - q.hd * q.nd[1];
    let out_top = out_bottom + s.output_block_height;
    // its sides continue the faces of hinges d: a trapezoid when the faces are tilted
    let side = |y: f64| f5[0] + (y - f5[1]) / q.nd[1] * q.nd[0];
    let output_top = vec![
        [side(out_bottom), out_bottom],
        [-side(out_bottom), out_bottom],
        mirror_x(hinge_d[1]),
        mirror_x(hinge_d[2]),
        [-side(out_top), out_top],
        [side(out_top), out_top],
        hinge_d[2],
        hinge_d[1],
    ];
    let pocket = -2.0 * a[0];
    if let Some(len) = s.actuator_length {
        if broken(pocket - len) {
            problems.push(format!(
                "the actuator's pocket between the input blocks is {} long, shorter than \
                 actuator.length ({})",
                mm(pocket),
                mm(len)
            ));
        }
    }
    if !problems.is_empty() {
        return Err(problems);
    }

    let mut solids = Vec::new();
    let mut hinges = Vec::new();
    let mut joints = Vec::new();
    // each quarter: its name, its mirror, and whether the mirror reverses the sense
    type Placement = (&'static str, fn(P) -> P, bool);
    let quarters: [Placement; 4] = [
        ("upper left", |p| p, false),
        ("upper right", mirror_x, true),
        ("lower left", mirror_y, true),
        ("lower right", mirror_xy, false),
    ];
    // the blocks first: solids 0-3
    let blocks = [
        ("the left input block", input_left.clone()),
        ("the right input block", mirrored(&input_left, mirror_x)),
        ("the upper output block", output_top.clone()),
        ("the lower output block", mirrored(&output_top, mirror_y)),
    ];
    for (name, points) in blocks {
        solids.push(Solid {
            name: name.into(),
            points,
        });
    }
    for (k, (name, m, flips)) in quarters.into_iter().enumerate() {
        let place = |points: &[P]| {
            if flips {
                mirrored(points, m)
            } else {
                points.iter().map(|&p| m(p)).collect()
            }
        };
        let first = solids.len();
        for (part, points) in [
            ("hinge b", &hinge_b),
            ("the middle link c", &link),
            ("hinge d", &hinge_d),
        ] {
            solids.push(Solid {
                name: format!("{part} ({name})"),
                points: place(points),
            });
        }
        // the input block on the quarter's side, the output block on its half
        let (input, output) = (k % 2, 2 + k / 2);
        joints.extend([
            (first, input),
            (first, first + 1),
            (first + 1, first + 2),
            (first + 2, output),
        ]);
        for (hinge, start, end, kind, dims, root, r, solid) in [
            (
                "hinge b",
                q.n[0],
                q.n[1],
                layout.hinge_b,
                g.b.dims(),
                tb,
                rb,
                first,
            ),
            (
                "hinge d",
                q.n[2],
                q.n[3],
                layout.hinge_d,
                g.d.dims(),
                td,
                rd,
                first + 2,
            ),
        ] {
            hinges.push(HingeSite {
                name: format!("{hinge} ({name})"),
                start: m(start),
                end: m(end),
                thickness: kind.least_thickness(dims),
                root,
                fillet: r,
                kind: kind.name(),
                profile: kind.outline(dims),
                solid,
            });
        }
    }

    let faces = vec![
        Face {
            name: fe_cases::INPUT_LEFT.into(),
            a: mirror_y(a),
            b: a,
        },
        Face {
            name: fe_cases::INPUT_RIGHT.into(),
            a: mirror_x(a),
            b: mirror_xy(a),
        },
        Face {
            name: fe_cases::OUTPUT_TOP.into(),
            a: [-side(out_top), out_top],
            b: [side(out_top), out_top],
        },
        Face {
            name: fe_cases::CLAMP_BOTTOM.into(),
            a: [side(out_top), -out_top],
            b: [-side(out_top), -out_top],
        },
    ];
    let mut warnings = Vec::new();
    if s.fillet_radius == 0.0
        && (layout.hinge_b.has_sharp_roots() || layout.hinge_d.has_sharp_roots())
    {
        warnings.push(
            "part.fillet_radius is 0: the hinge roots are sharp inner corners, which wire \
             EDM cannot cut (its smallest inner radius is about 0.1-0.2 mm) and whose elastic \
             stress is singular"
                .to_string(),
        );
    }
    Ok(PartSpec {
        width: settings.width,
        actuation: Some(Actuation {
            nominal_stroke: settings.actuator.nominal_stroke,
            preload: settings.actuator.preload,
            stiffness: settings.actuator.stiffness,
            payload_mass: settings.dynamics.as_ref().map_or(0.0, |d| d.payload_mass),
            stack_mass: settings.actuator.mass.unwrap_or(0.0),
        }),
        analysis: Some(fe_cases::analysis()),
        caption: if rb.max(rd) > 0.0 {
            format!(
                "fillets r {}, links {} thick",
                mm(s.fillet_radius),
                mm(s.link_thickness)
            )
        } else {
            format!("links {} thick", mm(s.link_thickness))
        },
        annotations: annotations(&g, &q, layout, [in_far, in_h, out_top, pocket]),
        solids,
        joints,
        hinges,
        faces,
        min_slot: s.min_slot,
        actuator: s.actuator_length.map(|length| Actuator {
            length,
            height: s.actuator_height,
        }),
        warnings,
    })
}

/// Sizes that leave no part: bodies thinner than the hinges they carry, blocks too small
/// for the faces the hinges need.
fn size_problems(s: &PartSettings, q: &Quarter, t: f64) -> Vec<String> {
    let mut problems = Vec::new();
    for (key, v) in [
        ("link_thickness", s.link_thickness),
        ("input_block_width", s.input_block_width),
        ("output_block_height", s.output_block_height),
    ] {
        if broken(v - t) {
            problems.push(format!(
                "part.{key} ({}) is thinner than the hinges ({}): a wall thinner than a \
                 hinge bends more than the hinge it carries",
                mm(v),
                mm(t)
            ));
        }
    }
    let [a, _] = across(q.f[0], q.nb, q.hb);
    if broken(a[1]) {
        problems.push(format!(
            "part.input_block_height ({}) leaves no room between the faces of the upper and \
             lower hinges b ({} wide each); make it at least {}",
            mm(s.input_block_height),
            mm(2.0 * q.hb),
            mm(s.input_block_height - 2.0 * a[1] + s.min_slot)
        ));
    }
    let face_height = 2.0 * q.hd * q.nd[1];
    if broken(s.output_block_height - face_height) {
        problems.push(format!(
            "part.output_block_height ({}) does not hold the faces of hinges d ({} wide, \
             tilted {}): make it more than {}",
            mm(s.output_block_height),
            mm(2.0 * q.hd),
            deg(q.ud[1].atan2(q.ud[0])),
            mm(face_height)
        ));
    }
    let out_bottom = q.f[3][1] - q.hd * q.nd[1];
    let out_top = out_bottom + s.output_block_height;
    let side = |y: f64| q.f[3][0] + (y - q.f[3][1]) / q.nd[1] * q.nd[0];
    // the slot between the block's two sides, where it is narrowest
    let gap = -2.0 * side(out_top).max(side(out_bottom));
    if broken(gap) {
        problems.push(format!(
            "part.output_block_width ({}) is too narrow for the faces of hinges d tilted {}: \
             the block's sides, which continue them, cross",
            mm(s.output_block_width),
            deg(q.ud[1].atan2(q.ud[0]))
        ));
    } else if broken(gap - s.min_slot) {
        // the sides do not cross: the slot asked for is what does not fit
        problems.push(format!(
            "part.min_slot ({}) is wider than the slot between the sides of the output block \
             ({} at its narrowest, the sides continuing the faces of hinges d tilted {}): make \
             it at most that, or widen part.output_block_width",
            mm(s.min_slot),
            mm(gap),
            deg(q.ud[1].atan2(q.ud[0]))
        ));
    }
    problems
}
