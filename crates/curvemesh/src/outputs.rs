//! The output files of one command, written all together or not at all: a
//! `mesh_io::atomic::Transaction` whose outputs carry the flag that named them, for messages.
//!
//! A command reserves every output before it starts work (so that an unwritable folder or two
//! outputs on one file are refused at once, and cost nothing), writes each one when its
//! content is ready, and commits at the end. Dropping the [`Outputs`] uncommitted — any error
//! on the way — removes every temporary file and every folder it created; no earlier file is
//! touched.

use std::path::{Path, PathBuf};

pub use crate::source::file_stem_of;

use crate::error::{Context, Error, Result, bail};
use crate::report::Report;
use crate::stages::Snapshot;
use std::time::Instant;

use mesh_io::atomic::{OutputId, Transaction};
use mesh_io::{Format, IoError};
use mesh_model::Mesh;

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
                bail!("{label} is the same file as {earlier}: give each output its own file")
            }
            Err(e) => Err(Error::from(e).context(format!("{label}: cannot write there"))),
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

/// The files of one run, reserved before any work: the meshes (each in the format of its
/// extension), the snapshot and the report, with the rest of the run's outputs (pictures) in
/// the same [`Outputs`] so that all are put in place together.
#[derive(Debug)]
pub struct Plan {
    /// Every reserved output.
    pub outputs: Outputs,
    /// The mesh files.
    pub meshes: Vec<(PathBuf, Output)>,
    /// The snapshot, if one is to be written.
    pub snapshot: Option<(PathBuf, Output)>,
    /// The report, if one is to be written.
    pub report: Option<(PathBuf, Output)>,
    /// The `.msh` outputs in binary MSH 4.1.
    pub binary: bool,
}

impl Plan {
    /// Writes `mesh` into every reserved mesh output, each in its format (`.msh` binary when
    /// [`Plan::binary`]). Returns each file written with its format.
    pub fn write_meshes(&mut self, mesh: &Mesh) -> Result<Vec<(PathBuf, Format)>> {
        let mut wrote = Vec::new();
        for (path, output) in &self.meshes {
            let binary = self.binary && Format::from_path(path) == Some(Format::Msh);
            self.outputs.write_with(*output, |w| {
                if binary {
                    mesh_io::msh::write_binary_to(w, mesh, path)
                } else {
                    mesh_io::write_to(w, path, mesh)
                }
            })?;
            if let Some(format) = Format::from_path(path) {
                wrote.push((path.clone(), format));
            }
        }
        Ok(wrote)
    }

    /// Writes the meshes ([`Plan::write_meshes`]) and, when reserved, the snapshot `stages`.
    /// Returns each mesh file written with its format, and the seconds it took.
    pub fn write_meshes_and_snapshot(
        &mut self,
        mesh: &Mesh,
        stages: Option<&Snapshot>,
    ) -> Result<(Vec<(PathBuf, Format)>, f64)> {
        let t = Instant::now();
        let wrote = self.write_meshes(mesh)?;
        if let (Some((path, output)), Some(stages)) = (&self.snapshot, stages) {
            let (path, output) = (path.clone(), *output);
            self.outputs
                .write_with(output, |w| mesh_io::snapshot::save_to(w, stages, &path))?;
        }
        Ok((wrote, t.elapsed().as_secs_f64()))
    }

    /// The end of a run: the files into the report, the report written, every output put
    /// in place. Returns the path of the report, if written.
    pub fn commit(mut self, report: &mut Report) -> Result<Option<PathBuf>> {
        report.files = self.outputs.files();
        if let Some((_, output)) = &self.report {
            self.outputs.write_bytes(*output, &report.json()?)?;
        }
        self.outputs.commit()?;
        Ok(self.report.map(|(p, _)| p))
    }
}
