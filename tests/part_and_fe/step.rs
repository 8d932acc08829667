//! `part.step`, the part as a solid (issue 28, item 5): read by OpenCASCADE (the
//! `cadquery-ocp` package in the virtual environment `.ci/run` makes at `.venv`), every
//! committed `part.step` and `refined_part.step` and a freshly exported one is one valid
//! closed solid whose volume is the outline's area times the plate's thickness and whose
//! bounding box is the part's, with a cylinder for every arc of the outline; and, read here,
//! the file's entities refer only to entities it defines, and every edge bounds two faces in
//! opposite senses.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::Command;

use crate::common::{flexopt_ok, random_design, rng, table1_optimum, venv_python, wei2017};
use flexopt::model::build_part;
use flexopt::part::step;
use flexopt::part::Part;

/// Table 1's printed design in the part's own units.
const PRINTED: &str = "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4";

/// The data section of a STEP file: each entity's text by its number.
fn entities(text: &str) -> BTreeMap<usize, String> {
    let data = text
        .split_once("\nDATA;\n")
        .and_then(|(_, rest)| rest.split_once("\nENDSEC;\nEND-ISO-10303-21;\n"))
        .map(|(data, _)| data)
        .expect("a DATA section and the end of the exchange structure");
    data.lines()
        .map(|line| {
            let (id, entity) = line.split_once('=').unwrap();
            let id = id.strip_prefix('#').unwrap().parse().unwrap();
            (id, entity.strip_suffix(';').unwrap().to_string())
        })
        .collect()
}

/// The entity numbers `entity` refers to.
fn references(entity: &str) -> Vec<usize> {
    entity
        .split('#')
        .skip(1)
        .map(|s| {
            let digits: String = s.chars().take_while(char::is_ascii_digit).collect();
            digits.parse().unwrap()
        })
        .collect()
}

/// The number of edges of the part's loops, and of its arcs.
fn edges_and_arcs(loops: &[serde_json::Value]) -> (usize, usize) {
    let vertices = loops.iter().flat_map(|l| l["vertices"].as_array().unwrap());
    let (edges, arcs) = vertices.fold((0, 0), |(e, a), v| {
        (e + 1, a + usize::from(v["bulge"].as_f64().unwrap() != 0.0))
    });
    (edges, arcs)
}

fn checked_structure(part: &Part) {
    let text = step::to_string(part, "wei2017");
    assert_eq!(
        text,
        step::to_string(part, "wei2017"),
        "the same bytes twice"
    );
    assert!(text.starts_with("ISO-10303-21;\nHEADER;\n"), "{text:.200}");
    assert!(
        text.contains("'2000-01-01T00:00:00'"),
        "the constant time stamp"
    );
    let e = entities(&text);
    // numbered 1..n, each reference to one of them
    assert_eq!(
        e.keys().copied().collect::<Vec<_>>(),
        (1..=e.len()).collect::<Vec<_>>()
    );
    for (id, entity) in &e {
        for r in references(entity) {
            assert!(e.contains_key(&r) && r != *id, "#{id}={entity}: #{r}");
        }
    }
    let named = |kind: &str| -> Vec<(usize, &String)> {
        e.iter()
            .filter(|(_, s)| s.starts_with(&format!("{kind}(")))
            .map(|(id, s)| (*id, s))
            .collect()
    };
    let json = serde_json::to_value(part.in_mm()).unwrap();
    let (edges, arcs) = edges_and_arcs(json["loops"].as_array().unwrap());
    let faces = named("ADVANCED_FACE");
    assert_eq!(faces.len(), 2 + edges);
    assert_eq!(named("CYLINDRICAL_SURFACE").len(), arcs);
    assert_eq!(
        named("CIRCLE").len(),
        2 * arcs,
        "the arcs of the bottom and the top"
    );
    assert_eq!(named("PLANE").len(), 2 + edges - arcs);
    assert_eq!(
        named("FACE_BOUND").len(),
        json["loops"].as_array().unwrap().len() * 2 - 2
    );
    // one solid of one closed shell of every face
    let shells = named("CLOSED_SHELL");
    assert_eq!(shells.len(), 1);
    let mut in_shell = references(shells[0].1);
    in_shell.sort();
    assert_eq!(in_shell, faces.iter().map(|f| f.0).collect::<Vec<_>>());
    assert_eq!(named("MANIFOLD_SOLID_BREP").len(), 1);
    // a closed shell: each edge bounds two faces, once in each sense
    let mut senses: BTreeMap<usize, Vec<bool>> = BTreeMap::new();
    for (_, oriented) in named("ORIENTED_EDGE") {
        let edge = references(oriented)[0];
        senses
            .entry(edge)
            .or_default()
            .push(oriented.ends_with(",.T.)"));
    }
    let curves = named("EDGE_CURVE");
    assert_eq!(senses.len(), curves.len());
    assert_eq!(curves.len(), 3 * edges, "bottom, top and vertical");
    for (edge, s) in &senses {
        let mut s = s.clone();
        s.sort();
        assert_eq!(s, [false, true], "#{edge}={}", e[edge]);
    }
}

