//! The journaled move of a set into its folder, and its undoing.
//!
//! Every step is a rename, so each name stands in exactly one place at any moment: in the
//! folder, in the staging folder (a new entry not yet placed) or in the staging folder's
//! `.aside` (an earlier one moved out of the way). The journal says which names go aside and
//! which are placed; from any point a kill can leave, the move is rolled forward (each step
//! done only where it is not yet) or back (the placed entries returned to the staging folder,
//! everything aside put back). The commit point is the rename of the new manifest into place.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{exists, fail, is_entry, read_manifest, Entry, Manifest, JOURNAL, MANIFEST};
use crate::report::WriteError;

/// Where a move puts what it takes out of the folder, inside its staging folder.
pub(super) const ASIDE: &str = ".aside";

/// The journal of a move.
#[derive(Debug, Serialize, Deserialize)]
pub(super) struct Journal {
    /// The folder's entries moved aside: the earlier set's that go, and whatever stands
    /// where a new entry goes (the manifest in place always goes first).
    aside: Vec<String>,
    /// The staged entries renamed into place, in order.
    placed: Vec<String>,
    /// The set in place once the move is done (also staged as `manifest.json`).
    #[serde(skip)]
    pub manifest: Manifest,
}

/// The move of the staged entries `staged` into `dir`: the new set (with the earlier set's
/// entries that are still there, when `keep_earlier`) and what goes aside. The caller holds
/// the folder's lock.
pub(super) fn plan(dir: &Path, staged: &[Entry], keep_earlier: bool) -> Journal {
    let earlier: Vec<Entry> = read_manifest(&dir.join(MANIFEST))
        .map(|m| m.files)
        .unwrap_or_default()
        .into_iter()
        .filter(|e| super::plain(&e.name))
        .collect();
    let mut files = Vec::new();
    let mut aside = Vec::new();
    for e in &earlier {
        let new = staged.iter().find(|s| s.name == e.name);
        if files.iter().any(|f: &Entry| f.name == e.name) {
            continue;
        }
        match new {
            Some(n) if keep_earlier => files.push(n.clone()),
            Some(_) => {}
            None if !is_entry(&dir.join(&e.name), e.folder) => {}
            None if keep_earlier => files.push(e.clone()),
            None => aside.push(e.name.clone()),
        }
    }
    for s in staged {
        if !files.iter().any(|f| f.name == s.name) {
            files.push(s.clone());
        }
        let path = dir.join(&s.name);
        let Ok(meta) = std::fs::symlink_metadata(&path) else {
            continue;
        };
        // a file takes the place of any file; a folder only that of a set's folder; and
        // whatever the earlier set listed goes
        let listed = earlier
            .iter()
            .any(|e| e.name == s.name && is_entry(&path, e.folder));
        let replaceable = if s.folder {
            is_entry(&path, true)
        } else {
            !meta.is_dir()
        };
        if listed || replaceable {
            aside.push(s.name.clone());
        }
    }
    Journal {
        aside,
        placed: staged.iter().map(|s| s.name.clone()).collect(),
        manifest: Manifest { files },
    }
}

pub(super) fn read_journal(staging: &Path) -> Result<Journal, WriteError> {
    let path = staging.join(JOURNAL);
    let text = std::fs::read_to_string(&path).map_err(|e| fail(&path, &e))?;
    serde_json::from_str(&text).map_err(|e| fail(&path, &e))
}

fn rename(from: &Path, to: &Path) -> Result<(), WriteError> {
    std::fs::rename(from, to).map_err(|e| fail(to, &e))
}

