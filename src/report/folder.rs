//! A run's files as one set: written under a folder unique to the run, moved into place
//! under a lock, and listed last in `manifest.json` with each file's size and hash, so that a
//! folder never holds two runs' files without saying so.
//!
//! - Two runs into one folder at once: the second to finish its files finds the lock held by
//!   a live run and gives up with a message; the folder keeps the first run's whole set.
//! - A run killed while it writes leaves its staging folder, never a file in place; the next
//!   run into the folder removes the staging folders and locks of runs that are gone.
//! - A reader checks the set against `manifest.json` (sizes and FNV-1a hashes); the manifest
//!   is written after every file is in place.

use std::path::{Path, PathBuf};

use serde::Serialize;

use super::{write_json, WriteError};

/// The lock file of a folder.
const LOCK: &str = ".flexopt.lock";
/// Staging folders start with this, followed by the owner's process id.
const STAGING: &str = ".run-";

/// A set of files being written for one run.
pub struct OutputSet {
    dir: PathBuf,
    staging: PathBuf,
}

/// `manifest.json`.
#[derive(Debug, Serialize)]
struct Manifest {
    /// The files of the set, with their size in bytes and FNV-1a 64-bit hash (hex).
    files: Vec<ManifestEntry>,
}

#[derive(Debug, Serialize)]
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
    /// Starts a set for `dir`, removing what runs that are gone left behind.
    pub fn begin(dir: &Path) -> Result<Self, WriteError> {
        std::fs::create_dir_all(dir).map_err(|e| fail(dir, &e))?;
        if let Ok(entries) = std::fs::read_dir(dir) {
            for entry in entries.flatten() {
                let name = entry.file_name().to_string_lossy().into_owned();
                // a temporary file outside a staging folder belongs to a sweep or a front,
                // which may be writing it now: removed only when an hour old
                let old = || {
                    entry
                        .metadata()
                        .and_then(|m| m.modified())
                        .ok()
                        .and_then(|t| t.elapsed().ok())
                        .is_some_and(|age| age.as_secs() > 3600)
                };
                let stale = match owner(&name) {
                    Some(pid) => !alive(pid),
                    None => name.contains(".partial") && old(),
                };
                if stale {
                    let p = entry.path();
                    let _ = std::fs::remove_dir_all(&p).or_else(|_| std::fs::remove_file(&p));
                }
            }
        }
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
    /// manifest; returns the paths in place. On failure nothing of this set is in place.
    pub fn commit(self, names: &[&str]) -> Result<Vec<PathBuf>, WriteError> {
        let result = self.commit_locked(names);
        let _ = std::fs::remove_dir_all(&self.staging);
        result
    }

    fn commit_locked(&self, names: &[&str]) -> Result<Vec<PathBuf>, WriteError> {
        let lock = self.dir.join(LOCK);
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
                    break;
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && tries < 50 => {
                    tries += 1;
                    let holder = std::fs::read_to_string(&lock)
                        .ok()
                        .and_then(|s| s.trim().parse::<u32>().ok());
                    match holder {
                        Some(pid) if alive(pid) => {
                            return Err(fail(
                                &self.dir,
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
        let moved = self.move_into_place(names);
        let _ = std::fs::remove_file(&lock);
        moved
    }

    fn move_into_place(&self, names: &[&str]) -> Result<Vec<PathBuf>, WriteError> {
        let mut files = Vec::new();
        let mut placed = Vec::new();
        for name in names {
            let staged = self.path(name);
            let bytes = std::fs::read(&staged).map_err(|e| fail(&staged, &e))?;
            files.push(ManifestEntry {
                name: name.to_string(),
                bytes: bytes.len() as u64,
                fnv1a64: format!("{:016x}", fnv1a64(&bytes)),
            });
            let target = self.dir.join(name);
            std::fs::rename(&staged, &target).map_err(|e| fail(&target, &e))?;
            placed.push(target);
        }
        let manifest = self.dir.join("manifest.json");
        write_json(&manifest, &Manifest { files })?;
        placed.push(manifest);
        Ok(placed)
    }
}

/// FNV-1a, 64 bits: a fixed, dependency-free hash for telling files apart (not for security).
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}
