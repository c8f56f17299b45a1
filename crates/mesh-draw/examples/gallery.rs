//! Writes a gallery of pictures of the test meshes (annulus P1–P3, NACA 0012 O-mesh) in every
//! colouring, whole and zoomed, as PNG and SVG, to look at by eye:
//! `cargo run -p mesh-draw --example gallery -- OUT_DIR`.

#[path = "../tests/common/mod.rs"]
mod common;

use common::{Annulus, annulus, naca0012_o_mesh};
use mesh_draw::{
    ColourBy, DrawParams, max_angle_deg, render_png, render_svg, view_around, view_of_role,
};
use mesh_model::Role;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::path::PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "gallery".into()));
    std::fs::create_dir_all(&out)?;
    let write = |name: &str,
                 mesh: &mesh_model::Mesh,
                 params: &DrawParams|
     -> Result<(), Box<dyn std::error::Error>> {
        std::fs::write(out.join(format!("{name}.png")), render_png(mesh, params)?)?;
        std::fs::write(out.join(format!("{name}.svg")), render_svg(mesh, params)?)?;
        Ok(())
    };
    let ring = |order, jitter| {
        annulus(&Annulus {
            around: 48,
            quad_rings: 14,
            tri_rings: 6,
            order,
            jitter,
        })
    };
    let p1 = ring(1, 0.3);
    let base = DrawParams {
        width_px: 1000,
        height_px: 750,
        ..DrawParams::default()
    };
    write(
        "annulus-p1-edges",
        &p1,
        &DrawParams {
            title: Some("Annulus P1, edges only".into()),
            ..base.clone()
        },
    )?;
    write(
        "annulus-p1-layer",
        &p1,
        &DrawParams {
            colour: ColourBy::Layer,
            title: Some("Layers".into()),
            ..base.clone()
        },
    )?;
    write(
        "annulus-p1-angle",
        &p1,
        &DrawParams {
            colour: ColourBy::MaxAngle,
            title: Some("Max angle".into()),
            ..base.clone()
        },
    )?;
    let values: Vec<f64> = (0..p1.cells.len())
        .map(|i| ((i as f64) * 0.37).sin() * 1.1)
        .collect();
    write(
        "annulus-p1-jacobian",
        &p1,
        &DrawParams {
            colour: ColourBy::ScaledJacobian(values),
            ..base.clone()
        },
    )?;
    let p3 = ring(3, 0.0);
    let zoom = view_around([0.5, 0.0], 0.12);
    write(
        "annulus-p3-zoom",
        &p3,
        &DrawParams {
            view: Some(zoom),
            colour: ColourBy::Layer,
            title: Some("P3 curved cells, zoomed".into()),
            ..base.clone()
        },
    )?;
    let p2 = ring(2, 0.0);
    write(
        "annulus-p2-whole",
        &p2,
        &DrawParams {
            title: Some("P2".into()),
            ..base.clone()
        },
    )?;
    let naca = naca0012_o_mesh(40);
    let angles = max_angle_deg(&naca);
    write(
        "naca-whole",
        &naca,
        &DrawParams {
            colour: ColourBy::Layer,
            title: Some("NACA 0012 O-mesh".into()),
            ..base.clone()
        },
    )?;
    let wall = view_of_role(&naca, Role::Wall, 0.05)?;
    write(
        "naca-wall",
        &naca,
        &DrawParams {
            view: Some(wall),
            colour: ColourBy::CellValues {
                values: angles,
                label: "max angle (deg)".into(),
            },
            ..base.clone()
        },
    )?;
    write(
        "naca-le",
        &naca,
        &DrawParams {
            view: Some(view_around([0.0, 0.0], 0.02)),
            colour: ColourBy::MaxAngle,
            ..base.clone()
        },
    )?;
    write(
        "small",
        &p1,
        &DrawParams {
            width_px: 240,
            height_px: 180,
            colour: ColourBy::MaxAngle,
            ..base.clone()
        },
    )?;
    for (i, line) in [
        "ABCDEFGHIJKLMNOPQRSTUVWXYZ 0123456789",
        "abcdefghijklmnopqrstuvwxyz .,-+=:;()[]/°%_×'\"!?<>#*|μ",
    ]
    .iter()
    .enumerate()
    {
        write(
            &format!("font-{i}"),
            &p1,
            &DrawParams {
                width_px: 1400,
                height_px: 300,
                view: Some(view_around([0.0, 5.0], 0.1)),
                title: Some((*line).into()),
                show_scale_bar: false,
                ..base.clone()
            },
        )?;
    }
    let big = annulus(&Annulus {
        around: 625,
        quad_rings: 80,
        tri_rings: 40,
        order: 1,
        jitter: 0.2,
    });
    write(
        "big-100k-layer",
        &big,
        &DrawParams {
            width_px: 2000,
            height_px: 1500,
            colour: ColourBy::Layer,
            title: Some("100k cells".into()),
            ..base.clone()
        },
    )?;
    Ok(())
}
