//! The DXF files open clean in an independent reader: ezdxf (Python, in the virtual
//! environment `.ci/run` makes at `.venv`) audits every committed `part.dxf` and
//! `refined_part.dxf` and finds nothing to fix; the header's extents are the outline's as
//! ezdxf computes them, and the plate's thickness is stated (`$THICKNESS` and a TEXT on
//! layer `PLATE`). Without the environment the test fails under CI (the variable `CI` set)
//! and says so elsewhere.

use std::path::Path;
use std::process::Command;

#[test]
fn every_committed_dxf_opens_with_nothing_to_fix_its_extents_and_thickness_set() {
    let Some(python) = crate::common::venv_python("ezdxf", "the DXF audit") else {
        return;
    };
    // every results/<run>/*.dxf
    let mut files: Vec<String> = std::fs::read_dir("results")
        .unwrap()
        .flat_map(|run| std::fs::read_dir(run.unwrap().path()).into_iter().flatten())
        .map(|f| f.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "dxf"))
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert!(files.len() >= 6, "{files:?}");
    let out = crate::common::succeeds(
        Command::new(python)
            .arg("scripts/dxf_audit.py")
            .args(&files),
    );
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for file in &files {
        let r = &report[file.as_str()];
        assert_eq!(r["errors"], serde_json::json!([]), "{file}");
        assert_eq!(r["fixes"], serde_json::json!([]), "{file}");
        for (header, outline) in [("extmin", "outline_min"), ("extmax", "outline_max")] {
            for k in 0..2 {
                let (a, b) = (
                    r[header][k].as_f64().unwrap(),
                    r[outline][k].as_f64().unwrap(),
                );
                assert!(
                    (a - b).abs() < 1e-9,
                    "{file} {header}[{k}]: {a} against {b}"
                );
            }
        }
        // the part's width, as part.json beside it states it (mm)
        let json = Path::new(file).with_extension("json");
        let part: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        let width = part["width"].as_f64().unwrap();
        assert_eq!(r["thickness"].as_f64().unwrap(), width, "{file}");
        let layers = r["layers"].as_array().unwrap();
        assert!(layers.iter().any(|l| l == "PLATE"), "{file}");
        let texts = r["texts"].as_array().unwrap();
        assert!(
            texts
                .iter()
                .any(|t| t.as_str().unwrap().starts_with("plate thickness")),
            "{file}: {texts:?}"
        );
    }
}
