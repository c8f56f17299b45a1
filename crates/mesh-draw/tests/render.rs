//! Pictures of hand-built meshes, checked by decoding them: size, content, colours, zoom,
//! curved edges, the SVG's structure, and refusals of bad requests.

mod common;

use std::collections::{HashMap, HashSet};

use common::{Annulus, R_WALL, annulus, naca0012_o_mesh};
use mesh_draw::{
    ColourBy, DrawError, DrawParams, View, render_png, render_rgba, render_svg, view_around,
    view_of_role,
};
use mesh_model::{CellType, Dim, Mesh, Problem, Role, Shape};
use proptest::prelude::*;
use tiny_skia::Pixmap;

fn small_annulus(order: u8) -> Mesh {
    annulus(&Annulus {
        around: 32,
        quad_rings: 8,
        tri_rings: 4,
        order,
        jitter: 0.25,
    })
}

fn params(width_px: u32, height_px: u32) -> DrawParams {
    DrawParams {
        width_px,
        height_px,
        ..DrawParams::default()
    }
}

fn decode(png: &[u8]) -> Pixmap {
    Pixmap::decode_png(png).expect("the PNG decodes")
}

fn rgb(p: &Pixmap) -> Vec<[u8; 3]> {
    p.pixels()
        .iter()
        .map(|c| [c.red(), c.green(), c.blue()])
        .collect()
}

const WHITE: [u8; 3] = [255, 255, 255];

/// Dark grey, like an edge: channels close together and dark.
fn is_edge_grey(c: [u8; 3]) -> bool {
    let (lo, hi) = (*c.iter().min().unwrap(), *c.iter().max().unwrap());
    hi < 140 && hi - lo < 12
}

#[test]
fn the_png_has_the_requested_size_and_shows_edges_and_both_boundaries() {
    let mesh = small_annulus(1);
    let png = render_png(&mesh, &params(640, 480)).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let pixmap = decode(&png);
    assert_eq!((pixmap.width(), pixmap.height()), (640, 480));
    let pixels = rgb(&pixmap);
    let non_white = pixels.iter().filter(|&&c| c != WHITE).count();
    assert!(
        non_white > pixels.len() / 20,
        "only {non_white} non-white pixels"
    );
    let edge = pixels.iter().filter(|&&c| is_edge_grey(c)).count();
    assert!(edge > 2000, "only {edge} edge-coloured pixels");
    let black = pixels.iter().filter(|c| c.iter().all(|&v| v < 30)).count();
    assert!(black > 500, "wall loop missing: {black} black pixels");
    let blue = pixels
        .iter()
        .filter(|c| c[2] > 100 && c[0] < 60 && c[2] > c[0] + 60)
        .count();
    assert!(blue > 500, "far-field loop missing: {blue} blue pixels");
    // The raw pixels agree with the PNG.
    let raw = render_rgba(&mesh, &params(640, 480)).unwrap();
    assert_eq!(raw, pixmap.data());
}

#[test]
fn a_zoomed_view_differs_from_the_whole_view() {
    let mesh = small_annulus(1);
    let whole = render_rgba(&mesh, &params(400, 300)).unwrap();
    let zoom = DrawParams {
        view: Some(view_around([R_WALL, 0.0], 0.05)),
        ..params(400, 300)
    };
    let zoomed = render_rgba(&mesh, &zoom).unwrap();
    assert_eq!(whole.len(), zoomed.len());
    let differing = whole
        .chunks(4)
        .zip(zoomed.chunks(4))
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        differing > whole.len() / 4 / 10,
        "only {differing} pixels differ"
    );
}

/// Colours covering at least `min_pixels` pixels, white left out.
fn large_areas(p: &Pixmap, min_pixels: usize) -> usize {
    let mut count: HashMap<[u8; 3], usize> = HashMap::new();
    for c in rgb(p) {
        if c != WHITE {
            *count.entry(c).or_default() += 1;
        }
    }
    count.values().filter(|&&n| n >= min_pixels).count()
}

