//! The whole bridge as a part: the outline's validity, its dimensions measured on the
//! outline itself, the area and extent against independent sums, symmetry, the exported
//! files read back, and every manufacturability check tripped by a design.

use crate::common;

use std::path::Path;

use common::{flexopt, flexopt_ok, random_design, rng, table1_optimum, wei2017_settings, DEG, MM};
use flexopt::model::bridge::part::PartSettings;
use flexopt::model::bridge::Bridge;
use flexopt::model::{build_part, PartMaker};
use flexopt::part::{Loop, PartMm};

/// Table 1's printed design in the part's own units.
const PRINTED: &str = "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4";

fn bridge(part: PartSettings) -> Bridge {
    let mut s = wei2017_settings();
    s.part = part;
    Bridge::new(s)
}

type P = [f64; 2];

/// Every straight edge and arc of a loop split into chords, as segments.
fn segments(l: &Loop) -> Vec<(P, P)> {
    let p = l.points(16);
    (0..p.len()).map(|i| (p[i], p[(i + 1) % p.len()])).collect()
}

fn cross(o: P, a: P, b: P) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

/// Whether two segments cross or touch (shared end points of neighbours excluded by the
/// caller); collinear ones when their extents along the line overlap.
fn intersect(s: (P, P), t: (P, P)) -> bool {
    let (d1, d2) = (cross(t.0, t.1, s.0), cross(t.0, t.1, s.1));
    let (d3, d4) = (cross(s.0, s.1, t.0), cross(s.0, s.1, t.1));
    let size = |a: P, b: P| (b[0] - a[0]).hypot(b[1] - a[1]);
    let eps = 1e-12 * size(s.0, s.1) * size(t.0, t.1);
    if [d1, d2, d3, d4].iter().all(|d| d.abs() <= eps) {
        let u = [s.1[0] - s.0[0], s.1[1] - s.0[1]];
        let along = |p: P| (p[0] - s.0[0]) * u[0] + (p[1] - s.0[1]) * u[1];
        let (a, b) = (along(t.0), along(t.1));
        let len2 = u[0] * u[0] + u[1] * u[1];
        return a.max(b) >= 0.0 && a.min(b) <= len2;
    }
    (d1 * d2 <= 0.0) && (d3 * d4 <= 0.0)
}

/// No two non-adjacent segments of the outline (all loops together) meet.
pub(crate) fn assert_simple(part: &PartMm) {
    let all: Vec<(usize, usize, (P, P))> = part
        .loops
        .iter()
        .enumerate()
        .flat_map(|(k, l)| {
            let s = segments(l);
            s.into_iter().enumerate().map(move |(i, s)| (k, i, s))
        })
        .collect();
    let sizes: Vec<usize> = part.loops.iter().map(|l| segments(l).len()).collect();
    for (a, &(ka, ia, sa)) in all.iter().enumerate() {
        for &(kb, ib, sb) in &all[a + 1..] {
            if ka == kb {
                let n = sizes[ka];
                if ib == (ia + 1) % n || ia == (ib + 1) % n {
                    continue;
                }
            }
            assert!(
                !intersect(sa, sb),
                "outline crosses itself: loop {ka} edge {ia} {sa:?} and loop {kb} edge {ib} {sb:?}"
            );
        }
    }
}

fn shoelace(points: &[P]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| {
            0.5 * (points[i][0] * points[(i + 1) % n][1] - points[(i + 1) % n][0] * points[i][1])
        })
        .sum()
}

/// The part's area from its solids: every solid by the shoelace formula (they meet only
/// along the hinges' end faces), plus the material each fillet adds in its corner
/// (r^2 - pi r^2 / 4, four per hinge).
fn expected_area(model: &dyn PartMaker, x: &[f64]) -> f64 {
    let spec = model.part(x).unwrap();
    let solids: f64 = spec.solids.iter().map(|s| shoelace(&s.points)).sum();
    let hinges: f64 = spec
        .hinges
        .iter()
        .map(|h| {
            let r = h.fillet;
            4.0 * r * r * (1.0 - std::f64::consts::FRAC_PI_4)
        })
        .sum();
    (solids + hinges) * 1e6
}

