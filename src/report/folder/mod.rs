//! A command's files as one set: written under a staging folder unique to the command, moved
//! into place under the output folder's lock, and listed last in `manifest.json` with each
//! file's size and hash, so that a folder with a manifest holds exactly the set it lists.
//!
//! - A set either replaces the folder's earlier set ([`OutputSet::commit`]: `run`, `export`,
//!   `verify`), and then the files and folders the earlier manifest lists that the new set
//!   does not hold are removed within the same move; or it adds to it
//!   ([`OutputSet::commit_added`]: a sweep, a front), and then the earlier set's entries stay
//!   listed beside the new ones, those of the same names replaced.
//! - Only what a flexopt manifest listed is removed, and a listed folder only while it holds
//!   nothing but its own set: a file or folder that no manifest lists is never touched, unless
//!   a file of the new set takes its name (a file there is then replaced, as any write would; a
//!   folder there stops the move, which puts the earlier set back).
//! - A folder of a set (`run --verify`'s `verify/`) is itself a set with its own manifest,
//!   moved into place whole.
//! - Two commands into one folder at once: the second to finish its files finds the lock held
//!   by a live command and gives up with a message; the folder keeps the first one's set.
//! - The move is journaled ([`moves`]): the new manifest and the journal are written in the
//!   staging folder first; the manifest in place, the earlier set's entries that go and
//!   whatever stands at a new entry's name are moved aside into the staging folder; the new
//!   entries are renamed into place and the new manifest last. A move that fails is undone
//!   from the journal: the folder holds its earlier set again. A folder without a manifest
//!   is therefore a move cut short, by a kill.
//! - A command killed before its move leaves only its staging folder, which the next command
//!   into the folder removes; one killed during its move leaves a staging folder with a
//!   journal, which the next command (or [`recover`]) rolls forward (or, where that fails,
//!   back), so the folder again holds one whole set.

mod moves;

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{write_json, WriteError};

/// The lock file of a folder.
const LOCK: &str = ".flexopt.lock";
/// Staging folders start with this, followed by the owner's process id.
const STAGING: &str = ".run-";
/// The manifest, in place and, as the set to be placed, in a staging folder.
const MANIFEST: &str = "manifest.json";
/// The journal of a move, in its staging folder ([`moves::Journal`]).
const JOURNAL: &str = ".journal.json";

/// A set of files being written for one command.
pub struct OutputSet {
    dir: PathBuf,
    staging: PathBuf,
}

/// `manifest.json`.
#[derive(Debug, Default, Serialize, Deserialize)]
struct Manifest {
    /// The files and folders of the set: a file with its size in bytes and FNV-1a 64-bit
    /// hash (hex), a folder as `"folder": true` (it holds a set of its own).
    files: Vec<Entry>,
}

/// A file or folder of a set, as its manifest lists it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Entry {
    pub name: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bytes: Option<u64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fnv1a64: Option<String>,
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub folder: bool,
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

/// The process id a staging folder (or a probe of [`super::check_writable`]) names, if it
/// names one.
fn owner(name: &str) -> Option<u32> {
    let rest = name
        .strip_prefix(STAGING)
        .or_else(|| name.strip_prefix(super::PROBE))?;
    rest.split('-').next()?.parse().ok()
}

/// Whether something (a file, folder or link) stands at `path`.
fn exists(path: &Path) -> bool {
    std::fs::symlink_metadata(path).is_ok()
}

/// A name a set may hold: one plain component, not hidden (the staging folders, the lock and
/// temporary files are), not the manifest's.
fn plain(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with('.')
        && name != MANIFEST
        && !name.contains(['/', '\\', '\0'])
}

/// The manifest at `path`, if there is one that reads as a manifest.
fn read_manifest(path: &Path) -> Option<Manifest> {
    let limit = crate::vocab::input::MAX_SET_FILE_BYTES;
    serde_json::from_str(&crate::vocab::input::read_text(path, limit, "a manifest").ok()?).ok()
}

/// Whether `path` is still the entry a set listed there: a regular file for a file; for a
/// folder, a folder that holds nothing but its own set (or nothing).
fn is_entry(path: &Path, folder: bool) -> bool {
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        return false;
    };
    if !folder || !meta.is_dir() {
        return meta.is_file() && !folder;
    }
    let Ok(entries) = std::fs::read_dir(path) else {
        return false;
    };
    let listed = read_manifest(&path.join(MANIFEST)).unwrap_or_default();
    entries.into_iter().all(|entry| {
        let Ok(entry) = entry else { return false };
        let name = entry.file_name();
        name == MANIFEST
            || listed
                .files
                .iter()
                .any(|e| name == e.name.as_str() && is_entry(&entry.path(), e.folder))
    })
}

/// The entries the manifest of `dir` lists, if it has a manifest that reads as one.
pub fn listed(dir: &Path) -> Option<Vec<Entry>> {
    read_manifest(&dir.join(MANIFEST)).map(|m| m.files)
}