#[test]
fn colouring_by_layer_shows_many_distinct_colours() {
    let mesh = small_annulus(1);
    let plain = decode(&render_png(&mesh, &params(600, 600)).unwrap());
    let by_layer = DrawParams {
        colour: ColourBy::Layer,
        ..params(600, 600)
    };
    let layered = decode(&render_png(&mesh, &by_layer).unwrap());
    // Colours covering at least 600 pixels: the edges-only picture has a few (the anti-aliased
    // edge greys), the layered one a colour per visible layer and the no-layer grey.
    let (plain_areas, layer_areas) = (large_areas(&plain, 600), large_areas(&layered, 600));
    assert!(layer_areas >= 6, "{layer_areas} large colour areas");
    assert!(
        layer_areas >= plain_areas + 4,
        "{plain_areas} vs {layer_areas}"
    );
}

#[test]
fn every_colouring_draws_and_a_jacobian_below_zero_is_red() {
    let mesh = small_annulus(2);
    let n = mesh.cells.len();
    let mut jacobian = vec![0.8; n];
    jacobian[..n / 2].fill(-0.5);
    for colour in [
        ColourBy::MaxAngle,
        ColourBy::ScaledJacobian(jacobian),
        ColourBy::CellValues {
            values: (0..n).map(|i| i as f64).collect(),
            label: "index".into(),
        },
    ] {
        let inverted = matches!(colour, ColourBy::ScaledJacobian(_));
        let p = DrawParams {
            colour,
            title: Some("Colours".into()),
            ..params(500, 400)
        };
        let pixels = rgb(&decode(&render_png(&mesh, &p).unwrap()));
        let red = pixels
            .iter()
            .filter(|c| c[0] > 180 && c[1] < 60 && c[2] < 60)
            .count();
        assert_eq!(inverted, red > 1000, "{red} red pixels");
        assert!(render_svg(&mesh, &p).unwrap().contains("<text"));
    }
}

#[test]
fn curved_edges_follow_the_circle_and_straight_ones_its_chord() {
    // Eight cells around: the chord between two wall nodes lies 0.038 inside the circle.
    let darkness_at_centre = |order: u8| {
        let mesh = annulus(&Annulus {
            around: 8,
            quad_rings: 2,
            tri_rings: 1,
            order,
            jitter: 0.0,
        });
        let a = std::f64::consts::PI / 8.0;
        let p = DrawParams {
            view: Some(view_around([R_WALL * a.cos(), R_WALL * a.sin()], 0.02)),
            show_scale_bar: false,
            // no legend column: the view's centre is the picture's
            show_legend: false,
            ..params(301, 301)
        };
        let pixmap = decode(&render_png(&mesh, &p).unwrap());
        let mut darkest = 255;
        for y in 148..=152 {
            for x in 148..=152 {
                let c = pixmap.pixel(x, y).unwrap();
                darkest = darkest.min(c.red().max(c.green()).max(c.blue()));
            }
        }
        darkest
    };
    assert!(darkness_at_centre(3) < 60, "P3 wall misses the circle");
    assert!(darkness_at_centre(2) < 60, "P2 wall misses the circle");
    assert_eq!(darkness_at_centre(1), 255, "P1 wall should be a chord");
}

/// Unique corner edges of the cells.
fn unique_edges(mesh: &Mesh) -> usize {
    let mut set = HashSet::new();
    for c in mesh.cells.iter() {
        let k = c.corners();
        for e in c.ty.shape.edges() {
            let (a, b) = (k[e[0]], k[e[1]]);
            set.insert((a.min(b), a.max(b)));
        }
    }
    set.len()
}

/// Number of drawing commands (segments) in a path's data.
fn segments(d: &str) -> usize {
    d.chars().filter(|c| matches!(c, 'l' | 'q' | 'c')).count()
}

