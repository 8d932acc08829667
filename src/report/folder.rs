//! A run's files as one set: written under a folder unique to the run, moved into place
//! under a lock, and listed last in `manifest.json` with each file's size and hash, so that a
//! folder never holds two runs' files without saying so.
//!
//! - Two runs into one folder at once: the second to finish its files finds the lock held by
//!   a live run and gives up with a message; the folder keeps the first run's whole set.
//! - The move into place is journaled: the set's manifest is written in the staging folder
//!   first, the manifest in place is removed, the files are renamed one by one and the manifest
//!   is renamed last. A folder with `manifest.json` therefore holds exactly the set it lists; a
//!   folder without one is a set cut short.
//! - A run killed before its move leaves only its staging folder, which the next run into the
//!   folder removes; a run killed during its move leaves a staging folder with a manifest, which
//!   the next run (or [`recover`]) rolls forward, so the folder again holds one whole set.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{write_json, WriteError};

/// The lock file of a folder.
const LOCK: &str = ".flexopt.lock";
/// Staging folders start with this, followed by the owner's process id.
const STAGING: &str = ".run-";
/// The manifest, in place and (as the journal of a move) in a staging folder.
const MANIFEST: &str = "manifest.json";

/// A set of files being written for one run.
pub struct OutputSet {
    dir: PathBuf,
    staging: PathBuf,
}

/// `manifest.json`.
#[derive(Debug, Serialize, Deserialize)]
struct Manifest {
    /// The files of the set, with their size in bytes and FNV-1a 64-bit hash (hex).
    files: Vec<ManifestEntry>,
}

#[derive(Debug, Serialize, Deserialize)]
struct ManifestEntry {
    name: String,
    bytes: u64,
    fnv1a64: String,
}

fn fail(path: &Path, e: &dyn std::fmt::Display) -> WriteError {
    WriteError {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// Whether the process `pid` still runs (Linux: its `/proc` entry).
fn alive(pid: u32) -> bool {
    pid == std::process::id() || Path::new(&format!("/proc/{pid}")).exists()
}

/// The process id a staging folder or lock names, if it names one.
fn owner(name: &str) -> Option<u32> {
    name.strip_prefix(STAGING)?.split('-').next()?.parse().ok()
}

impl OutputSet {
    /// Starts a set for `dir`, after [`recover`] has finished or removed what runs that are
    /// gone left behind.
    pub fn begin(dir: &Path) -> Result<Self, WriteError> {
        std::fs::create_dir_all(dir).map_err(|e| fail(dir, &e))?;
        recover(dir)?;
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos());
        let staging = dir.join(format!("{STAGING}{}-{nanos}", std::process::id()));
        std::fs::create_dir(&staging).map_err(|e| fail(&staging, &e))?;
        Ok(OutputSet {
            dir: dir.to_path_buf(),
            staging,
        })
    }

    /// Where the file `name` of the set is written.
    pub fn path(&self, name: &str) -> PathBuf {
        self.staging.join(name)
    }

    /// Moves the set's files `names` into place under the folder's lock and writes the
    /// manifest; returns the paths in place. A failure before the move leaves the folder as it
    /// was; one during the move (a full disk) leaves it without `manifest.json`.
    pub fn commit(self, names: &[&str]) -> Result<Vec<PathBuf>, WriteError> {
        let result = self.commit_locked(names);
        let _ = std::fs::remove_dir_all(&self.staging);
        result
    }

    fn commit_locked(&self, names: &[&str]) -> Result<Vec<PathBuf>, WriteError> {
        let mut files = Vec::new();
        for name in names {
            let staged = self.path(name);
            let bytes = std::fs::read(&staged).map_err(|e| fail(&staged, &e))?;
            files.push(ManifestEntry {
                name: name.to_string(),
                bytes: bytes.len() as u64,
                fnv1a64: format!("{:016x}", fnv1a64(&bytes)),
            });
        }
        let lock = Lock::take(&self.dir)?;
        // the journal: from here on, a kill is rolled forward by the next run
        write_json(&self.path(MANIFEST), &Manifest { files })?;
        let placed = roll_forward(&self.staging, &self.dir);
        drop(lock);
        placed
    }
}

/// Finishes the moves of runs that were killed while moving their files, and removes the
/// staging folders, and temporary files over an hour old, of runs that are gone.
pub fn recover(dir: &Path) -> Result<(), WriteError> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let path = entry.path();
        match owner(&name) {
            Some(pid) if !alive(pid) => {
                if path.join(MANIFEST).is_file() {
                    let lock = Lock::take(dir)?;
                    // another run may have finished it while this one waited for the lock
                    if path.join(MANIFEST).is_file() {
                        roll_forward(&path, dir)?;
                    }
                    drop(lock);
                }
                let _ = std::fs::remove_dir_all(&path);
            }
            Some(_) => {}
            // a temporary file outside a staging folder belongs to a sweep or a front, which
            // may be writing it now: removed only when an hour old
            None => {
                let old = entry
                    .metadata()
                    .and_then(|m| m.modified())
                    .ok()
                    .and_then(|t| t.elapsed().ok())
                    .is_some_and(|age| age.as_secs() > 3600);
                if name.contains(".partial") && old {
                    let _ = std::fs::remove_file(&path);
                }
            }
        }
    }
    Ok(())
}