/// The bounding box the design and the block sizes give (mm): the width from the spans,
/// the fillets and the blocks; the height the larger of the input blocks', the output
/// blocks' and the links' extents.
fn expected_box(x: &[f64; 8], s: &PartSettings) -> [f64; 2] {
    let [l2, d2, t2, l3, d3, l4, d4, t4] = *x;
    let r = s.fillet_radius;
    let span_x = l2 * d2.cos() + l3 * d3.cos() + l4 * d4.cos();
    let span_y = l2 * d2.sin() + l3 * d3.sin() + l4 * d4.sin();
    let half_width =
        0.5 * s.output_block_width + span_x + r * (d2.cos() + d4.cos()) + s.input_block_width;
    let hb = (0.5 * s.link_thickness).max(0.5 * t2 + r);
    let hd = (0.5 * s.link_thickness).max(0.5 * t4 + r);
    let in_h = 0.5 * s.input_block_height;
    // node 2 sits `r` along hinge b from its face, whose centre is hb below the block's top
    let n2 = [0.0, in_h - hb + r * d2.sin()];
    let n3 = [n2[0] + l2 * d2.cos(), n2[1] + l2 * d2.sin()];
    let n4 = [n3[0] + l3 * d3.cos(), n3[1] + l3 * d3.sin()];
    let f5y = n2[1] + span_y + r * d4.sin();
    let out_top = f5y - hd * d4.cos() + s.output_block_height;
    // the link's corners: its faces, r beyond nodes 3 and 4, hb and hd to each side
    let f3y = n3[1] + r * d2.sin();
    let f4y = n4[1] - r * d4.sin();
    let link_top = (f3y + hb * d2.cos())
        .max(f3y - hb * d2.cos())
        .max(f4y + hd * d4.cos())
        .max(f4y - hd * d4.cos());
    [
        2.0 * half_width * 1e3,
        2.0 * in_h.max(out_top).max(link_top) * 1e3,
    ]
}

/// The thickness and the length of the thin section of each hinge, measured on the
/// outline: the straight edges parallel to the hinge beside its centre line, the distance
/// between them and their length.
fn measured_hinges(part: &PartMm) -> Vec<(f64, f64)> {
    part.hinges
        .iter()
        .map(|h| {
            let (s, e) = (h.start, h.end);
            let len = (e[0] - s[0]).hypot(e[1] - s[1]);
            let u = [(e[0] - s[0]) / len, (e[1] - s[1]) / len];
            let n = [-u[1], u[0]];
            let mut sides = Vec::new();
            for l in &part.loops {
                let m = l.vertices.len();
                for i in 0..m {
                    let (a, b) = (l.vertices[i], l.vertices[(i + 1) % m]);
                    if a.bulge != 0.0 {
                        continue;
                    }
                    let d = [b.x - a.x, b.y - a.y];
                    let dl = d[0].hypot(d[1]);
                    let parallel = (d[0] * u[1] - d[1] * u[0]).abs() < 1e-9 * dl;
                    // its offset from the centre line, and where along the hinge it lies
                    let off = (a.x - s[0]) * n[0] + (a.y - s[1]) * n[1];
                    let along =
                        (0.5 * (a.x + b.x) - s[0]) * u[0] + (0.5 * (a.y + b.y) - s[1]) * u[1];
                    if parallel && off.abs() < h.thickness && (0.0..len).contains(&along) {
                        sides.push((off, dl));
                    }
                }
            }
            assert_eq!(
                sides.len(),
                2,
                "{}: the two edges of its thin section",
                h.name
            );
            assert!(
                (sides[0].1 - sides[1].1).abs() < 1e-9,
                "{}: {sides:?}",
                h.name
            );
            ((sides[0].0 - sides[1].0).abs(), sides[0].1)
        })
        .collect()
}

/// The loop's points (arcs sampled) mirrored by `m` are the loop's points again.
fn assert_symmetric(part: &PartMm, m: fn(P) -> P) {
    for l in &part.loops {
        let pts = l.points(4);
        for p in &pts {
            let q = m(*p);
            let d = pts
                .iter()
                .map(|r| (r[0] - q[0]).hypot(r[1] - q[1]))
                .fold(f64::INFINITY, f64::min);
            assert!(
                d < 1e-12,
                "{p:?} has no mirror image (nearest {d:e} mm away)"
            );
        }
    }
}