#[test]
fn the_svg_parses_and_has_one_segment_per_visible_edge() {
    for order in [1, 3] {
        let mesh = small_annulus(order);
        let svg = render_svg(
            &mesh,
            &DrawParams {
                colour: ColourBy::Layer,
                title: Some("a <title> & more".into()),
                ..params(900, 900)
            },
        )
        .unwrap();
        let doc = roxmltree::Document::parse(&svg).expect("the SVG is well-formed XML");
        let root = doc.root_element();
        assert_eq!(root.tag_name().name(), "svg");
        assert_eq!(root.attribute("width"), Some("900"));
        let paths: Vec<_> = doc
            .descendants()
            .filter(|n| n.has_tag_name("path"))
            .collect();
        let by_id = |id: &str| {
            paths
                .iter()
                .find(|n| n.attribute("id") == Some(id))
                .and_then(|n| n.attribute("d"))
                .unwrap_or_else(|| panic!("no path {id}"))
        };
        // Edges: all in one path, one segment each, but those shorter than a pixel (the thin
        // first layers, seen whole) are left out.
        let expected = unique_edges(&mesh);
        let drawn = segments(by_id("edges"));
        assert!(
            drawn <= expected && drawn >= expected * 2 / 3,
            "P{order}: {drawn} edge segments for {expected} edges"
        );
        assert_eq!(by_id("edges").contains('c'), order == 3);
        // One segment per boundary facet of each role.
        assert_eq!(segments(by_id("wall")), 32);
        assert_eq!(segments(by_id("farfield")), 32);
        // Fills: one path per colour (8 layers, lighter odd ones, grey): about ten, not one
        // per cell.
        let fills = paths.iter().filter(|n| n.attribute("id").is_none()).count();
        assert!((5..=20).contains(&fills), "{fills} fill paths");
        let texts: Vec<&str> = doc
            .descendants()
            .filter(|n| n.has_tag_name("text"))
            .filter_map(|n| n.text())
            .collect();
        assert!(texts.contains(&"a <title> & more"), "{texts:?}");
        assert!(texts.contains(&"layer from wall"), "{texts:?}");
    }
}

#[test]
fn the_svg_of_a_zoomed_view_leaves_out_what_is_outside() {
    let mesh = small_annulus(1);
    let whole = render_svg(&mesh, &params(600, 600)).unwrap();
    let zoom = render_svg(
        &mesh,
        &DrawParams {
            view: Some(view_around([R_WALL, 0.0], 0.05)),
            ..params(600, 600)
        },
    )
    .unwrap();
    assert!(
        zoom.len() * 3 < whole.len(),
        "{} vs {}",
        zoom.len(),
        whole.len()
    );
}

#[test]
fn bad_views_sizes_and_inputs_are_refused_with_an_error() {
    let mesh = small_annulus(1);
    let with_view = |v: View| DrawParams {
        view: Some(v),
        ..params(200, 200)
    };
    let flipped = View {
        x0: 1.0,
        y0: 0.0,
        x1: 0.0,
        y1: 1.0,
    };
    let flat = View {
        x0: 0.0,
        y0: 1.0,
        x1: 1.0,
        y1: 1.0,
    };
    let nan = View {
        x0: f64::NAN,
        y0: 0.0,
        x1: 1.0,
        y1: 1.0,
    };
    for v in [flipped, flat, nan] {
        let e = render_png(&mesh, &with_view(v)).unwrap_err();
        assert!(matches!(e, DrawError::InvalidView { .. }), "{e}");
        let e = render_svg(&mesh, &with_view(v)).unwrap_err();
        assert!(matches!(e, DrawError::InvalidView { .. }), "{e}");
    }
    assert!(matches!(
        render_png(&mesh, &params(0, 100)),
        Err(DrawError::InvalidSize { .. })
    ));
    let e = render_png(&Mesh::new(Dim::Two, 1), &params(100, 100)).unwrap_err();
    assert_eq!(e, DrawError::EmptyMesh);
    assert!(e.to_string().contains("nothing to draw"));
    let wrong_length = DrawParams {
        colour: ColourBy::ScaledJacobian(vec![1.0; 3]),
        ..params(100, 100)
    };
    let e = render_png(&mesh, &wrong_length).unwrap_err();
    assert!(matches!(e, DrawError::LengthMismatch { len: 3, .. }), "{e}");
    let mut no_layers = mesh.clone();
    no_layers.cell_layer.clear();
    let by_layer = DrawParams {
        colour: ColourBy::Layer,
        ..params(100, 100)
    };
    let e = render_svg(&no_layers, &by_layer).unwrap_err();
    assert!(e.to_string().contains("cell_layer"), "{e}");
    let mut broken = mesh.clone();
    broken
        .cells
        .push(CellType::new(Shape::Tri, 1), &[0, 1, 999_999]);
    broken.cell_layer.push(0);
    let e = render_png(&broken, &params(100, 100)).unwrap_err();
    assert!(
        matches!(
            e,
            DrawError::InvalidMesh(Problem::NodeOutOfRange { node: 999_999, .. })
        ),
        "{e}"
    );
    let mut nan_node = mesh.clone();
    nan_node.nodes[5][1] = f64::NAN;
    assert!(matches!(
        render_png(&nan_node, &params(100, 100)),
        Err(DrawError::InvalidMesh(Problem::NonFiniteNode {
            node: 5,
            ..
        }))
    ));
    let mut volume = mesh.clone();
    volume.dim = Dim::Three;
    assert_eq!(
        render_svg(&volume, &params(100, 100)),
        Err(DrawError::NotPlanar)
    );
}

