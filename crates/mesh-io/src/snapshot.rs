//! Binary snapshots of intermediate stages (a layered mesh with its layer and pipe records, a
//! boundary mesh, …), for resuming a pipeline or comparing runs. This is the only module
//! that uses `bincode`, so that another encoding (postcard) can replace it here alone.
//!
//! A snapshot file is: the 8 magic bytes [`MAGIC`], the format version [`FORMAT_VERSION`] as
//! a little-endian `u32`, the length and UTF-8 bytes of the saved type's name (for error
//! messages only), then the value encoded by bincode 1.3 (fixed-width integers, little
//! endian). Snapshots are not an exchange format: they are read by the same version of the
//! program that wrote them.
//!
//! Written by [`save`] (a file, atomically) or [`save_to`] (any writer); read by [`load`] (a
//! file) or [`parse`] (its bytes, which may be anything: a bad file is an error, never a
//! panic or an unbounded allocation; fuzzed by the `snapshot` target of `fuzz/run.sh`).

use std::io::Write;
use std::path::Path;

use bincode::Options;
use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::IoError;
use crate::atomic::write_atomic;

/// The first bytes of every snapshot file.
pub const MAGIC: [u8; 8] = *b"MESHSNAP";

/// The snapshot format version this build writes and reads. Bump it when the encoding or
/// the header changes.
pub const FORMAT_VERSION: u32 = 1;

/// The longest type name a header may hold, in bytes.
const MAX_TYPE_NAME: usize = 1024;

fn options() -> impl Options {
    bincode::DefaultOptions::new()
        .with_fixint_encoding()
        .with_little_endian()
}

/// Saves `value` to `path` as a snapshot, atomically.
///
/// Errors: [`IoError::Snapshot`] if `value` cannot be encoded (a serializer error, such as a
/// map with non-string keys in a format that needs them), [`IoError::Io`] if the file cannot
/// be written.
pub fn save<T: Serialize>(path: &Path, value: &T) -> Result<(), IoError> {
    let (header, payload) = encode(path, value)?;
    write_atomic(path, |w: &mut dyn Write| {
        w.write_all(&header)
            .and_then(|()| w.write_all(&payload))
            .map_err(|e| IoError::io(path, e))
    })
}

/// Writes `value` as a snapshot to any writer (for example a file of an
/// [`crate::atomic::Transaction`]); `path` only names the destination in errors. The value is
/// encoded in full before the first byte is written.
///
/// Errors: as [`save`].
pub fn save_to<T: Serialize>(out: &mut dyn Write, value: &T, path: &Path) -> Result<(), IoError> {
    let (header, payload) = encode(path, value)?;
    out.write_all(&header)
        .and_then(|()| out.write_all(&payload))
        .map_err(|e| IoError::io(path, e))
}

/// The snapshot file of `value`: its header and its payload.
fn encode<T: Serialize>(path: &Path, value: &T) -> Result<(Vec<u8>, Vec<u8>), IoError> {
    let payload = options().serialize(value).map_err(|e| IoError::Snapshot {
        path: path.to_path_buf(),
        message: format!("cannot encode the value: {e}"),
    })?;
    let type_name = std::any::type_name::<T>().as_bytes();
    let type_name = &type_name[..type_name.len().min(MAX_TYPE_NAME)];
    let mut header = Vec::with_capacity(16 + type_name.len());
    header.extend_from_slice(&MAGIC);
    header.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    header.extend_from_slice(&(type_name.len() as u32).to_le_bytes());
    header.extend_from_slice(type_name);
    Ok((header, payload))
}

/// Loads a snapshot saved by [`save`] with the same type `T`.
///
/// Errors: [`IoError::Io`] if the file cannot be read; [`IoError::Snapshot`] if it is not a
/// snapshot (wrong magic bytes), is of another format version, or does not decode as `T`
/// (the message names the type the file holds).
pub fn load<T: DeserializeOwned>(path: &Path) -> Result<T, IoError> {
    let bytes = std::fs::read(path).map_err(|e| IoError::io(path, e))?;
    parse(&bytes, path)
}

