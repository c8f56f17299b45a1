//! Pictures of the mesh (`--png`, `--svg`): parsing what was asked for and reserving the files
//! before any work is done, and drawing each picture into its reserved file at the end. Drawing is `mesh-draw`'s job.

use std::collections::BTreeMap;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use curvemesh::outputs::{Output, Outputs};
use mesh_draw::slice::Plane;
use mesh_draw::{ColourBy, DrawParams, View};
use mesh_model::{Mesh, Role, Shape};

pub use crate::cli::Colour;
use crate::cli::PictureArgs;

/// Picture formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Raster, drawn with tiny-skia.
    Png,
    /// Vector text.
    Svg,
}

/// One picture to draw: where, what part of the plane.
#[derive(Debug, Clone)]
pub struct Picture {
    /// The file to write.
    pub path: PathBuf,
    /// PNG or SVG.
    pub format: Format,
    /// The view as given (a name or four numbers), for the title.
    pub view_name: String,
    /// What part of the plane to show.
    pub view: ViewSpec,
}

/// A view not yet tied to a mesh.
#[derive(Debug, Clone, Copy)]
pub enum ViewSpec {
    /// The whole mesh.
    All,
    /// The bounding box of every wall loop.
    Walls,
    /// A rectangle of the plane.
    Rect(View),
}

/// Parses `FILE` or `FILE@VIEW` of each `--png` and `--svg`; `VIEW` is a name (`all`, `walls`, or a
/// view of the case's `[views]`) or `x0,y0,x1,y1`. `--view` applies where no `@VIEW` is given.
pub fn parse(args: &PictureArgs, named: &BTreeMap<String, [f64; 4]>) -> Result<Vec<Picture>> {
    if let Some(slice) = &args.slice {
        bail!("--slice {slice}: applies to 3D cases (dimension = 3)");
    }
    parse_files(args, named)
}

/// [`parse`] without the 2D check: the pictures of a 3D run and the plane they cut through
/// the mesh (`--slice`, default z through the middle of the mesh: `None`).
pub fn parse_3d(args: &PictureArgs) -> Result<(Vec<Picture>, Option<Plane>)> {
    let plane = match &args.slice {
        None => None,
        Some(spec) => {
            let fail = || anyhow::anyhow!("--slice {spec}: give x=C, y=C or z=C (C a number)");
            let (axis, at) = spec.split_once('=').ok_or_else(fail)?;
            let axis = ["x", "y", "z"]
                .iter()
                .position(|a| a.eq_ignore_ascii_case(axis.trim()))
                .ok_or_else(fail)?;
            let at: f64 = at.trim().parse().map_err(|_| fail())?;
            if !at.is_finite() {
                return Err(fail());
            }
            Some(Plane { axis, at })
        }
    };
    if let Some(c @ (Colour::Angle | Colour::Jacobian)) = args.colour {
        bail!("--colour {c:?}: 3D slices are coloured by type, layer, dihedral or none");
    }
    Ok((parse_files(args, &BTreeMap::new())?, plane))
}

/// The pictures' files and views without the checks of [`parse`] and [`parse_3d`]: for
/// `quality`, which reserves the files before it reads the mesh that tells which applies.
pub fn parse_files_only(args: &PictureArgs) -> Result<Vec<Picture>> {
    parse_files(args, &BTreeMap::new())
}

fn parse_files(args: &PictureArgs, named: &BTreeMap<String, [f64; 4]>) -> Result<Vec<Picture>> {
    let (pngs, svgs, default_view) = (&args.pngs, &args.svgs, args.view.as_deref());
    let mut pictures = Vec::new();
    for (specs, format, flag) in [(pngs, Format::Png, "--png"), (svgs, Format::Svg, "--svg")] {
        for spec in specs {
            let (file, view) = match spec.rsplit_once('@') {
                Some((file, view)) => (file, view),
                None => (spec.as_str(), default_view.unwrap_or("all")),
            };
            let path = PathBuf::from(file);
            let ext = if format == Format::Png { "png" } else { "svg" };
            if path
                .extension()
                .is_none_or(|e| !e.eq_ignore_ascii_case(ext))
            {
                bail!("{flag} {file}: the file name must end in .{ext}");
            }
            let view_spec = view_spec(view, named).with_context(|| format!("{flag} {spec}"))?;
            pictures.push(Picture {
                path,
                format,
                view_name: view.to_string(),
                view: view_spec,
            });
        }
    }
    Ok(pictures)
}

