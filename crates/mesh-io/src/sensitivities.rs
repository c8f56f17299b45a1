//! The mesh sensitivities file: for each node of a written mesh, its position and its
//! derivative with respect to each design variable, as CSV.
//!
//! Layout: a header line `node,x,y,d_<var>_x,d_<var>_y,...`, then one line per node in the
//! mesh file's node order (node `i` is the `i+1`-th node of the `.msh`/`.vtu`/`.su2` written
//! with it): its number from 1, its coordinates, and for every variable the two components
//! of `dX/dα`. Numbers are written shortest-round-trip, so they read back exactly.

use std::path::Path;

use crate::IoError;
use crate::atomic::write_atomic;

/// Writes the sensitivities of `positions` to `variables` (their names, and for each one
/// derivative per node) to `path`, atomically.
///
/// # Errors
/// [`IoError::Io`] when the file cannot be written, or (kind `InvalidInput`, nothing
/// written) when a column does not have one entry per node or a name is empty or holds a
/// comma.
pub fn write_sensitivities(
    path: &Path,
    positions: &[[f64; 2]],
    variables: &[(String, Vec<[f64; 2]>)],
) -> Result<(), IoError> {
    for (name, column) in variables {
        if column.len() != positions.len() || name.is_empty() || name.contains([',', '\n']) {
            return Err(IoError::Io {
                path: path.to_path_buf(),
                source: std::io::Error::new(
                    std::io::ErrorKind::InvalidInput,
                    format!(
                        "sensitivity column '{name}' has {} entries for {} nodes (or a bad name)",
                        column.len(),
                        positions.len()
                    ),
                ),
            });
        }
    }
    write_atomic(path, |out| {
        let io = |source| IoError::Io {
            path: path.to_path_buf(),
            source,
        };
        let mut line = String::from("node,x,y");
        for (name, _) in variables {
            line.push_str(&format!(",d_{name}_x,d_{name}_y"));
        }
        writeln!(out, "{line}").map_err(io)?;
        for (i, p) in positions.iter().enumerate() {
            line.clear();
            line.push_str(&format!("{},{:?},{:?}", i + 1, p[0], p[1]));
            for (_, column) in variables {
                line.push_str(&format!(",{:?},{:?}", column[i][0], column[i][1]));
            }
            writeln!(out, "{line}").map_err(io)?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_file_has_a_header_and_one_exact_line_per_node() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.csv");
        let x = [[0.1, 0.2], [1.0, -3.5e-7]];
        let cols = vec![("a".to_string(), vec![[1.0, 0.0], [0.5, 1.0 / 3.0]])];
        write_sensitivities(&path, &x, &cols).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "node,x,y,d_a_x,d_a_y");
        assert_eq!(lines[2], "2,1.0,-3.5e-7,0.5,0.3333333333333333");
        let bad = vec![("b".to_string(), vec![[1.0, 0.0]])];
        assert!(write_sensitivities(&dir.path().join("t.csv"), &x, &bad).is_err());
        assert!(!dir.path().join("t.csv").exists());
    }
}
