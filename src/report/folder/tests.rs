use std::collections::BTreeMap;

use super::moves::{read_journal, steps_left};
use super::*;

/// A folder of its own for a test.
fn fresh(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexopt-folder-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Every file under `dir`, hidden ones too, with its text: two folders with equal listings
/// hold the same files and nothing else.
fn listing(dir: &Path) -> BTreeMap<String, String> {
    walkdir::WalkDir::new(dir)
        .min_depth(1)
        .into_iter()
        .map(|entry| {
            let path = entry.unwrap().into_path();
            let rel = path.strip_prefix(dir).unwrap().display().to_string();
            match std::fs::read_to_string(&path) {
                Ok(text) => (rel, text),
                Err(_) => (format!("{rel}/"), String::new()),
            }
        })
        .collect()
}

/// Writes the files `(name, text)` through `set`.
fn write(set: &OutputSet, files: &[(&str, &str)]) {
    for (name, text) in files {
        let path = set.path(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
}

/// The earlier set: two files, one that the new set drops, and a folder that is a set of
/// its own; beside it a file of the user's and an unlisted file at a name the new set takes.
fn earlier(dir: &Path) {
    let set = OutputSet::begin(dir).unwrap();
    write(
        &set,
        &[
            ("a.txt", "old a"),
            ("b.txt", "old b"),
            ("dropped.txt", "old only"),
            ("sub/x.txt", "old x"),
        ],
    );
    set.seal_folder("sub", &["x.txt"]).unwrap();
    set.commit(&["a.txt", "b.txt", "dropped.txt", "sub"])
        .unwrap();
    std::fs::write(dir.join("notes.txt"), "the user's").unwrap();
    std::fs::write(dir.join("c.txt"), "unlisted, in the new set's way").unwrap();
}

const NEW: [(&str, &str); 3] = [
    ("a.txt", "new a"),
    ("b.txt", "new b, longer"),
    ("c.txt", "new c"),
];

/// The new set staged by a command that is gone (a process id that cannot exist), its
/// move journaled and not begun.
fn journaled(dir: &Path) -> PathBuf {
    let staging = dir.join(format!("{STAGING}4000000000-1"));
    std::fs::create_dir(&staging).unwrap();
    for (name, text) in NEW {
        std::fs::write(staging.join(name), text).unwrap();
    }
    let names: Vec<&str> = NEW.iter().map(|f| f.0).collect();
    let staged = entries(&staging, &names).unwrap();
    journal_move(dir, &staging, &staged, false).unwrap();
    staging
}

/// A command killed after any step of its move leaves a folder that the next command rolls
/// forward to the new set whole; a move that fails after any step is undone to the earlier
/// set whole. Either way the user's files stay and nothing of the move is left.
#[test]
fn a_move_cut_after_any_step_is_finished_or_undone_whole() {
    let dir = fresh("steps");
    earlier(&dir);
    let before = listing(&dir);
    assert!(before.contains_key("sub/manifest.json"), "{before:?}");
    // the new set as an uncut move leaves it
    let whole = fresh("steps-whole");
    earlier(&whole);
    let set = OutputSet::begin(&whole).unwrap();
    write(&set, &NEW);
    set.commit(&["a.txt", "b.txt", "c.txt"]).unwrap();
    let after = listing(&whole);
    let names: Vec<&String> = after.keys().collect();
    assert_eq!(
        names,
        ["a.txt", "b.txt", "c.txt", "manifest.json", "notes.txt"],
        "the dropped file and the folder are gone, the user's file stays"
    );
    assert_eq!(after["c.txt"], "new c");

    let staging = journaled(&dir);
    let steps = steps_left(&staging, &dir, &read_journal(&staging).unwrap()).unwrap();
    // the manifest, the earlier set's two entries that go, the three at new names, the
    // three new files and the new manifest
    assert_eq!(steps.len(), 10, "{steps:?}");
    std::fs::remove_dir_all(&staging).unwrap();
    for k in 0..=steps.len() {
        for undo in [false, true] {
            if undo && k == steps.len() {
                continue;
            }
            let _ = std::fs::remove_dir_all(&dir);
            earlier(&dir);
            let staging = journaled(&dir);
            let steps = steps_left(&staging, &dir, &read_journal(&staging).unwrap()).unwrap();
            for (from, to) in &steps[..k] {
                std::fs::rename(from, to).unwrap();
            }
            assert_eq!(dir.join(MANIFEST).exists(), k == 0 || k == steps.len());
            if undo {
                roll_back_and_clean(&staging, &dir);
                assert_eq!(listing(&dir), before, "undone after {k} steps");
            } else {
                recover(&dir).unwrap();
                assert_eq!(listing(&dir), after, "rolled forward after {k} steps");
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
    std::fs::remove_dir_all(&whole).unwrap();
}

fn roll_back_and_clean(staging: &Path, dir: &Path) {
    moves::roll_back(staging, dir).unwrap();
    std::fs::remove_dir_all(staging).unwrap();
}

/// A folder standing where a file of the new set goes stops the move after the earlier
/// set's files were moved aside and some new ones placed: the move is undone, the folder
/// holds its earlier set whole, and the user's folder is untouched.
#[test]
fn a_failed_move_puts_the_earlier_set_back() {
    let dir = fresh("failed");
    earlier(&dir);
    std::fs::remove_file(dir.join("c.txt")).unwrap();
    std::fs::create_dir(dir.join("c.txt")).unwrap();
    std::fs::write(dir.join("c.txt/mine"), "the user's").unwrap();
    let before = listing(&dir);
    let set = OutputSet::begin(&dir).unwrap();
    write(&set, &NEW);
    let e = set.commit(&["a.txt", "b.txt", "c.txt"]).unwrap_err();
    assert_eq!(e.path, dir.join("c.txt"));
    assert!(e.message.contains("holds its earlier files again"), "{e}");
    assert_eq!(listing(&dir), before);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A set added to the folder's keeps the earlier entries it does not replace, listed in
/// their order, and lists its own after them.
#[test]
fn an_added_set_keeps_the_earlier_entries() {
    let dir = fresh("added");
    earlier(&dir);
    let set = OutputSet::begin(&dir).unwrap();
    write(&set, &[("b.txt", "newer b"), ("d.txt", "new d")]);
    let placed = set.commit_added(&["b.txt", "d.txt"]).unwrap();
    assert_eq!(
        placed,
        [dir.join("b.txt"), dir.join("d.txt"), dir.join(MANIFEST)]
    );
    let manifest = read_manifest(&dir.join(MANIFEST)).unwrap();
    let names: Vec<&str> = manifest.files.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(names, ["a.txt", "b.txt", "dropped.txt", "sub", "d.txt"]);
    assert_eq!(std::fs::read_to_string(dir.join("a.txt")).unwrap(), "old a");
    assert_eq!(manifest.files[1].bytes, Some(7));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A folder of the earlier set that the user put a file of their own into is no longer
/// the set's alone: the new set leaves it where it is, unlisted, with its files.
#[test]
fn a_folder_holding_the_users_files_is_left() {
    let dir = fresh("users");
    earlier(&dir);
    std::fs::write(dir.join("sub/mine.txt"), "the user's").unwrap();
    let set = OutputSet::begin(&dir).unwrap();
    write(&set, &NEW);
    set.commit(&["a.txt", "b.txt", "c.txt"]).unwrap();
    let names: Vec<String> = listing(&dir).into_keys().collect();
    assert_eq!(
        names,
        [
            "a.txt",
            "b.txt",
            "c.txt",
            "manifest.json",
            "notes.txt",
            "sub/",
            "sub/manifest.json",
            "sub/mine.txt",
            "sub/x.txt"
        ]
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A manifest that names something outside the folder, or a hidden or the manifest's own
/// name, has those entries ignored: nothing outside the set's plain names is ever removed.
#[test]
fn only_plain_names_of_a_manifest_are_removed() {
    let dir = fresh("plain");
    let outside = fresh("plain-outside");
    std::fs::write(outside.join("keep.txt"), "elsewhere").unwrap();
    std::fs::write(dir.join(".hidden"), "hidden").unwrap();
    let hostile = format!(
        r#"{{"files": [{{"name": "../flexopt-folder-{}-plain-outside/keep.txt"}},
            {{"name": ".hidden"}}, {{"name": "manifest.json"}}, {{"name": ""}}]}}"#,
        std::process::id()
    );
    std::fs::write(dir.join(MANIFEST), hostile).unwrap();
    let set = OutputSet::begin(&dir).unwrap();
    write(&set, &[("a.txt", "a")]);
    set.commit(&["a.txt"]).unwrap();
    assert!(outside.join("keep.txt").is_file());
    assert!(dir.join(".hidden").is_file());
    let names: Vec<String> = listing(&dir).into_keys().collect();
    assert_eq!(names, [".hidden", "a.txt", "manifest.json"]);
    std::fs::remove_dir_all(&dir).unwrap();
    std::fs::remove_dir_all(&outside).unwrap();
}
