//! The output flags of a run (`--out`, `--report`, `--snapshot`, `--png`, `--svg`) checked
//! and every output file reserved before any work, so that a bad flag, an unwritable folder
//! or two outputs on one file are refused at once. Without `--out`, the mesh and the report
//! go to `out/STEM.msh` and `out/STEM.json`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Result, bail};
use curvemesh::outputs::{Output, Outputs, Plan};
use mesh_io::Format;

use crate::cli::PictureArgs;
use crate::pictures::{self, Picture};

/// The files a run will write, reserved: the library's [`Plan`] and the pictures.
pub struct Planned {
    /// The meshes, the snapshot and the report, with every output reserved.
    pub plan: Plan,
    /// The pictures, each with its reserved output.
    pub pictures: Vec<(Picture, Output)>,
}

/// The flags that name the outputs of a run.
pub struct OutputFlags<'a> {
    /// `--out`, each.
    pub outs: &'a [PathBuf],
    /// `--report`.
    pub report: Option<&'a Path>,
    /// `--snapshot` (written).
    pub snapshot: Option<&'a Path>,
    /// `--png`, `--svg` and their options.
    pub pictures: &'a PictureArgs,
}

/// Checks every output flag and reserves every output file (meshes, snapshot, pictures,
/// report); `stem` names the default outputs, `views` are the case's named views.
pub fn plan(
    flags: &OutputFlags<'_>,
    stem: &str,
    views: &BTreeMap<String, [f64; 4]>,
) -> Result<Planned> {
    plan_with(flags, stem, || pictures::parse(flags.pictures, views))
}

/// [`plan`] with the pictures parsed by `pictures` (after the mesh and report flags).
pub fn plan_with(
    flags: &OutputFlags<'_>,
    stem: &str,
    pictures: impl FnOnce() -> Result<Vec<Picture>>,
) -> Result<Planned> {
    let (outs, report_path) = outputs(flags, stem)?;
    let pictures = pictures()?;
    let mut outputs = Outputs::new();
    let meshes = outs
        .into_iter()
        .map(|p| outputs.reserve("--out", &p).map(|o| (p, o)))
        .collect::<curvemesh::Result<Vec<_>>>()?;
    let snapshot = match flags.snapshot {
        Some(p) => Some((p.to_path_buf(), outputs.reserve("--snapshot", p)?)),
        None => None,
    };
    let picture_outputs = pictures::reserve(&pictures, &mut outputs)?;
    let report = match report_path {
        Some(p) => {
            let o = outputs.reserve("--report", &p)?;
            Some((p, o))
        }
        None => None,
    };
    Ok(Planned {
        plan: Plan {
            outputs,
            meshes,
            snapshot,
            report,
            binary: false,
        },
        pictures: pictures.into_iter().zip(picture_outputs).collect(),
    })
}

/// The mesh files and the report to write, by flags or by default (under `out/`, named after
/// `stem`); checked before any work is done.
fn outputs(flags: &OutputFlags<'_>, stem: &str) -> Result<(Vec<PathBuf>, Option<PathBuf>)> {
    let defaulted = flags.outs.is_empty();
    let outs = if defaulted {
        vec![PathBuf::from(format!("out/{stem}.msh"))]
    } else {
        flags.outs.to_vec()
    };
    for out in &outs {
        if Format::from_path(out).is_none() {
            bail!(
                "--out {}: unknown extension: use .msh (Gmsh), .vtu (VTK) or .su2 (SU2)",
                out.display()
            );
        }
    }
    let report = match flags.report {
        Some(r) if r.extension().is_none_or(|e| e != "json") => {
            bail!(
                "--report {}: the report is JSON: give a .json file name",
                r.display()
            )
        }
        Some(r) => Some(r.to_path_buf()),
        None if defaulted => Some(PathBuf::from(format!("out/{stem}.json"))),
        None => None,
    };
    Ok((outs, report))
}
