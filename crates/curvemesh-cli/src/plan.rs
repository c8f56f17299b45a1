//! The output flags of a run (`--out`, `--report`, `--snapshot`, `--png`, `--svg`) checked
//! and every output file reserved before any work, so that a bad flag, an unwritable folder
//! or two outputs on one file are refused at once. Without `--out`, the mesh and the report
//! go to `out/STEM.msh` and `out/STEM.json` ([`default_stem`]: an order other than the case's
//! is in the name, so that a picture run at P1 does not replace the P3 mesh of the case).

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

/// The stem of a run's default outputs: the case's `stem`, with `-pN` when the order `asked`
/// is not the case's own `order` (`out/30p30n-p1.msh` beside the default `out/30p30n.msh`).
pub fn default_stem(stem: &str, asked: Option<u8>, order: u8) -> String {
    match asked {
        Some(p) if p != order => format!("{stem}-p{p}"),
        _ => stem.to_string(),
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_order_other_than_the_cases_is_in_the_default_name() {
        assert_eq!(default_stem("30p30n", None, 3), "30p30n");
        assert_eq!(default_stem("30p30n", Some(3), 3), "30p30n");
        assert_eq!(default_stem("30p30n", Some(1), 3), "30p30n-p1");
        assert_eq!(default_stem("sphere-moved", Some(2), 1), "sphere-moved-p2");
    }
}