fn view_spec(view: &str, named: &BTreeMap<String, [f64; 4]>) -> Result<ViewSpec> {
    match view {
        "all" => return Ok(ViewSpec::All),
        "walls" => return Ok(ViewSpec::Walls),
        _ => {}
    }
    let rect = if let Some(r) = named.get(view) {
        *r
    } else if view.contains(',') {
        let numbers: Vec<f64> = view
            .split(',')
            .map(|v| v.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .with_context(|| format!("view '{view}' is not four numbers x0,y0,x1,y1"))?;
        let Ok(r) = <[f64; 4]>::try_from(numbers) else {
            bail!("view '{view}' is not four numbers x0,y0,x1,y1");
        };
        r
    } else {
        let mut names: Vec<&str> = vec!["all", "walls"];
        names.extend(named.keys().map(String::as_str));
        bail!(
            "no view named '{view}' (this case has: {})",
            names.join(", ")
        );
    };
    let v = View {
        x0: rect[0],
        y0: rect[1],
        x1: rect[2],
        y1: rect[3],
    };
    v.check()
        .map_err(|e| anyhow::anyhow!("view '{view}': {e}"))?;
    Ok(ViewSpec::Rect(v))
}

/// Reserves the file of every picture in `outputs`, in order.
pub fn reserve(pictures: &[Picture], outputs: &mut Outputs) -> Result<Vec<Output>> {
    pictures
        .iter()
        .map(|p| {
            let flag = if p.format == Format::Png {
                "--png"
            } else {
                "--svg"
            };
            outputs.reserve(flag, &p.path)
        })
        .collect::<curvemesh::Result<_>>()
        .map_err(Into::into)
}

/// Draws every picture of `mesh` (its last `fill_cells` cells its filled region), coloured
/// as the flags say or else by `default_colour`, into its reserved output; `scaled_jacobian`
/// holds one value per cell for [`Colour::Jacobian`].
pub fn draw_all(
    (mesh, fill_cells): (&Mesh, usize),
    pictures: &[(Picture, Output)],
    args: &PictureArgs,
    default_colour: Colour,
    title: &str,
    scaled_jacobian: &[f64],
    outputs: &mut Outputs,
) -> Result<()> {
    let colour_by = |colour| {
        Ok(match colour {
            Colour::Layer if mesh.cell_layer.len() == mesh.cells.len() => ColourBy::Layer,
            Colour::None | Colour::Layer => ColourBy::None,
            Colour::Angle => ColourBy::MaxAngle,
            Colour::Jacobian => ColourBy::ScaledJacobian(scaled_jacobian.to_vec()),
            Colour::Type | Colour::Dihedral => {
                bail!("--colour {colour:?}: applies to 3D slices")
            }
        })
    };
    let colour = args.colour.unwrap_or(default_colour);
    let colour = (colour_by(colour)?, fill_cells);
    draw_each(mesh, pictures, args, colour, title, outputs)
}

/// Draws every picture of a 3D run: the cut of `mesh` by `plane` (default z through the
/// middle of the mesh's nodes), coloured as the flags say (default by cell type; by layer
/// only when the mesh has layers, else uncoloured).
pub fn draw_slices(
    mesh: &Mesh,
    pictures: &[(Picture, Output)],
    args: &PictureArgs,
    plane: Option<Plane>,
    title: &str,
    outputs: &mut Outputs,
) -> Result<()> {
    if pictures.is_empty() {
        return Ok(());
    }
    if let Some(problem) = mesh_model::first_structural_problem(mesh) {
        bail!("cannot slice the mesh to draw it: {problem}");
    }
    let plane = plane.unwrap_or_else(|| {
        let (lo, hi) = mesh.nodes.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
            (lo.min(p[2]), hi.max(p[2]))
        });
        Plane {
            axis: 2,
            at: 0.5 * (lo + hi),
        }
    });
    let cut = mesh_draw::slice::slice(mesh, plane)?;
    let of_cell = |i: &u32| mesh.cells.get(*i as usize);
    let colour = match args.colour.unwrap_or(Colour::Type) {
        Colour::Type => {
            let shapes = [Shape::Tet, Shape::Pyramid, Shape::Prism, Shape::Hex];
            ColourBy::Categories {
                values: cut
                    .cell_of
                    .iter()
                    .map(|i| {
                        shapes
                            .iter()
                            .position(|&s| s == of_cell(i).ty.shape)
                            .unwrap_or(4) as u32
                    })
                    .collect(),
                names: shapes.iter().map(|s| s.name().to_string()).collect(),
                label: "cell type".into(),
            }
        }
        Colour::Dihedral => ColourBy::CellValues {
            values: cut
                .cell_of
                .iter()
                .map(|&i| match of_cell(&i).ty.shape {
                    Shape::Tet => mesh_model::measure3d::tet_max_dihedral_deg(mesh, i as usize),
                    _ => f64::NAN,
                })
                .collect(),
            label: "max dihedral".into(),
        },
        // a mesh read back has no layers: drawn uncoloured, as in 2D
        Colour::Layer if mesh.cell_layer.len() == mesh.cells.len() => ColourBy::Layer,
        _ => ColourBy::None,
    };
    let axis = ["x", "y", "z"][plane.axis];
    let title = format!("{title}, slice {axis} = {}", plane.at);
    // (a slice's fill cells have no layer)
    draw_each(&cut.mesh, pictures, args, (colour, 0), &title, outputs)
}

/// Draws every picture of the 2D `mesh` coloured by `colour` (its last `fill_cells` cells
/// its filled region), into its reserved output.
fn draw_each(
    mesh: &Mesh,
    pictures: &[(Picture, Output)],
    args: &PictureArgs,
    (colour, fill_cells): (ColourBy, usize),
    title: &str,
    outputs: &mut Outputs,
) -> Result<()> {
    let width_px = args.width;
    for (p, output) in pictures {
        let view = match p.view {
            ViewSpec::All => None,
            ViewSpec::Walls => Some(
                mesh_draw::view_of_role(mesh, Role::Wall, 0.05)
                    .or_else(|_| mesh_draw::mesh_view(mesh, 0.04))?,
            ),
            ViewSpec::Rect(v) => Some(v),
        };
        let params = DrawParams {
            width_px,
            height_px: width_px * 3 / 4,
            view,
            colour: colour.clone(),
            title: Some(format!("{title}, view {}", p.view_name)),
            fill_cells,
            ..DrawParams::default()
        };
        let bytes = match p.format {
            Format::Png => mesh_draw::render_png(mesh, &params),
            Format::Svg => mesh_draw::render_svg(mesh, &params).map(String::into_bytes),
        }
        .map_err(|e| anyhow::anyhow!("drawing {}: {e}", p.path.display()))?;
        outputs.write_bytes(*output, &bytes)?;
    }
    Ok(())
}