#[test]
fn a_thousand_random_designs_give_valid_outlines_with_the_designs_dimensions() {
    let settings = PartSettings::default();
    let model = bridge(settings.clone());
    let mut rng = rng(16);
    let (mut built, mut tried) = (0, 0);
    while built < 1000 {
        tried += 1;
        assert!(
            tried < 20_000,
            "only {built} of {tried} random designs give a part"
        );
        let x = random_design(&mut rng);
        let Ok(part) = build_part(&model, &x) else {
            continue;
        };
        // the part is in metres; its dimensions are checked in mm, as its files give them
        let part = part.in_mm();
        built += 1;
        // closed loops: one outer, counterclockwise, the pockets clockwise
        assert!(part.loops[0].outer && part.loops[0].signed_area() > 0.0);
        for l in &part.loops[1..] {
            assert!(!l.outer && l.signed_area() < 0.0);
        }
        assert_simple(&part);
        let area = expected_area(&model, &x);
        assert!(
            (part.area - area).abs() < 1e-9 * area,
            "area {} against {area}",
            part.area
        );
        let [w, h] = expected_box(&x, &settings);
        let bb = part.bounding_box;
        assert!(
            (bb[2] - bb[0] - w).abs() < 1e-9,
            "width {} against {w}",
            bb[2] - bb[0]
        );
        assert!(
            (bb[3] - bb[1] - h).abs() < 1e-9,
            "height {} against {h}",
            bb[3] - bb[1]
        );
        let measured = measured_hinges(&part);
        for (k, (t, l)) in measured.iter().enumerate() {
            // hinge b first in each quarter, then hinge d
            let (t_design, l_design) = if k % 2 == 0 {
                (x[2], x[0])
            } else {
                (x[7], x[5])
            };
            assert!(
                (t - t_design * 1e3).abs() < 1e-9,
                "thickness {t} against {}",
                t_design * 1e3
            );
            assert!(
                (l - l_design * 1e3).abs() < 1e-9,
                "length {l} against {}",
                l_design * 1e3
            );
        }
        assert_symmetric(&part, |p| [-p[0], p[1]]);
        assert_symmetric(&part, |p| [p[0], -p[1]]);
    }
    // most of Table 1's box gives a part with the default sizes
    assert!(built * 4 > tried, "{built} of {tried}");
}

#[test]
fn without_fillets_the_hinge_runs_from_face_to_face_and_a_warning_says_why_that_is_bad() {
    let settings = PartSettings {
        fillet_radius: 0.0,
        ..PartSettings::default()
    };
    let model = bridge(settings.clone());
    let x = table1_optimum();
    let part = build_part(&model, &x).unwrap().in_mm();
    assert!(part
        .loops
        .iter()
        .all(|l| l.vertices.iter().all(|v| v.bulge == 0.0)));
    for (t, l) in measured_hinges(&part) {
        assert!((t - 0.4).abs() < 1e-9 && (l - 1.96).abs() < 1e-9, "{t} {l}");
    }
    assert!((part.area - expected_area(&model, &x)).abs() < 1e-9 * part.area);
    assert!(part
        .warnings
        .iter()
        .any(|w| w.contains("fillet_radius is 0")));
}