#[test]
fn the_real_naca0012_wall_view_frames_the_section() {
    let mesh = naca0012_o_mesh(30);
    let view = view_of_role(&mesh, Role::Wall, 0.05).unwrap();
    // The section spans x = 0..1 and about ±0.06 in y.
    assert!(view.x0 < 0.0 && view.x0 > -0.1, "{view:?}");
    assert!(view.x1 > 1.0 && view.x1 < 1.1, "{view:?}");
    assert!(view.y1 > 0.06 && view.y1 < 0.2, "{view:?}");
    let p = DrawParams {
        view: Some(view),
        colour: ColourBy::Layer,
        ..params(800, 300)
    };
    let pixels = rgb(&decode(&render_png(&mesh, &p).unwrap()));
    // The wall loop is drawn bold in black: at least twice the chord's length in pixels.
    let black = pixels.iter().filter(|c| c.iter().all(|&v| v < 30)).count();
    assert!(black > 2 * 700, "{black} black pixels");
    // Inside the section nothing is drawn: the pixel at mid-chord on the axis (the centre of
    // the plot, which is the picture's centre without legend) is white.
    let no_legend = DrawParams {
        show_legend: false,
        ..p.clone()
    };
    let centre = decode(&render_png(&mesh, &no_legend).unwrap())
        .pixel(400, 150)
        .unwrap();
    assert_eq!([centre.red(), centre.green(), centre.blue()], WHITE);
    let svg = render_svg(&mesh, &p).unwrap();
    assert!(roxmltree::Document::parse(&svg).is_ok());
    assert!(view_of_role(&mesh, Role::Farfield, 0.0).unwrap().x1 > 6.0);
    let mut wall_only = mesh.clone();
    wall_only.patches[1].role = Role::Wall;
    wall_only.patches[0].role = Role::Wall;
    assert!(matches!(
        view_of_role(&wall_only, Role::Farfield, 0.0),
        Err(DrawError::NoSuchRole { .. })
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Any view, even far away, tiny, huge or inverted, gives a picture of the requested size
    /// or an `InvalidView` error, never a panic.
    #[test]
    fn any_view_gives_a_picture_or_an_invalid_view_error(
        cx in -1e3f64..1e3,
        cy in -1e3f64..1e3,
        log_half in -9.0f64..6.0,
        aspect in -2.0f64..2.0,
        w in 16u32..300,
        h in 16u32..300,
    ) {
        let mesh = small_annulus(2);
        let half = 10f64.powf(log_half);
        let view = View { x0: cx - half, x1: cx + half, y0: cy - half * aspect, y1: cy + half * aspect };
        let valid = view.x0 < view.x1 && view.y0 < view.y1;
        let p = DrawParams { view: Some(view), colour: ColourBy::Layer, ..params(w, h) };
        match render_png(&mesh, &p) {
            Ok(png) => {
                prop_assert!(valid);
                let pixmap = decode(&png);
                prop_assert_eq!((pixmap.width(), pixmap.height()), (w, h));
            }
            Err(e) => prop_assert!(matches!(e, DrawError::InvalidView { .. }) && !valid, "{}", e),
        }
        prop_assert_eq!(render_svg(&mesh, &p).is_ok(), valid);
    }
}

/// One convention for "good" in every colouring: the light end of the map. A small largest
/// angle and a high scaled Jacobian are both light; their opposites both dark.
#[test]
fn good_cells_are_light_in_every_colouring() {
    let mesh = annulus(&Annulus {
        around: 12,
        quad_rings: 2,
        tri_rings: 2,
        order: 1,
        jitter: 0.3,
    });
    let n = mesh.cells.len();
    let angles = mesh_draw::max_angle_deg(&mesh);
    let (good, bad) = (0..n).fold((0, 0), |(g, b), i| {
        (
            if angles[i] < angles[g] { i } else { g },
            if angles[i] > angles[b] { i } else { b },
        )
    });
    let lightness = |colour: ColourBy, cell: usize| {
        // the fill colour at the cell's centroid, with no edge there: a picture of one cell
        let k = mesh.cells.get(cell).corners().to_vec();
        let c = k.iter().fold([0.0, 0.0], |s, &v| {
            let p = mesh.xy(v);
            [s[0] + p[0] / k.len() as f64, s[1] + p[1] / k.len() as f64]
        });
        let p = DrawParams {
            colour,
            view: Some(view_around(c, 1e-4)),
            show_scale_bar: false,
            show_legend: false,
            ..params(41, 41)
        };
        let px = decode(&render_png(&mesh, &p).unwrap());
        let c = px.pixel(20, 20).unwrap();
        u32::from(c.red()) + u32::from(c.green()) + u32::from(c.blue())
    };
    assert!(
        angles[bad] > angles[good] + 2.0,
        "{} {}",
        angles[good],
        angles[bad]
    );
    assert!(lightness(ColourBy::MaxAngle, good) > lightness(ColourBy::MaxAngle, bad));
    let mut sj = vec![0.5; n];
    sj[good] = 1.0;
    sj[bad] = 0.1;
    assert!(
        lightness(ColourBy::ScaledJacobian(sj.clone()), good)
            > lightness(ColourBy::ScaledJacobian(sj), bad)
    );
}

/// A view lands on the same pixels whatever colours the cells: the legend's column has one
/// width. Compared on the SVG, which writes the PNG's geometry exactly (the PNG's anti-aliased
/// thin wall line darkens its pixels differently over different fills).
#[test]
fn a_view_does_not_move_with_the_legend() {
    let mesh = annulus(&Annulus {
        around: 12,
        quad_rings: 2,
        tri_rings: 2,
        order: 1,
        jitter: 0.0,
    });
    let n = mesh.cells.len();
    // the frame of the plot, the boundary loops and the scale bar, as drawn
    let placed = |colour: ColourBy| {
        let p = DrawParams {
            colour,
            view: Some(view_around([0.0, 0.0], 2.0)),
            ..params(600, 450)
        };
        let svg = render_svg(&mesh, &p).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let frame = doc
            .descendants()
            .find(|n| n.has_tag_name("rect") && n.attribute("fill") == Some("none"))
            .map(|n| ["x", "y", "width", "height"].map(|a| n.attribute(a).unwrap().to_string()));
        let paths: Vec<String> = ["wall", "farfield"]
            .iter()
            .map(|id| {
                let path = doc.descendants().find(|n| n.attribute("id") == Some(*id));
                path.and_then(|n| n.attribute("d")).unwrap().to_string()
            })
            .collect();
        let bar = doc
            .descendants()
            .find(|n| n.has_tag_name("polyline"))
            .and_then(|n| n.attribute("points"))
            .map(str::to_string);
        (frame.unwrap(), paths, bar.unwrap())
    };
    let values = ColourBy::CellValues {
        values: (0..n).map(|i| 1e-6 * i as f64 - 0.000_125).collect(),
        label: "x".into(),
    };
    let a = placed(ColourBy::None);
    let width: f64 = a.0[2].parse().unwrap();
    assert!(width > 300.0, "{a:?}");
    for c in [
        ColourBy::Layer,
        ColourBy::MaxAngle,
        ColourBy::ScaledJacobian(vec![0.5; n]),
        values,
    ] {
        assert_eq!(placed(c), a);
    }
}
