//! Atomic file writes, one file ([`write_atomic`]) or a set of files that are replaced together
//! or not at all ([`Transaction`]).
//!
//! Every output first goes to a fresh temporary file `.NAME.tmp-PID-N` in the target's
//! directory (so the final rename never crosses a file system). A [`Transaction`] creates the
//! temporary files of *all* its outputs first — which proves every directory writable before
//! any work is spent on content — then fills, flushes and syncs each one (synced behind the
//! writer as it fills: `sync_behind`), and only when every one is complete renames them over
//! their targets, one after the other. On any error, or when the transaction is dropped
//! uncommitted, every temporary file is removed (and every folder the transaction created,
//! when empty), and no target is touched.
//!
//! Interruptions. Every live temporary file of the process is registered here; a signal
//! handler calls [`on_interrupt`], which removes them all and runs its closure (which should
//! exit the process) while holding the registry's lock, so that no rename can start after the
//! temporary files are gone, and a commit already renaming runs to its end first. A process
//! killed outright (SIGKILL, a power cut) cannot clean up: the next transaction that writes
//! into the same directory removes the temporary files of our naming pattern whose process is
//! no longer alive (judged by `/proc/PID` on Linux; elsewhere such files are left alone).
//!
//! Limits. The renames of a commit are atomic one by one, not together: a process killed
//! outright between two of them, or a rename refused by the operating system after every
//! temporary file was written (a target replaced meanwhile by a folder, a disk yanked), leaves
//! the targets renamed so far new and the others old. Everything else — every error while
//! making content, a full disk, a read-only folder, Ctrl-C or SIGTERM at any moment — leaves
//! the targets as they were, or all new.
//!
//! This module owns only the mechanics; what is written is the business of the format
//! modules and of the caller.

use std::collections::BTreeSet;
use std::ffi::OsString;
use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard};

use crate::IoError;

mod sync_behind;
use sync_behind::SyncBehind;

/// Size of the write buffer in front of each temporary file, in bytes: small writes are
/// gathered, and the writers' chunks of formatted records (larger) go to the file directly,
/// not copied through it.
const BUFFER_BYTES: usize = 64 << 10;

/// The live temporary files of this process, and whether an interruption closed the door.
struct Registry {
    temporaries: BTreeSet<PathBuf>,
    interrupted: bool,
}

static REGISTRY: Mutex<Registry> = Mutex::new(Registry {
    temporaries: BTreeSet::new(),
    interrupted: false,
});

fn registry() -> MutexGuard<'static, Registry> {
    // A panic while holding the lock leaves the set consistent (every change is one call).
    REGISTRY.lock().unwrap_or_else(|e| e.into_inner())
}

/// For a signal handler: removes every temporary file this process has not yet renamed into
/// place, refuses every later reservation and commit, then calls `then` with the number of
/// files removed — still holding the lock, so that when `then` ends the process (as it
/// should, e.g. `std::process::exit(130)`), no rename can have happened after the removal.
/// A commit in progress on another thread finishes its renames before this runs.
pub fn on_interrupt<R>(then: impl FnOnce(usize) -> R) -> R {
    let mut reg = registry();
    reg.interrupted = true;
    let removed = std::mem::take(&mut reg.temporaries);
    let count = removed.len();
    for path in removed {
        // Already gone or not removable: nothing more can be done here.
        let _ = fs::remove_file(path);
    }
    then(count)
}

/// Writes a file atomically: `fill` writes the content into a buffered temporary file beside
/// `path`; when it returns `Ok`, the file is flushed, synced to disk and renamed to `path`
/// (replacing any file there). When `fill` or any later step fails, the temporary file is
/// removed and the error returned; `path` is untouched. The folder of `path` must exist.
///
/// Errors from the operating system are returned as [`IoError::Io`] naming `path`.
pub fn write_atomic<F>(path: &Path, fill: F) -> Result<(), IoError>
where
    F: FnOnce(&mut dyn Write) -> Result<(), IoError>,
{
    let mut transaction = Transaction::new();
    let id = transaction.reserve(path)?;
    transaction.write(id, fill)?;
    transaction.commit()
}

/// One output reserved in a [`Transaction`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OutputId(usize);

/// A set of output files written together: reserve every output, write each, commit. See the
/// module documentation for what is guaranteed when.
#[derive(Debug, Default)]
pub struct Transaction {
    outputs: Vec<Pending>,
    /// Create missing folders of targets (and remove them again on rollback when empty).
    create_folders: bool,
    /// Folders this transaction created, outermost first.
    created: Vec<PathBuf>,
    /// Folders already cleaned of stale temporary files.
    cleaned: BTreeSet<PathBuf>,
}

#[derive(Debug)]
struct Pending {
    target: PathBuf,
    /// The canonical folder joined with the file name: two outputs with the same key would
    /// overwrite each other.
    key: PathBuf,
    temporary: PathBuf,
    /// The open temporary file until it is written.
    file: Option<File>,
    written: bool,
}

