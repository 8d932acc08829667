//! `flexopt init --hinge KIND --material PRESET` (issue 28, item 4): for every kind and every
//! preset a file that runs as it is, with the kind's dimensions as its variables; unknown
//! choices and models that have no such section refused, naming the option.

use crate::common::{flexopt, flexopt_ok};
use crate::designer::temp_dir;

use flexopt::model::hinge::HingeKind;
use flexopt::model::material::Material;

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn every_kind_and_preset_gives_a_file_that_runs() {
    let dir = temp_dir("init-choices");
    for &kind in HingeKind::ALL {
        for &preset in Material::PRESETS {
            let tag = format!("{}_{preset}", kind.name());
            let file = dir.join(format!("{tag}.toml"));
            let f = file.to_str().unwrap();
            flexopt_ok(&["init", "--hinge", kind.name(), "--material", preset, f]);
            let text = std::fs::read_to_string(&file).unwrap();
            assert!(
                text.contains(&format!("kind = \"{}\"", kind.name())),
                "{tag}"
            );
            assert!(text.contains(&format!("preset = \"{preset}\"")), "{tag}");
            // the variables are the kind's dimensions at both hinges, within its bounds
            for (dim, &(lower, upper)) in kind.dimensions().iter().zip(kind.start_bounds()) {
                for number in ['2', '4'] {
                    let entry = format!("name = \"{}{number}\"", dim.stem);
                    let at = text
                        .find(&entry)
                        .unwrap_or_else(|| panic!("{tag}: {entry}"));
                    let bounds = format!("lower = {lower}\nupper = {upper}\n");
                    assert!(text[at..].contains(&bounds), "{tag}: {entry}");
                }
            }
            // outputs lists the file's parameters: those of its kind
            let listed = String::from_utf8_lossy(&flexopt_ok(&["outputs", f]).stdout).into_owned();
            for dim in kind.dimensions() {
                assert!(
                    listed.contains(&format!("  {}2 ", dim.stem)),
                    "{tag}: {listed}"
                );
            }
            let out_dir = dir.join(&tag);
            let out = flexopt(&[
                "run",
                f,
                "--starts",
                "4",
                "--quiet",
                "--out",
                out_dir.to_str().unwrap(),
            ]);
            // a study that ran: a design found (0) or none feasible (3), never refused
            assert!(
                matches!(out.status.code(), Some(0 | 3)),
                "{tag}: {:?} {}",
                out.status.code(),
                stderr(&out)
            );
            assert!(out_dir.join("optimum.json").is_file(), "{tag}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_guide_states_each_kinds_starting_bounds() {
    let guide = std::fs::read_to_string("docs/guide/src/commands.md").unwrap();
    for &kind in HingeKind::ALL {
        let row = guide
            .lines()
            .find(|l| l.starts_with(&format!("| {} | ", kind.name())))
            .unwrap_or_else(|| panic!("commands.md: no row for {}", kind.name()));
        for (dim, (lower, upper)) in kind.dimensions().iter().zip(kind.start_bounds()) {
            let bounds = format!("`{}` {lower} .. {upper}", dim.stem);
            assert!(row.contains(&bounds), "commands.md: {row} lacks {bounds}");
        }
    }
}

#[test]
fn unknown_kinds_and_presets_are_refused_with_the_valid_names() {
    let dir = temp_dir("init-unknown");
    let file = dir.join("never.toml");
    let f = file.to_str().unwrap();
    for (option, names) in [
        ("--hinge", HingeKind::NAMES),
        ("--material", Material::PRESETS),
    ] {
        let out = flexopt(&["init", option, "titanium-notch", f]);
        assert_eq!(out.status.code(), Some(2), "{option}");
        let message = stderr(&out);
        assert!(
            message.contains(option) && message.contains("titanium-notch"),
            "{message}"
        );
        for name in names {
            assert!(
                message.contains(name),
                "{option}: {name} not listed: {message}"
            );
        }
        assert!(!file.exists(), "{option}");
    }
    // models without hinges or a material take neither
    for (option, value, section) in [
        ("--hinge", "circular", "hinges"),
        ("--material", "ti6al4v", "[material]"),
    ] {
        let out = flexopt(&["init", "--model", "prr3", option, value, f]);
        assert_eq!(out.status.code(), Some(2), "{option}");
        let message = stderr(&out);
        assert!(
            message.contains(option) && message.contains("\"prr3\"") && message.contains(section),
            "{message}"
        );
        assert!(message.contains("bridge"), "{message}");
        assert!(!file.exists(), "{option}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