/// Where a file that `files` (a manifest of `dir`) lists differs from what the manifest says
/// of it, the file and what differs: a file edited, replaced or removed since it was written.
pub fn differing(dir: &Path, files: &[Entry]) -> Option<String> {
    files.iter().filter(|e| !e.folder).find_map(|e| {
        let path = dir.join(&e.name);
        let listed = format!(
            "{} bytes, hash {}",
            e.bytes.map_or("?".into(), |b| b.to_string()),
            e.fnv1a64.as_deref().unwrap_or("?")
        );
        let found = match std::fs::read(&path) {
            Ok(bytes) => format!("{} bytes, hash {:016x}", bytes.len(), fnv1a64(&bytes)),
            Err(err) => return Some(format!("{}: cannot be read ({err})", path.display())),
        };
        (found != listed).then(|| {
            format!(
                "{}: not the file {} lists ({listed}; the file has {found}): it was changed \
                 after flexopt wrote it",
                path.display(),
                dir.join(MANIFEST).display()
            )
        })
    })
}

/// Refuses, before anything is written, file names a set of `dir` cannot hold: a name that
/// is not a plain file name (a path, a leading `.`, the manifest's) or one given twice. The
/// commands whose file names come from a problem file's names (a histogram per output) call
/// it first.
pub fn check_names(dir: &Path, names: &[&str]) -> Result<(), WriteError> {
    for (i, name) in names.iter().enumerate() {
        if !plain(name) || names[..i].contains(name) {
            return Err(fail(
                &dir.join(crate::vocab::error::printable(name)),
                &"not a name a set of files can hold once; nothing was written",
            ));
        }
    }
    Ok(())
}

/// The entries of the files `names` as written in `dir`, as a manifest would list them: what
/// a file of the set that describes the others (the report) lists before the manifest exists.
pub fn entries_of(dir: &Path, names: &[&str]) -> Result<Vec<Entry>, WriteError> {
    entries(dir, names)
}

/// The entries of the names `names` written in `dir`: each file's size and hash, each
/// folder's (which must hold its own manifest, [`OutputSet::seal_folder`]) mark.
fn entries(dir: &Path, names: &[&str]) -> Result<Vec<Entry>, WriteError> {
    let mut list: Vec<Entry> = Vec::new();
    for name in names {
        let path = dir.join(name);
        if !plain(name) || list.iter().any(|e| e.name == *name) {
            return Err(fail(&path, &"not a name a set of files can hold once"));
        }
        let meta = std::fs::symlink_metadata(&path).map_err(|e| fail(&path, &e))?;
        list.push(if meta.is_dir() {
            let own = path.join(MANIFEST);
            if !own.is_file() {
                return Err(fail(&own, &"a folder of a set lacks its manifest"));
            }
            Entry {
                name: name.to_string(),
                bytes: None,
                fnv1a64: None,
                folder: true,
            }
        } else {
            let bytes = std::fs::read(&path).map_err(|e| fail(&path, &e))?;
            Entry {
                name: name.to_string(),
                bytes: Some(bytes.len() as u64),
                fnv1a64: Some(format!("{:016x}", fnv1a64(&bytes))),
                folder: false,
            }
        });
    }
    Ok(list)
}

impl OutputSet {
    /// Starts a set for `dir`, after [`recover`] has finished or removed what commands that
    /// are gone left behind.
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

    /// Where the file (or folder) `name` of the set is written.
    pub fn path(&self, name: &str) -> PathBuf {
        // a name that would lead out (`..`, an absolute path) writes inside the staging
        // folder under a name of its own, which the commit then refuses; a path down into a
        // folder of the set (`sub/x.txt`) stays, and the empty name is the staging folder
        let inside = Path::new(name)
            .components()
            .all(|c| matches!(c, std::path::Component::Normal(_)));
        if inside {
            self.staging.join(name)
        } else {
            self.staging
                .join(format!("refused-{:016x}", fnv1a64(name.as_bytes())))
        }
    }

    /// Runs `stage`, which writes the set's files through [`OutputSet::path`]; an error of
    /// its is told of the file in place (not of the staging folder), and that nothing was
    /// written: the folder keeps its earlier files.
    pub fn write<T>(
        &self,
        stage: impl FnOnce(&Self) -> Result<T, WriteError>,
    ) -> Result<T, WriteError> {
        stage(self).map_err(|e| WriteError {
            path: match e.path.strip_prefix(&self.staging) {
                Ok(rel) => self.dir.join(rel),
                Err(_) => e.path,
            },
            message: format!(
                "{}; nothing was written: the folder keeps its earlier files",
                e.message
            ),
        })
    }

    /// Makes the folder `name`, whose files `files` were written into [`OutputSet::path`]
    /// `(name)`, a set of its own: writes its manifest, so that a later set written into that
    /// folder replaces it as a set. Commit it by its name with the set's files.
    pub fn seal_folder(&self, name: &str, files: &[&str]) -> Result<(), WriteError> {
        let folder = self.path(name);
        let manifest = Manifest {
            files: entries(&folder, files)?,
        };
        write_json(&folder.join(MANIFEST), &manifest)
    }