#[test]
fn a_step_file_refers_to_its_own_entities_and_bounds_each_edge_by_two_faces() {
    let model = wei2017();
    let mut parts = vec![build_part(&model, &table1_optimum()).unwrap()];
    let mut r = rng(28);
    while parts.len() < 6 {
        if let Ok(p) = build_part(&model, &random_design(&mut r)) {
            parts.push(p);
        }
    }
    for p in &parts {
        checked_structure(p);
    }
}

/// Every committed `results/<run>/part.json` and `refined_part.json`, with the STEP file
/// that must stand beside it.
fn committed() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir("results")
        .unwrap()
        .flat_map(|run| std::fs::read_dir(run.unwrap().path()).into_iter().flatten())
        .map(|f| f.unwrap().path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n == "part.json" || n == "refined_part.json")
        })
        .collect();
    files.sort();
    files
}

#[test]
fn opencascade_reads_each_part_step_as_one_valid_closed_solid_of_the_parts_volume_and_box() {
    let Some(python) = venv_python("OCP", "the STEP check with OpenCASCADE") else {
        return;
    };
    let fresh = std::env::temp_dir().join(format!("flexopt-step-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&fresh);
    flexopt_ok(&[
        "export",
        "problems/wei2017.toml",
        "--design",
        PRINTED,
        "--out",
        fresh.to_str().unwrap(),
    ]);
    let manifest = std::fs::read_to_string(fresh.join("manifest.json")).unwrap();
    assert!(manifest.contains("\"part.step\""), "{manifest}");
    let mut jsons = committed();
    assert!(jsons.len() >= 6, "{jsons:?}");
    jsons.push(fresh.join("part.json"));
    let steps: Vec<String> = jsons
        .iter()
        .map(|j| {
            let s = j.with_extension("step");
            assert!(
                s.is_file(),
                "{} has no {} beside it",
                j.display(),
                s.display()
            );
            s.to_string_lossy().into_owned()
        })
        .collect();
    let out = crate::common::succeeds(
        Command::new(python)
            .arg("scripts/step_check.py")
            .args(&steps),
    );
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for (json, step) in jsons.iter().zip(&steps) {
        let r = &report[step.as_str()];
        assert_eq!(r["read"], true, "{step}");
        for (key, want) in [("solids", 1), ("shells", 1)] {
            assert_eq!(r[key], want, "{step}: {key}");
        }
        assert_eq!(r["valid"], true, "{step}: BRepCheck");
        assert_eq!(r["closed"], true, "{step}: the shell");
        let part: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap();
        let (width, area) = (
            part["width"].as_f64().unwrap(),
            part["area"].as_f64().unwrap(),
        );
        let volume = r["volume"].as_f64().unwrap();
        assert!(
            (volume - area * width).abs() <= 1e-6 * area * width,
            "{step}: volume {volume} mm^3 against {area} mm^2 x {width} mm"
        );
        let bb: [f64; 4] = serde_json::from_value(part["bounding_box"].clone()).unwrap();
        let want = [bb[0], bb[1], 0.0, bb[2], bb[3], width];
        for (k, w) in want.iter().enumerate() {
            let got = r["box"][k].as_f64().unwrap();
            assert!(
                (got - w).abs() <= 1e-6,
                "{step}: box[{k}] {got} against {w}"
            );
        }
        // no face merged or split on reading: a face for each edge, each arc a cylinder
        let (edges, arcs) = edges_and_arcs(part["loops"].as_array().unwrap());
        assert_eq!(r["faces"], 2 + edges, "{step}");
        assert_eq!(r["cylinders"], arcs, "{step}");
        assert_eq!(r["planes"], 2 + edges - arcs, "{step}");
    }
    std::fs::remove_dir_all(&fresh).unwrap();
}
