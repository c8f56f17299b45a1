//! Where a case's text and files come from, shared by the 2D and 3D case files: the folder
//! (or the built-in data) its relative file names are looked up in, the TOML reader whose
//! errors name the line at fault, and a name made safe for file names.

use std::path::Path;

use crate::error::{Result, input_error};

/// Where a case's relative file names are looked up.
pub enum FileSource<'a> {
    /// On disk, relative to the case file's folder.
    Dir(&'a Path),
    /// Embedded in the binary (built-in cases).
    Builtin,
}

/// TOML `text` read as a `T`; an error names `origin` and the line at fault, on one line.
pub fn from_toml<T: serde::de::DeserializeOwned>(text: &str, origin: &str) -> Result<T> {
    toml::from_str(text).map_err(|e| {
        let msg = e.message().trim().to_string();
        match e.span() {
            Some(span) => {
                let line = text[..span.start].matches('\n').count() + 1;
                input_error!("{origin}, line {line}: {msg}")
            }
            None => input_error!("{origin}: {msg}"),
        }
    })
}

/// `name` made safe as a file name: characters other than ASCII letters, digits, `.`, `_`
/// and `-` become `_`, leading dots are dropped, an empty result is `case`. So a case named
/// `../escape` writes `out/_escape.msh`, inside `out/`.
pub fn file_stem_of(name: &str) -> String {
    let safe: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-') {
                c
            } else {
                '_'
            }
        })
        .collect();
    let safe = safe.trim_start_matches('.');
    if safe.is_empty() {
        "case".to_string()
    } else {
        safe.to_string()
    }
}