/// Moves the files the journal `staging/manifest.json` lists into `dir`, then the manifest
/// itself. Files already moved (by a run killed halfway) are skipped; the caller holds the lock.
fn roll_forward(staging: &Path, dir: &Path) -> Result<Vec<PathBuf>, WriteError> {
    let journal = staging.join(MANIFEST);
    let text = std::fs::read_to_string(&journal).map_err(|e| fail(&journal, &e))?;
    let manifest: Manifest = serde_json::from_str(&text).map_err(|e| fail(&journal, &e))?;
    let in_place = dir.join(MANIFEST);
    match std::fs::remove_file(&in_place) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(fail(&in_place, &e)),
        _ => {}
    }
    let mut placed = Vec::new();
    for file in &manifest.files {
        let (staged, target) = (staging.join(&file.name), dir.join(&file.name));
        if staged.exists() {
            std::fs::rename(&staged, &target).map_err(|e| fail(&target, &e))?;
        } else if !target.exists() {
            return Err(fail(&staged, &"a file of the set is missing"));
        }
        placed.push(target);
    }
    std::fs::rename(&journal, &in_place).map_err(|e| fail(&in_place, &e))?;
    placed.push(in_place);
    Ok(placed)
}

/// The folder's lock, held while a set moves into place; released when dropped.
struct Lock(PathBuf);

impl Lock {
    fn take(dir: &Path) -> Result<Lock, WriteError> {
        let lock = dir.join(LOCK);
        let mut tries = 0;
        loop {
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&lock)
            {
                Ok(mut f) => {
                    use std::io::Write;
                    let _ = write!(f, "{}", std::process::id());
                    return Ok(Lock(lock));
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && tries < 50 => {
                    tries += 1;
                    let holder = std::fs::read_to_string(&lock)
                        .ok()
                        .and_then(|s| s.trim().parse::<u32>().ok());
                    match holder {
                        Some(pid) if alive(pid) => {
                            return Err(fail(
                                dir,
                                &format!(
                                    "another flexopt run (process {pid}) is putting its results \
                                     in this folder at the same moment; this run's results were \
                                     not written (run it again, or give it its own --out)"
                                ),
                            ))
                        }
                        // a lock of a run that is gone, or one being written this instant
                        _ => {
                            std::thread::sleep(std::time::Duration::from_millis(20));
                            if holder.is_some() {
                                let _ = std::fs::remove_file(&lock);
                            }
                        }
                    }
                }
                Err(e) => return Err(fail(&lock, &e)),
            }
        }
    }
}

impl Drop for Lock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// FNV-1a, 64 bits: a fixed, dependency-free hash for telling files apart (not for security).
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A move cut after its first file: the folder has no manifest, and recovery finishes
    /// the move so the folder holds the new set whole.
    #[test]
    fn a_move_cut_short_is_rolled_forward() {
        let dir = std::env::temp_dir().join(format!("flexopt-roll-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let old = OutputSet::begin(&dir).unwrap();
        for name in ["a.txt", "b.txt"] {
            std::fs::write(old.path(name), format!("old {name}")).unwrap();
        }
        old.commit(&["a.txt", "b.txt"]).unwrap();

        // a run (process id that cannot exist) killed after moving a.txt
        let staging = dir.join(format!("{STAGING}4000000000-1"));
        std::fs::create_dir(&staging).unwrap();
        let mut files = Vec::new();
        for name in ["a.txt", "b.txt"] {
            let text = format!("new {name}, longer");
            std::fs::write(staging.join(name), &text).unwrap();
            files.push(ManifestEntry {
                name: name.into(),
                bytes: text.len() as u64,
                fnv1a64: format!("{:016x}", fnv1a64(text.as_bytes())),
            });
        }
        write_json(&staging.join(MANIFEST), &Manifest { files }).unwrap();
        std::fs::remove_file(dir.join(MANIFEST)).unwrap();
        std::fs::rename(staging.join("a.txt"), dir.join("a.txt")).unwrap();

        recover(&dir).unwrap();
        assert!(!staging.exists());
        for name in ["a.txt", "b.txt"] {
            assert_eq!(
                std::fs::read_to_string(dir.join(name)).unwrap(),
                format!("new {name}, longer")
            );
        }
        let manifest: Manifest =
            serde_json::from_str(&std::fs::read_to_string(dir.join(MANIFEST)).unwrap()).unwrap();
        assert_eq!(manifest.files.len(), 2);
        assert_eq!(manifest.files[1].bytes, "new b.txt, longer".len() as u64);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