impl Transaction {
    /// An empty transaction whose targets' folders must exist.
    pub fn new() -> Self {
        Transaction::default()
    }

    /// An empty transaction that creates the missing folders of its targets when reserving
    /// them, and removes those it created again (when empty) if it does not commit.
    pub fn creating_folders() -> Self {
        let mut t = Transaction::default();
        t.create_folders = true;
        t
    }

    /// The targets reserved so far, in order.
    pub fn targets(&self) -> impl Iterator<Item = &Path> {
        self.outputs.iter().map(|p| p.target.as_path())
    }

    /// Reserves `target`: checks that it names a file that no earlier output of this
    /// transaction names, creates its folder if allowed, removes stale temporary files there,
    /// and creates the (empty) temporary file — which proves the folder writable.
    ///
    /// Errors: [`IoError::Io`] when the path names no file, names a folder, or the folder
    /// cannot be created or written; [`IoError::DuplicateOutput`] when an earlier output is
    /// the same file; [`IoError::Interrupted`] after [`on_interrupt`].
    pub fn reserve(&mut self, target: &Path) -> Result<OutputId, IoError> {
        let name = target
            .file_name()
            .ok_or_else(|| {
                io_error(
                    target,
                    io::ErrorKind::InvalidInput,
                    "the path names no file (it ends in `..` or `/`)",
                )
            })?
            .to_os_string();
        if target.is_dir() {
            return Err(io_error(
                target,
                io::ErrorKind::InvalidInput,
                "is a folder, not a file",
            ));
        }
        let dir = folder_of(target);
        if self.create_folders {
            self.create_folder(&dir).map_err(|e| IoError::io(&dir, e))?;
        }
        let canonical = dir.canonicalize().map_err(|e| IoError::io(target, e))?;
        let key = canonical.join(&name);
        if let Some(first) = self.outputs.iter().find(|p| p.key == key) {
            return Err(IoError::DuplicateOutput {
                path: target.to_path_buf(),
                first: first.target.clone(),
            });
        }
        if self.cleaned.insert(canonical) {
            remove_stale_temporaries(&dir);
        }
        let (temporary, file) = create_temporary(&dir, &name).map_err(|e| match e {
            Reserve::Interrupted => IoError::Interrupted {
                path: target.to_path_buf(),
            },
            Reserve::Io(e) => IoError::io(target, e),
        })?;
        self.outputs.push(Pending {
            target: target.to_path_buf(),
            key,
            temporary,
            file: Some(file),
            written: false,
        });
        Ok(OutputId(self.outputs.len() - 1))
    }

    /// Writes the content of output `id`: `fill` writes into its buffered temporary file,
    /// which is then flushed and synced. Each output is written once.
    ///
    /// Errors: those of `fill`; [`IoError::Io`] naming the target when the operating system
    /// refuses the write (a full disk), or when the output was already written.
    pub fn write<F>(&mut self, id: OutputId, fill: F) -> Result<(), IoError>
    where
        F: FnOnce(&mut dyn Write) -> Result<(), IoError>,
    {
        self.write_via(id, fill, SyncBehind::new)
    }

    /// [`Transaction::write`] through the file made by `behind` (which syncs it behind the
    /// writer): the final sync finds little left, and a failed sync behind fails the output.
    fn write_via<F>(
        &mut self,
        id: OutputId,
        fill: F,
        behind: fn(File) -> SyncBehind,
    ) -> Result<(), IoError>
    where
        F: FnOnce(&mut dyn Write) -> Result<(), IoError>,
    {
        let pending = &mut self.outputs[id.0];
        let target = pending.target.clone();
        let file = pending.file.take().ok_or_else(|| {
            io_error(
                &target,
                io::ErrorKind::InvalidInput,
                "this output was already written",
            )
        })?;
        let mut out = BufWriter::with_capacity(BUFFER_BYTES, behind(file));
        fill(&mut out)?;
        let file = out
            .into_inner()
            .map_err(|e| IoError::io(&target, e.into_error()))?
            .finish()
            .map_err(|e| IoError::io(&target, e))?;
        file.sync_all().map_err(|e| IoError::io(&target, e))?;
        pending.written = true;
        Ok(())
    }

    /// Renames every temporary file over its target, in the order reserved, then syncs the
    /// folders. Every output must have been written.
    ///
    /// Errors: [`IoError::Unwritten`] (nothing renamed) when an output was reserved but not
    /// written; [`IoError::Interrupted`] (nothing renamed) after [`on_interrupt`];
    /// [`IoError::Io`] when a rename fails — the targets before it are then already new (see
    /// the module documentation), the others untouched.
    pub fn commit(mut self) -> Result<(), IoError> {
        if let Some(p) = self.outputs.iter().find(|p| !p.written) {
            return Err(IoError::Unwritten {
                path: p.target.clone(),
            });
        }
        if self.outputs.is_empty() {
            return Ok(());
        }
        let mut reg = registry();
        if reg.interrupted {
            return Err(IoError::Interrupted {
                path: self.outputs[0].target.clone(),
            });
        }
        let outputs = std::mem::take(&mut self.outputs);
        let mut failure = None;
        for p in &outputs {
            if failure.is_none() {
                // (no let-chain: the MSRV is 1.85)
                failure = fs::rename(&p.temporary, &p.target)
                    .err()
                    .map(|e| IoError::io(&p.target, e));
            }
            if failure.is_some() {
                let _ = fs::remove_file(&p.temporary);
            }
            reg.temporaries.remove(&p.temporary);
        }
        drop(reg);
        self.created.clear();
        if let Some(e) = failure {
            return Err(e);
        }
        let folders: BTreeSet<PathBuf> = outputs.iter().map(|p| folder_of(&p.target)).collect();
        for dir in folders {
            sync_folder(&dir);
        }
        Ok(())
    }