#[test]
fn the_dxf_reads_back_as_the_same_loops_and_the_svg_is_xml_at_true_scale() {
    let model = bridge(PartSettings::default());
    let si = build_part(&model, &table1_optimum()).unwrap();
    let part = si.in_mm();
    let bytes = flexopt::part::dxf::to_bytes(&si).unwrap();
    let drawing = dxf::Drawing::load(&mut bytes.as_slice()).unwrap();
    assert_eq!(
        drawing.header.default_drawing_units,
        dxf::enums::Units::Millimeters
    );
    let mut polylines = Vec::new();
    let mut face_layers = Vec::new();
    for e in drawing.entities() {
        match &e.specific {
            dxf::entities::EntityType::LwPolyline(p) => {
                assert_eq!(e.common.layer, "OUTLINE");
                assert!(p.is_closed());
                polylines.push(p.vertices.clone());
            }
            dxf::entities::EntityType::Line(_) => face_layers.push(e.common.layer.clone()),
            // the plate's thickness, on a layer of its own
            dxf::entities::EntityType::Text(t) => {
                assert_eq!(e.common.layer, "PLATE");
                assert_eq!(t.value, format!("plate thickness {} mm", part.width));
            }
            other => panic!("unexpected entity {other:?}"),
        }
    }
    assert_eq!(polylines.len(), part.loops.len());
    for (l, p) in part.loops.iter().zip(&polylines) {
        assert_eq!(l.vertices.len(), p.len());
        for (v, w) in l.vertices.iter().zip(p) {
            assert!((v.x - w.x).abs() < 1e-9 && (v.y - w.y).abs() < 1e-9);
            assert!((v.bulge - w.bulge).abs() < 1e-9);
        }
    }
    for f in [
        "FACE_INPUT_LEFT",
        "FACE_INPUT_RIGHT",
        "FACE_OUTPUT_TOP",
        "FACE_CLAMP_BOTTOM",
    ] {
        assert!(face_layers.iter().any(|l| l == f), "{f} in {face_layers:?}");
    }

    let svg = flexopt::part::svg::document(&si).to_string();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    let view: Vec<f64> = root
        .attribute("viewBox")
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    let [x0, y0, x1, y1] = part.bounding_box;
    // the part and a 1 mm margin, y pointing down
    let want = [x0 - 1.0, -y1 - 1.0, x1 - x0 + 2.0, y1 - y0 + 2.0];
    for (v, w) in view.iter().zip(want) {
        assert!((v - w).abs() < 1e-9, "{view:?} against {want:?}");
    }
    assert_eq!(root.attribute("width").unwrap(), format!("{}mm", want[2]));
    let paths = root
        .descendants()
        .filter(|n| n.has_tag_name("path"))
        .count();
    assert_eq!(paths, 1);
}

/// The problems of the part of `x` with `settings`.
fn problems(settings: PartSettings, x: &[f64; 8]) -> Vec<String> {
    match build_part(&bridge(settings), x) {
        Ok(_) => Vec::new(),
        Err(e) => e.problems,
    }
}

fn assert_trips(settings: PartSettings, x: [f64; 8], words: &[&str]) {
    let found = problems(settings, &x);
    assert!(
        found.iter().any(|p| words.iter().all(|w| p.contains(w))),
        "{words:?} not in {found:#?}"
    );
}

#[test]
fn every_check_has_a_design_that_trips_it_and_names_what_collides_with_what() {
    let d = PartSettings::default;
    let x = table1_optimum();
    // walls thinner than the hinges they carry
    for key in ["link_thickness", "input_block_width", "output_block_height"] {
        let mut s = d();
        match key {
            "link_thickness" => s.link_thickness = 0.3 * MM,
            "input_block_width" => s.input_block_width = 0.3 * MM,
            _ => s.output_block_height = 0.3 * MM,
        }
        assert_trips(s, x, &[&format!("part.{key}"), "thinner than the hinges"]);
    }
    // blocks too small for the faces the hinges need
    assert_trips(
        PartSettings {
            input_block_height: 4.0 * MM,
            ..d()
        },
        x,
        &["part.input_block_height", "no room", "hinges b"],
    );
    assert_trips(
        PartSettings {
            output_block_height: 2.0 * MM,
            ..d()
        },
        x,
        &[
            "part.output_block_height",
            "does not hold the faces of hinges d",
        ],
    );
    let mut tilted = x;
    tilted[6] = 40.0 * DEG;
    assert_trips(
        PartSettings {
            output_block_width: 1.0 * MM,
            ..d()
        },
        tilted,
        &["part.output_block_width", "too narrow"],
    );
    // the actuator: too long for the pocket, too high for the gap between the output blocks
    assert_trips(
        PartSettings {
            actuator_length: Some(40.0 * MM),
            ..d()
        },
        x,
        &["pocket", "shorter than actuator.length (40 mm)"],
    );
    let mut inward = x;
    for i in [1, 4, 6] {
        inward[i] = -inward[i];
    }
    assert_trips(
        PartSettings {
            actuator_length: Some(20.0 * MM),
            actuator_height: Some(5.0 * MM),
            ..d()
        },
        inward,
        &["the actuator", "overlaps the upper output block"],
    );
    // arms through each other: the upper and lower left arms cross below the axis
    let mut steep = x;
    steep[4] = -40.0 * DEG;
    steep[3] = 15.0 * MM;
    assert_trips(d(), steep, &["(upper left)", "(lower left)", "overlap"]);
    // a link swung back over its own hinge (the link turns back along it): beyond the
    // corner beside its own face, into the hinge's band
    let mut folded = x;
    folded[0] = 3.0 * MM;
    folded[1] = 45.0 * DEG;
    folded[3] = 5.0 * MM;
    folded[4] = -125.0 * DEG;
    folded[6] = 0.0;
    let tall = PartSettings {
        input_block_height: 30.0 * MM,
        ..d()
    };
    assert_trips(
        tall,
        folded,
        &[
            "the middle link c (upper left) reaches within",
            "of hinge b (upper left)",
        ],
    );
    // a block cutting a hinge: long, inward arms bring the upper output block down beside
    // the lower hinges d
    let inward_long = [
        2.04 * MM,
        -23.72 * DEG,
        1.71 * MM,
        13.95 * MM,
        4.28 * DEG,
        13.83 * MM,
        -15.07 * DEG,
        0.785 * MM,
    ];
    assert_trips(
        d(),
        inward_long,
        &[
            "the upper output block reaches within",
            "of hinge d (lower left)",
        ],
    );
    // a slot narrower than the wire cuts
    assert_trips(
        PartSettings {
            min_slot: 3.0 * MM,
            ..d()
        },
        x,
        &["apart, less than the narrowest slot the wire cuts (3.0000 mm)"],
    );
}

