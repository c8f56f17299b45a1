//! The output files of one command, written all together or not at all: a
//! `mesh_io::atomic::Transaction` whose outputs carry the flag that named them, for messages.
//!
//! A command reserves every output before it starts work (so that an unwritable folder or two
//! outputs on one file are refused at once, and cost nothing), writes each one when its
//! content is ready, and commits at the end. Dropping the [`Outputs`] uncommitted — any error
//! on the way — removes every temporary file and every folder it created; no earlier file is
//! touched.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use mesh_io::IoError;
use mesh_io::atomic::{OutputId, Transaction};

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

/// One reserved output.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Output {
    id: OutputId,
    /// Its place in the labels.
    index: usize,
}

/// The pending outputs of a command.
#[derive(Debug)]
pub struct Outputs {
    transaction: Transaction,
    /// `--flag path` of each output, in the order reserved.
    labels: Vec<(String, PathBuf)>,
}

impl Default for Outputs {
    fn default() -> Self {
        Outputs::new()
    }
}

impl Outputs {
    /// No outputs yet; folders of outputs are created as needed.
    pub fn new() -> Outputs {
        Outputs {
            transaction: Transaction::creating_folders(),
            labels: Vec::new(),
        }
    }

    /// Reserves `path`, named on the command line by `flag` (`--out`, `--png`, …).
    pub fn reserve(&mut self, flag: &str, path: &Path) -> Result<Output> {
        let label = format!("{flag} {}", path.display());
        match self.transaction.reserve(path) {
            Ok(id) => {
                self.labels.push((label, path.to_path_buf()));
                Ok(Output {
                    id,
                    index: self.labels.len() - 1,
                })
            }
            Err(IoError::DuplicateOutput { first, .. }) => {
                let earlier = self
                    .labels
                    .iter()
                    .find(|(_, p)| *p == first)
                    .map_or_else(|| first.display().to_string(), |(l, _)| l.clone());
                anyhow::bail!(
                    "{label} is the same file as {earlier}: give each output its own file"
                )
            }
            Err(e) => Err(anyhow::Error::new(e).context(format!("{label}: cannot write there"))),
        }
    }

    /// The files reserved so far, as shown in the report.
    pub fn files(&self) -> Vec<String> {
        self.labels
            .iter()
            .map(|(_, p)| p.display().to_string())
            .collect()
    }

    /// Writes the content of `output` with `fill`.
    pub fn write_with<F>(&mut self, output: Output, fill: F) -> Result<()>
    where
        F: FnOnce(&mut dyn std::io::Write) -> Result<(), IoError>,
    {
        let path = self.labels[output.index].1.clone();
        self.transaction
            .write(output.id, fill)
            .with_context(|| format!("writing {}", path.display()))
    }

    /// Writes `bytes` as the content of `output`.
    pub fn write_bytes(&mut self, output: Output, bytes: &[u8]) -> Result<()> {
        let path = self.labels[output.index].1.clone();
        self.write_with(output, |w| {
            w.write_all(bytes)
                .map_err(|source| IoError::Io { path, source })
        })
    }

    /// Puts every output in place (see `mesh_io::atomic::Transaction::commit`).
    pub fn commit(self) -> Result<()> {
        self.transaction
            .commit()
            .context("putting the output files in place")
    }
}