    /// Creates `dir` and its missing ancestors, remembering which were created.
    fn create_folder(&mut self, dir: &Path) -> io::Result<()> {
        let mut missing = Vec::new();
        let mut d = Some(dir);
        while let Some(p) = d {
            if p.as_os_str().is_empty() || p.exists() {
                break;
            }
            missing.push(p.to_path_buf());
            d = p.parent();
        }
        for p in missing.into_iter().rev() {
            match fs::create_dir(&p) {
                Ok(()) => self.created.push(p),
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => {}
                Err(e) => return Err(e),
            }
        }
        Ok(())
    }
}

impl Drop for Transaction {
    /// Rolls back: removes every temporary file and every folder created (when empty).
    fn drop(&mut self) {
        if !self.outputs.is_empty() {
            let mut reg = registry();
            for p in self.outputs.drain(..) {
                drop(p.file);
                let _ = fs::remove_file(&p.temporary);
                reg.temporaries.remove(&p.temporary);
            }
        }
        for dir in self.created.drain(..).rev() {
            // fails, as it should, when something else was put there meanwhile
            let _ = fs::remove_dir(dir);
        }
    }
}

/// The folder a target lives in (`.` for a bare file name).
fn folder_of(target: &Path) -> PathBuf {
    match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

fn io_error(path: &Path, kind: io::ErrorKind, message: &str) -> IoError {
    IoError::io(path, io::Error::new(kind, message))
}

enum Reserve {
    Interrupted,
    Io(io::Error),
}

/// Creates and registers a new temporary file `.NAME.tmp-PID-N` in `dir`.
fn create_temporary(dir: &Path, name: &std::ffi::OsStr) -> Result<(PathBuf, File), Reserve> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let mut last_error = None;
    for _ in 0..64 {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let mut tmp_name = OsString::from(".");
        tmp_name.push(name);
        tmp_name.push(format!(".tmp-{}-{n}", std::process::id()));
        let tmp = dir.join(tmp_name);
        // created and registered under the lock: an interruption sees it or prevents it
        let mut reg = registry();
        if reg.interrupted {
            return Err(Reserve::Interrupted);
        }
        match OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(f) => {
                reg.temporaries.insert(tmp.clone());
                return Ok((tmp, f));
            }
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => last_error = Some(e),
            Err(e) => return Err(Reserve::Io(e)),
        }
    }
    Err(Reserve::Io(last_error.unwrap_or_else(|| {
        io::Error::other("no free temporary file name")
    })))
}

/// The process id in a temporary file name of ours, `.NAME.tmp-PID-N`.
fn temporary_pid(file_name: &str) -> Option<u32> {
    if !file_name.starts_with('.') {
        return None;
    }
    let (_, tail) = file_name.rsplit_once(".tmp-")?;
    let (pid, n) = tail.split_once('-')?;
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    if !digits(n) {
        return None;
    }
    if !digits(pid) {
        return None;
    }
    pid.parse().ok()
}

/// Removes the temporary files of our naming pattern in `dir` left by processes that are
/// gone (killed outright): those of another process that is not alive, and those of this
/// process's id that this process did not create (an earlier process with the same id).
fn remove_stale_temporaries(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    let own = std::process::id();
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(temporary_pid) else {
            continue;
        };
        let path = entry.path();
        let stale = if pid == own {
            !registry().temporaries.contains(&path)
        } else {
            process_is_gone(pid)
        };
        if stale && entry.file_type().is_ok_and(|t| t.is_file()) {
            let _ = fs::remove_file(path);
        }
    }
}

/// True when no process `pid` exists. Only Linux can tell (`/proc`); elsewhere every process
/// is taken to be alive, so that no live run's file is ever removed.
fn process_is_gone(pid: u32) -> bool {
    if cfg!(target_os = "linux") {
        let proc = Path::new("/proc");
        proc.join("self").exists() && !proc.join(pid.to_string()).exists()
    } else {
        false
    }
}

/// Syncs a folder so that the renames into it survive a crash (best effort: not every
/// platform can open a folder).
fn sync_folder(dir: &Path) {
    if let Ok(f) = File::open(dir) {
        let _ = f.sync_all();
    }
}

#[cfg(test)]
mod tests;
