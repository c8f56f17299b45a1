//! Loading a case by name or path: a built-in case, or a `.toml` case file, 2D or 3D as its
//! top-level `dimension` says.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::builtin;
use crate::case::Case;
use crate::case3d::Case3d;
use crate::error::{Context, Result, bail};
use crate::source::FileSource;

/// A 2D or a 3D case.
#[derive(Debug, Clone)]
pub enum AnyCase {
    /// `dimension = 2` (the default).
    Two(Case),
    /// `dimension = 3`.
    Three(Case3d),
}

/// Loads a 2D case: `spec` is a path to a `.toml` file or the name of a built-in case; a 3D
/// case is refused with one line.
pub fn load_2d(spec: &str) -> Result<Case> {
    match load(spec)? {
        AnyCase::Two(case) => Ok(case),
        AnyCase::Three(case) => bail!(
            "{}: a 3D case (dimension = 3): this command takes 2D cases only",
            case.origin
        ),
    }
}

/// Loads a 2D or 3D case: `spec` is a path to a `.toml` file or the name of a built-in case.
pub fn load(spec: &str) -> Result<AnyCase> {
    if let Some(text) = builtin::case_text(spec) {
        return parse_any(text, spec, FileSource::Builtin, spec);
    }
    let path = PathBuf::from(spec);
    if path.extension().is_none_or(|e| e != "toml") && !path.exists() {
        bail!(
            "'{spec}' is neither a built-in case ({}) nor a case file (.toml) nor airfoil \
             coordinates (.dat or .txt)",
            builtin::all_names().join(", ")
        );
    }
    let text = std::fs::read_to_string(&path)
        .with_context(|| format!("cannot read case file {}", path.display()))?;
    let dir = path.parent().unwrap_or(Path::new("."));
    let stem = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("case")
        .to_string();
    parse_any(
        &text,
        &path.display().to_string(),
        FileSource::Dir(dir),
        &stem,
    )
}

/// Parses a 2D or 3D case from TOML text without touching the disk: a file it names must be a
/// built-in data file (for the fuzz target and tests). The case is named `case` unless it
/// says.
pub fn parse_str(text: &str) -> Result<AnyCase> {
    parse_any(text, "case", FileSource::Builtin, "case")
}

/// Parses a 2D or 3D case from TOML text whose relative file names are looked up in `dir` (a
/// case made in memory, as the Python package's dicts): `origin` names it in messages, and it
/// is named `case` unless it says.
pub fn parse_str_in(text: &str, origin: &str, dir: &Path) -> Result<AnyCase> {
    parse_any(text, origin, FileSource::Dir(dir), "case")
}

/// The case in `text`: 3D when its top-level `dimension` is 3, else 2D.
fn parse_any(
    text: &str,
    origin: &str,
    files: FileSource<'_>,
    default_name: &str,
) -> Result<AnyCase> {
    /// Reads `dimension` alone (every other key ignored here).
    #[derive(Deserialize)]
    struct Probe {
        dimension: Option<toml::Value>,
    }
    let probe = toml::from_str::<Probe>(text).ok().and_then(|p| p.dimension);
    if probe.and_then(|d| d.as_integer()) == Some(3) {
        return crate::case3d::parse(text, origin, &files, default_name).map(AnyCase::Three);
    }
    crate::case::parse(text, origin, files, default_name).map(AnyCase::Two)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builtin::{DEFAULT, case_text, names, names_3d};

    #[test]
    fn every_builtin_case_loads() {
        for name in names() {
            let case = load_2d(name);
            assert!(
                case.is_ok(),
                "{name}: {:#}",
                case.err().map(|e| e.to_string()).unwrap_or_default()
            );
        }
        assert!(case_text(DEFAULT).is_some());
        for name in names_3d() {
            let case = load(name);
            assert!(matches!(case, Ok(AnyCase::Three(_))), "{name}: {case:?}");
        }
    }
}
