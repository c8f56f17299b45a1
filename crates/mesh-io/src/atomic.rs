//! Atomic file writes: the content goes to a fresh temporary file in the target's directory,
//! is flushed and synced, and is then renamed over the target, so that a reader (or a user
//! after a crash) sees either the old file, or the whole new file, never a partial one. On any
//! error the temporary file is removed and the target is left as it was.
//!
//! This module owns only the mechanics; what is written is the business of the format
//! modules, which all go through [`write_atomic`].

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::IoError;

/// Size of the write buffer in front of the temporary file, in bytes.
const BUFFER_BYTES: usize = 1 << 20;

/// Writes a file atomically: `fill` writes the content into a buffered temporary file beside
/// `path`; when it returns `Ok`, the file is flushed, synced to disk and renamed to `path`
/// (replacing any file there). When `fill` or any later step fails, the temporary file is
/// removed and the error returned; `path` is untouched.
///
/// Errors from the operating system are returned as [`IoError::Io`] naming `path`.
pub fn write_atomic<F>(path: &Path, fill: F) -> Result<(), IoError>
where
    F: FnOnce(&mut dyn Write) -> Result<(), IoError>,
{
    let (tmp_path, file) = create_temporary(path).map_err(|e| IoError::io(path, e))?;
    let guard = RemoveOnDrop(Some(tmp_path));
    let mut out = BufWriter::with_capacity(BUFFER_BYTES, file);
    fill(&mut out)?;
    let file = out
        .into_inner()
        .map_err(|e| IoError::io(path, e.into_error()))?;
    file.sync_all().map_err(|e| IoError::io(path, e))?;
    drop(file);
    let tmp_path = guard.path();
    fs::rename(tmp_path, path).map_err(|e| IoError::io(path, e))?;
    guard.disarm();
    Ok(())
}

/// Creates a new temporary file in the directory of `target`, named after it, that did not
/// exist before.
fn create_temporary(target: &Path) -> io::Result<(PathBuf, File)> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = target.file_name().ok_or_else(|| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            "the path names no file (it ends in `..` or `/`)",
        )
    })?;
    let mut last_error = None;
    for _ in 0..64 {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let mut tmp_name = std::ffi::OsString::from(".");
        tmp_name.push(name);
        tmp_name.push(format!(".tmp-{}-{n}", std::process::id()));
        let tmp = dir.join(tmp_name);
        match OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(f) => return Ok((tmp, f)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => last_error = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last_error.unwrap_or_else(|| io::Error::other("no free temporary file name")))
}

/// Removes the temporary file when dropped, unless disarmed after the rename.
struct RemoveOnDrop(Option<PathBuf>);

impl RemoveOnDrop {
    fn path(&self) -> &Path {
        self.0.as_deref().unwrap_or(Path::new(""))
    }

    fn disarm(mut self) {
        self.0 = None;
    }
}

impl Drop for RemoveOnDrop {
    fn drop(&mut self) {
        if let Some(p) = self.0.take() {
            // The file may already be gone; nothing more can be done about a failure here.
            let _ = fs::remove_file(p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entries(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_successful_write_leaves_exactly_the_target() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("a.txt");
        write_atomic(&target, |w| {
            w.write_all(b"hello").map_err(|e| IoError::io(&target, e))
        })
        .unwrap();
        assert_eq!(fs::read(&target).unwrap(), b"hello");
        assert_eq!(entries(dir.path()), vec!["a.txt"]);
    }

    #[test]
    fn a_failed_write_leaves_the_old_file_and_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("a.txt");
        fs::write(&target, b"old").unwrap();
        let err = write_atomic(&target, |w| {
            w.write_all(b"partial new content").unwrap();
            Err(IoError::InvalidMesh {
                path: target.clone(),
                message: "stop".into(),
            })
        })
        .unwrap_err();
        assert!(matches!(err, IoError::InvalidMesh { .. }), "{err}");
        assert_eq!(fs::read(&target).unwrap(), b"old");
        assert_eq!(entries(dir.path()), vec!["a.txt"]);
    }

    #[test]
    fn a_missing_directory_is_an_error_naming_the_target() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("no/such/dir/a.txt");
        let err = write_atomic(&target, |_| Ok(())).unwrap_err();
        assert!(matches!(err, IoError::Io { .. }));
        assert!(err.to_string().contains("no/such/dir/a.txt"), "{err}");
    }

    #[test]
    fn a_path_without_file_name_is_an_error() {
        let err = write_atomic(Path::new("/"), |_| Ok(())).unwrap_err();
        assert!(matches!(err, IoError::Io { .. }), "{err}");
    }
}
