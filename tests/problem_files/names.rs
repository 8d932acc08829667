//! Issue 50, cases 1 and 2: a name from a problem file never becomes a path out of the output
//! folder, and a name with a control character is refused where it is read, its key named and
//! the character escaped in the message.

use std::path::PathBuf;

use flexopt::report::folder::{check_names, OutputSet};

use crate::common::flexopt;

const LEVER: &str = "problems/lever_network.toml";

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexopt-names-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The lever network with `from` replaced by `to` (once; it must occur), written into `dir`.
fn lever_with(dir: &std::path::Path, from: &str, to: &str) -> PathBuf {
    let text = std::fs::read_to_string(LEVER).unwrap();
    assert!(text.contains(from), "{from:?} not in {LEVER}");
    let file = dir.join("lever.toml");
    // the body's name where the hinges and ports name it too
    let text = match from {
        "name = \"lever\"" => text.replace("\"lever\"", to.trim_start_matches("name = ")),
        _ => text.replacen(from, to, 1),
    };
    std::fs::write(&file, text).unwrap();
    file
}

/// Case 2: a body, hinge, port or measure named with a control character, a path, a space or
/// nothing is refused at reading (exit 2) naming its key; the message shows the character
/// escaped, never raw.
#[test]
fn names_that_are_no_names_are_refused_at_reading() {
    let dir = scratch("control");
    let measure = "[[network.measures]]\nname = \"m\"\ndimension = \"length\"\nvalue = \"a\"\n\n\
                   [network.input]";
    let places = [
        ("name = \"pivot\"", "network.hinges[0].name"),
        ("name = \"lever\"", "network.bodies[0].name"),
        ("name = \"tip\"", "network.outputs[0].name"),
        ("[network.input]", "network.measures[0].name"),
    ];
    let bad = [
        r"piv\u001b[31mot\u0000",
        "/../../../../../escaped",
        "two words",
        "",
        "9lives",
    ];
    for (from, key) in places {
        for name in bad {
            let to = if from.starts_with('[') {
                measure.replacen("name = \"m\"", &format!("name = \"{name}\""), 1)
            } else {
                format!("name = \"{name}\"")
            };
            let file = lever_with(&dir, from, &to);
            for command in [
                &["outputs"][..],
                &["eval", "--format", "table", "--design", "r=1,t=0.5,a=8"],
            ] {
                let mut args = command.to_vec();
                args.insert(1, file.to_str().unwrap());
                let o = flexopt(&args);
                let stderr = String::from_utf8_lossy(&o.stderr);
                assert_eq!(o.status.code(), Some(2), "{key} {name:?}: {stderr}");
                assert!(
                    stderr.contains("lever.toml")
                        && stderr.contains(key)
                        && stderr.contains("a name is a letter"),
                    "{key} {name:?}: {stderr}"
                );
                assert!(
                    !stderr.chars().any(|c| c.is_control() && c != '\n'),
                    "{stderr:?}"
                );
                if name.starts_with("piv") {
                    assert!(
                        stderr.contains(r"\u{1b}") && stderr.contains(r"\0"),
                        "{stderr}"
                    );
                }
                assert!(o.stdout.is_empty(), "{key} {name:?}");
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Case 1: a measure named as a path, constrained, so that `tolerance` would draw its
/// histogram: refused at reading, and nothing written in the output folder or beyond it.
#[test]
fn no_name_leads_out_of_the_output_folder() {
    let dir = scratch("escape");
    let name = "/../../../../../escaped";
    let text = std::fs::read_to_string(LEVER).unwrap().replacen(
        "[network.input]",
        &format!(
            "[[network.measures]]\nname = \"{name}\"\ndimension = \"length\"\nvalue = \"a\"\n\n\
             [network.input]"
        ),
        1,
    ) + &format!("\n[[constraints]]\noutput = \"{name}\"\nunit = \"mm\"\nlower = 1\n");
    let file = dir.join("lever.toml");
    std::fs::write(&file, text).unwrap();
    let out = dir.join("a").join("b").join("out");
    let o = flexopt(&[
        "tolerance",
        file.to_str().unwrap(),
        "--design",
        "r=1,t=0.5,a=8,arm=40",
        "--samples",
        "20",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("network.measures[0].name"), "{stderr}");
    assert!(!out.exists());
    let escaped: Vec<_> = walk(&dir)
        .into_iter()
        .filter(|p| p.to_string_lossy().contains("escaped"))
        .collect();
    assert!(escaped.is_empty(), "{escaped:?}");
    assert!(!std::path::Path::new("/escaped.png").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Case 1 beneath the reading: the writers check every file name before anything is
/// written, and a set's staging path never leads out of its folder, whatever the name.
#[test]
fn file_names_are_checked_before_anything_is_written() {
    let dir = scratch("writers").join("out");
    for names in [
        &["tolerance.json", "histogram_/../../x.png"][..],
        &["a.png", "a.png"],
        &["../x.json"],
        &[".hidden"],
        &["manifest.json"],
    ] {
        let e = check_names(&dir, names).unwrap_err();
        assert!(e.to_string().contains("nothing was written"), "{e}");
        assert!(!dir.exists(), "{names:?} made the folder");
    }
    check_names(&dir, &["tolerance.json", "histogram_k_in.png"]).unwrap();
    let set = OutputSet::begin(&dir).unwrap();
    for name in ["../../x.png", "/etc/passwd", "..", "a/../../b"] {
        let path = set.path(name);
        let staging = set.path("plain");
        assert_eq!(path.parent(), staging.parent(), "{name}: {path:?}");
    }
    let _ = std::fs::remove_dir_all(dir.parent().unwrap());
}

/// Every file below `dir`.
fn walk(dir: &std::path::Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let p = entry.path();
        if p.is_dir() {
            found.extend(walk(&p));
        }
        found.push(p);
    }
    found
}