#[test]
fn export_writes_the_five_files_and_refuses_a_part_that_cannot_be_made() {
    let dir = std::env::temp_dir().join(format!("flexopt-export-{}", std::process::id()));
    let out = flexopt_ok(&[
        "export",
        "problems/wei2017.toml",
        "--design",
        PRINTED,
        "--out",
        dir.to_str().unwrap(),
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    for f in ["part.dxf", "part.svg", "part.json", "part.png", "part.step"] {
        assert!(dir.join(f).is_file() && text.contains(f), "{f}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("part.json")).unwrap()).unwrap();
    assert_eq!(json["units"], "mm");
    assert_eq!(json["design"]["l2"], 1.96);
    assert_eq!(json["loops"].as_array().unwrap().len(), 2);
    assert_eq!(json["faces"].as_array().unwrap().len(), 4);
    std::fs::remove_dir_all(&dir).unwrap();

    // the printed design's mirror image puts the output blocks over the 5 mm actuator
    let out = flexopt(&[
        "export",
        "problems/wei2017.toml",
        "--design",
        "l2=1.96,delta2=-4.07,t2=0.4,l3=8.1,delta3=-4.01,l4=1.96,delta4=-4.07,t4=0.4",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(5));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("problems/wei2017.toml") && err.contains("overlaps the upper output block"),
        "{err}"
    );
    assert!(!dir.join("part.dxf").exists());
    let _ = std::fs::remove_dir_all(&dir);

    // a model without a part
    let out = flexopt(&[
        "export",
        "problems/prr3_frequency.toml",
        "--optimum",
        "results/prr3_frequency/optimum.json",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("has no part"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_optimum_of_a_run_is_reported_outward_and_exported_with_the_study() {
    let dir = std::env::temp_dir().join(format!("flexopt-run-part-{}", std::process::id()));
    flexopt_ok(&[
        "run",
        "problems/wei2017.toml",
        "--starts",
        "20",
        "--quiet",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let optimum: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("optimum.json")).unwrap()).unwrap();
    // the output blocks outward: span_y and the angles positive, as Table 1 prints them
    assert!(optimum["outputs"]["span_y"].as_f64().unwrap() > 0.0);
    assert!(optimum["design"]["delta3"].as_f64().unwrap() > 0.0);
    let manifest = std::fs::read_to_string(dir.join("manifest.json")).unwrap();
    for f in ["part.dxf", "part.svg", "part.json", "part.png", "part.step"] {
        assert!(dir.join(f).is_file() && manifest.contains(f), "{f}");
    }
    // the part file's design is the optimum's
    let part: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("part.json")).unwrap()).unwrap();
    assert_eq!(part["design"], optimum["design"]);
    std::fs::remove_dir_all(&dir).unwrap();
    let _ = Path::new("");
}