/// Decodes the bytes of a snapshot (a whole file saved by [`save`] or [`save_to`]) as a `T`:
/// [`load`] without the file; `path` only names the source in errors.
///
/// Any bytes give a value or an error, never a panic, and memory in proportion to their
/// length: the header's type name is read only when it is at most 1 KiB and within the
/// bytes, and the decoder may read no more than the payload holds, so a hostile length
/// prefix (a vector of 2⁶⁰ nodes in a file of a hundred bytes) fails before it allocates.
///
/// Errors: [`IoError::Snapshot`], as [`load`].
pub fn parse<T: DeserializeOwned>(bytes: &[u8], path: &Path) -> Result<T, IoError> {
    let snapshot_error = |message: String| IoError::Snapshot {
        path: path.to_path_buf(),
        message,
    };
    let Some(rest) = bytes.strip_prefix(&MAGIC) else {
        return Err(snapshot_error(
            "not a snapshot file (it does not start with the magic bytes MESHSNAP)".into(),
        ));
    };
    let u32_at = |b: &[u8], at: usize| -> Option<u32> {
        b.get(at..at + 4)
            .map(|s| u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
    };
    let version =
        u32_at(rest, 0).ok_or_else(|| snapshot_error("truncated snapshot header".into()))?;
    if version != FORMAT_VERSION {
        return Err(snapshot_error(format!(
            "snapshot format version {version}, but this program reads version {FORMAT_VERSION}: regenerate it"
        )));
    }
    let name_len = u32_at(rest, 4)
        .map(|n| n as usize)
        .filter(|&n| n <= MAX_TYPE_NAME && 8 + n <= rest.len())
        .ok_or_else(|| snapshot_error("truncated or corrupt snapshot header".into()))?;
    let stored = String::from_utf8_lossy(&rest[8..8 + name_len]);
    let payload = &rest[8 + name_len..];
    // the limit: every length prefix is checked against the bytes left before its elements
    // are read (bincode's byte buffers and strings), and serde preallocates at most 1 MiB for
    // a sequence whatever its prefix claims
    options()
        .with_limit(payload.len() as u64)
        .deserialize::<T>(payload)
        .map_err(|e| {
            snapshot_error(format!(
                "the snapshot holds a {stored} that does not decode as a {}: {e}",
                std::any::type_name::<T>()
            ))
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::{AnnulusParams, annulus};
    use mesh_model::Mesh;

    #[test]
    fn a_mesh_with_layers_and_pipes_survives_a_snapshot() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("m.snap");
        let m = annulus(&AnnulusParams::default());
        assert!(!m.cell_layer.is_empty() && !m.cell_pipe.is_empty());
        save(&path, &m).unwrap();
        let back: Mesh = load(&path).unwrap();
        assert_eq!(back, m);
    }

    #[test]
    fn a_file_that_is_not_a_snapshot_is_named_as_such() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.snap");
        std::fs::write(&path, b"$MeshFormat\n4.1 0 8\n").unwrap();
        let err = load::<Mesh>(&path).unwrap_err();
        assert!(err.to_string().contains("not a snapshot"), "{err}");
    }

    #[test]
    fn another_format_version_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.snap");
        save(&path, &42u64).unwrap();
        let mut bytes = std::fs::read(&path).unwrap();
        bytes[8..12].copy_from_slice(&(FORMAT_VERSION + 1).to_le_bytes());
        std::fs::write(&path, &bytes).unwrap();
        let err = load::<u64>(&path).unwrap_err();
        assert!(err.to_string().contains("format version"), "{err}");
    }

    #[test]
    fn a_snapshot_of_another_type_or_truncated_gives_an_error_not_a_panic() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.snap");
        save(&path, &vec![1.5f64, 2.5]).unwrap();
        let err = load::<Mesh>(&path).unwrap_err();
        assert!(matches!(err, IoError::Snapshot { .. }), "{err}");
        assert!(err.to_string().contains("Vec<f64>"), "{err}");
        let bytes = std::fs::read(&path).unwrap();
        for cut in [4, 10, 14, bytes.len() - 3] {
            std::fs::write(&path, &bytes[..cut]).unwrap();
            let err = load::<Vec<f64>>(&path).unwrap_err();
            assert!(matches!(err, IoError::Snapshot { .. }), "cut {cut}: {err}");
        }
    }

    /// The bytes of a snapshot of `value`, as [`save`] writes them.
    fn snapshot_bytes<T: Serialize>(value: &T) -> Vec<u8> {
        let mut out = Vec::new();
        save_to(&mut out, value, Path::new("mem.snap")).unwrap();
        out
    }

    /// The small mesh of the fuzz seed `tests/data/annulus_p1.snap`.
    fn seed_mesh() -> Mesh {
        annulus(&AnnulusParams {
            order: 1,
            radial_cells: 1,
            angular_cells: 4,
            triangle_mask: vec![true, false],
            ..AnnulusParams::default()
        })
    }

    fn seed_path() -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/annulus_p1.snap")
    }

    #[test]
    fn parse_decodes_what_save_to_writes_as_load_does() {
        let m = seed_mesh();
        let bytes = snapshot_bytes(&m);
        assert_eq!(parse::<Mesh>(&bytes, Path::new("mem.snap")).unwrap(), m);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("m.snap");
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(load::<Mesh>(&path).unwrap(), m);
    }

    /// Regression for the fuzz target `snapshot` (`fuzz/fuzz_targets/snapshot.rs`): every
    /// truncation of a snapshot, every byte of it overwritten, and pseudo-random bytes (with
    /// and without a valid header) give an error or a value, never a panic; truncations always
    /// an error.
    #[test]
    fn truncated_corrupt_and_random_bytes_give_an_error_not_a_panic() {
        let path = Path::new("fuzz.snap");
        let bytes = snapshot_bytes(&seed_mesh());
        for cut in 0..bytes.len() {
            let err = parse::<Mesh>(&bytes[..cut], path).unwrap_err();
            assert!(matches!(err, IoError::Snapshot { .. }), "cut {cut}: {err}");
        }
        for at in 0..bytes.len() {
            for byte in [0x00, 0x7f, 0xff] {
                let mut b = bytes.clone();
                b[at] = byte;
                let _ = parse::<Mesh>(&b, path);
            }
        }
        let header_len = bytes.len() - options().serialize(&seed_mesh()).unwrap().len();
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for round in 0..2000 {
            let len = round % 300;
            let mut b: Vec<u8> = (0..len)
                .map(|_| {
                    // xorshift64
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    state as u8
                })
                .collect();
            if round % 2 == 1 {
                b.splice(0..0, bytes[..header_len].iter().copied());
            }
            let err = parse::<Mesh>(&b, path).unwrap_err();
            assert!(
                matches!(err, IoError::Snapshot { .. }),
                "round {round}: {err}"
            );
        }
    }

    /// A length prefix claiming far more elements than the bytes hold is an error, not an
    /// allocation of that many (which would abort the process).
    #[test]
    fn a_hostile_length_prefix_is_an_error_not_an_allocation() {
        let path = Path::new("hostile.snap");
        let mut bytes = snapshot_bytes(&vec![1.5f64, 2.5]);
        let at = bytes.len() - 2 * 8 - 8; // the vector's u64 length
        for len in [3u64, 1 << 40, 1 << 60, u64::MAX] {
            bytes[at..at + 8].copy_from_slice(&len.to_le_bytes());
            let err = parse::<Vec<f64>>(&bytes, path).unwrap_err();
            assert!(matches!(err, IoError::Snapshot { .. }), "{len}: {err}");
        }
        // in a mesh: its node count (after `dim`, a u32 variant index, and `order`, a u8)
        let mut bytes = snapshot_bytes(&seed_mesh());
        let at = bytes.len() - options().serialize(&seed_mesh()).unwrap().len() + 5;
        let nodes = seed_mesh().nodes.len() as u64;
        assert_eq!(
            bytes[at..at + 8],
            nodes.to_le_bytes(),
            "the node count's place"
        );
        for len in [1u64 << 40, u64::MAX] {
            bytes[at..at + 8].copy_from_slice(&len.to_le_bytes());
            let err = parse::<Mesh>(&bytes, path).unwrap_err();
            assert!(matches!(err, IoError::Snapshot { .. }), "{len}: {err}");
        }
        // and a string: a patch name
        let mut m = seed_mesh();
        m.patches[0].name = "ABCDEFGH".into();
        let mut bytes = snapshot_bytes(&m);
        let name = bytes.windows(8).position(|w| w == b"ABCDEFGH").unwrap();
        bytes[name - 8..name].copy_from_slice(&u64::MAX.to_le_bytes());
        let err = parse::<Mesh>(&bytes, path).unwrap_err();
        assert!(matches!(err, IoError::Snapshot { .. }), "{err}");
    }

    /// The fuzz seed `tests/data/annulus_p1.snap` (run by `fuzz/run.sh`) is a snapshot this
    /// build reads. When the format or `Mesh` changes, rewrite it with
    /// `UPDATE_SEED=1 cargo test -p mesh-io --lib the_fuzz_seed`.
    #[test]
    fn the_fuzz_seed_is_a_current_snapshot() {
        if std::env::var_os("UPDATE_SEED").is_some() {
            save(&seed_path(), &seed_mesh()).unwrap();
        }
        let back: Mesh = load(&seed_path()).unwrap();
        assert_eq!(back, seed_mesh());
    }
}