/// Finishes the move journaled in `staging`, or undoes it where it cannot be finished, and
/// then removes the journal; the folder then holds the new set (returned: the paths in
/// place), or its earlier one (with the error that stopped the move). Where neither can be
/// done, the journal stays for the next command to try again. The caller holds the lock.
pub(super) fn finish(staging: &Path, dir: &Path) -> Result<Vec<PathBuf>, WriteError> {
    let forward = roll_forward(staging, dir);
    let outcome = match forward {
        Ok(placed) => Ok(placed),
        Err(e) => match roll_back(staging, dir) {
            Ok(()) => Err(WriteError {
                message: format!(
                    "{}; nothing was written: the folder holds its earlier files again",
                    e.message
                ),
                ..e
            }),
            Err(back) => {
                return Err(WriteError {
                    message: format!(
                        "{}; putting the earlier files back failed too ({back}): the next \
                         flexopt command into this folder tries again",
                        e.message
                    ),
                    ..e
                })
            }
        },
    };
    let _ = std::fs::remove_file(staging.join(JOURNAL));
    outcome
}

/// Does the steps of the move that are not yet done; returns the paths in place.
fn roll_forward(staging: &Path, dir: &Path) -> Result<Vec<PathBuf>, WriteError> {
    let journal = read_journal(staging)?;
    // without the staged manifest the move is done: the manifest in place is the new one
    if exists(&staging.join(MANIFEST)) {
        for (from, to) in steps_left(staging, dir, &journal)? {
            rename(&from, &to)?;
        }
    }
    let mut placed: Vec<PathBuf> = journal
        .placed
        .iter()
        .flat_map(|name| paths_in(&dir.join(name)))
        .collect();
    placed.push(dir.join(MANIFEST));
    Ok(placed)
}

/// The renames left of the move journaled in `staging`, in order: each is done once, so a
/// step is left while its source still stands and (for a move aside) its target does not.
pub(super) fn steps_left(
    staging: &Path,
    dir: &Path,
    journal: &Journal,
) -> Result<Vec<(PathBuf, PathBuf)>, WriteError> {
    let aside = staging.join(ASIDE);
    std::fs::create_dir_all(&aside).map_err(|e| fail(&aside, &e))?;
    let mut steps = Vec::new();
    // the manifest in place goes first: a folder in the middle of a move has none
    for name in std::iter::once(MANIFEST).chain(journal.aside.iter().map(String::as_str)) {
        let (from, to) = (dir.join(name), aside.join(name));
        if exists(&from) && !exists(&to) {
            steps.push((from, to));
        }
    }
    for name in &journal.placed {
        let (staged, target) = (staging.join(name), dir.join(name));
        if exists(&staged) {
            steps.push((staged, target));
        } else if !exists(&target) {
            return Err(fail(&staged, &"a file of the set is missing"));
        }
    }
    steps.push((staging.join(MANIFEST), dir.join(MANIFEST)));
    Ok(steps)
}

/// Undoes the steps of the move that were done: the placed entries back into the staging
/// folder, everything aside back into the folder.
pub(super) fn roll_back(staging: &Path, dir: &Path) -> Result<(), WriteError> {
    let journal = read_journal(staging)?;
    if !exists(&staging.join(MANIFEST)) {
        return Err(fail(dir, &"the move was done: the new set is in place"));
    }
    for name in &journal.placed {
        let (staged, placed) = (staging.join(name), dir.join(name));
        // placed only after whatever stood there went aside: what stands there is the new one
        if !exists(&staged) && exists(&placed) {
            rename(&placed, &staged)?;
        }
    }
    let aside = staging.join(ASIDE);
    let Ok(entries) = std::fs::read_dir(&aside) else {
        return Ok(());
    };
    for entry in entries {
        let entry = entry.map_err(|e| fail(&aside, &e))?;
        let target = dir.join(entry.file_name());
        if exists(&target) {
            return Err(fail(
                &target,
                &"something new stands where an earlier file was",
            ));
        }
        rename(&entry.path(), &target)?;
    }
    Ok(())
}

/// The paths of an entry in place: a file's, or a folder's files and its manifest.
fn paths_in(path: &Path) -> Vec<PathBuf> {
    if !path.is_dir() {
        return vec![path.to_path_buf()];
    }
    let own = read_manifest(&path.join(MANIFEST)).unwrap_or_default();
    let mut paths: Vec<PathBuf> = own
        .files
        .iter()
        .flat_map(|e| paths_in(&path.join(&e.name)))
        .collect();
    paths.push(path.join(MANIFEST));
    paths
}