    /// Moves the set's files `names` into place under the folder's lock in place of the
    /// folder's earlier set, whose entries that `names` lacks are removed, and writes the
    /// manifest; returns the paths in place (a folder's files, each). A failure before the
    /// move leaves the folder as it was, and so does one during the move (a full disk, a
    /// folder where a file goes), which puts the earlier set back.
    pub fn commit(self, names: &[&str]) -> Result<Vec<PathBuf>, WriteError> {
        self.move_into_place(names, false, None)
    }

    /// [`OutputSet::commit`], keeping the earlier set's entries that `names` does not replace
    /// (and that are still there) in the set: the manifest lists both.
    pub fn commit_added(self, names: &[&str]) -> Result<Vec<PathBuf>, WriteError> {
        self.move_into_place(names, true, None)
    }

    /// [`OutputSet::commit_added`] of files made of the set `made_of` (a report of the files
    /// a manifest listed), only while the folder still holds that set: a command that
    /// replaced it meanwhile made another set, which the files must not join.
    pub fn commit_added_to(
        self,
        names: &[&str],
        made_of: &[Entry],
    ) -> Result<Vec<PathBuf>, WriteError> {
        self.move_into_place(names, true, Some(made_of))
    }

    fn move_into_place(
        &self,
        names: &[&str],
        keep_earlier: bool,
        made_of: Option<&[Entry]>,
    ) -> Result<Vec<PathBuf>, WriteError> {
        let staged = entries(&self.staging, names)?;
        let lock = Lock::take(&self.dir)?;
        if let Some(made_of) = made_of {
            let now: Vec<Entry> = listed(&self.dir)
                .unwrap_or_default()
                .into_iter()
                .filter(|e| !names.contains(&e.name.as_str()))
                .collect();
            if now != made_of {
                return Err(fail(
                    &self.dir.join(names.first().copied().unwrap_or(MANIFEST)),
                    &"another command replaced the folder's set while these files were made \
                      of it; they belong to the set that is gone and were not added (make them \
                      again of the set there now)",
                ));
            }
        }
        journal_move(&self.dir, &self.staging, &staged, keep_earlier)?;
        let placed = moves::finish(&self.staging, &self.dir);
        drop(lock);
        placed
    }
}

/// Plans the move of the entries `staged` from `staging` into `dir` and writes the new
/// manifest and then the journal into `staging`: from then on, a kill is rolled forward by
/// the next command into the folder. The caller holds the lock.
fn journal_move(
    dir: &Path,
    staging: &Path,
    staged: &[Entry],
    keep_earlier: bool,
) -> Result<(), WriteError> {
    let journal = moves::plan(dir, staged, keep_earlier);
    write_json(&staging.join(MANIFEST), &journal.manifest)?;
    write_json(&staging.join(JOURNAL), &journal)
}

impl Drop for OutputSet {
    /// Removes the staging folder, but for one whose move could neither be finished nor
    /// undone: it holds the earlier set's files, for [`recover`] to put back.
    fn drop(&mut self) {
        if !self.staging.join(JOURNAL).exists() {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}

/// Finishes the moves of commands that were killed while moving their files (or undoes
/// them where they cannot be finished), removes the staging folders, probes and lock of
/// commands that are gone, and temporary files over an hour old.
pub fn recover(dir: &Path) -> Result<(), WriteError> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let path = entry.path();
        match owner(&name) {
            Some(pid) if !alive(pid) => {
                if path.join(JOURNAL).is_file() {
                    let lock = Lock::take(dir)?;
                    // another command may have finished it while this one waited for the lock
                    let outcome = if path.join(JOURNAL).is_file() {
                        moves::finish(&path, dir).map(drop)
                    } else {
                        Ok(())
                    };
                    drop(lock);
                    if let (Err(e), true) = (outcome, path.join(JOURNAL).is_file()) {
                        return Err(fail(
                            &path,
                            &format!(
                                "a move of files into this folder was cut short and can be \
                                 neither finished nor undone ({e}); the earlier set's files it \
                                 moved aside are in {}",
                                path.join(moves::ASIDE).display()
                            ),
                        ));
                    }
                }
                let _ = std::fs::remove_dir_all(&path).or_else(|_| std::fs::remove_file(&path));
            }
            Some(_) => {}
            // a temporary file outside a staging folder is an older flexopt's, or one that
            // may be being written now: removed only when an hour old
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
    // the lock of a command killed while it held it
    let lock = dir.join(LOCK);
    let holder = std::fs::read_to_string(&lock)
        .ok()
        .and_then(|s| s.trim().parse::<u32>().ok());
    if holder.is_some_and(|pid| !alive(pid)) {
        let _ = std::fs::remove_file(&lock);
    }
    Ok(())
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
mod tests;
