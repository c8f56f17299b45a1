//! Pictures from the command line: `--png FILE@VIEW` and `--svg`, named views of the built-in
//! cases, and clear errors for bad picture requests.

use end_to_end::{Outcome, mesh, xtask as run};

#[test]
fn whole_and_zoomed_views_are_drawn_and_differ() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let (whole, le, svg, msh) = (p("whole.png"), p("le.png"), p("te.svg"), p("m.msh"));
    let outcome = mesh(
        "naca0012",
        "1",
        &[
            "--out",
            &msh,
            "--width",
            "400",
            "--png",
            &whole,
            "--png",
            &format!("{le}@le"),
            "--svg",
            &format!("{svg}@te"),
        ],
    )
    .unwrap();
    assert_eq!(outcome, Outcome::Valid);
    let a = tiny_skia::Pixmap::load_png(&whole).unwrap();
    let b = tiny_skia::Pixmap::load_png(&le).unwrap();
    assert_eq!((a.width(), a.height()), (400, 300));
    let not_white = a
        .pixels()
        .iter()
        .filter(|p| p.red() < 250 || p.blue() < 250)
        .count();
    assert!(
        not_white > 400 * 300 / 10,
        "the picture is not blank ({not_white} pixels drawn)"
    );
    assert_ne!(
        a.data(),
        b.data(),
        "the zoomed view differs from the whole view"
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    let doc = roxmltree::Document::parse(&text).expect("the SVG is well-formed XML");
    assert_eq!(doc.root_element().tag_name().name(), "svg");
}

#[test]
fn quality_reads_a_mesh_and_draws_it() {
    let dir = tempfile::tempdir().unwrap();
    let msh = dir.path().join("m.msh").to_str().unwrap().to_string();
    let png = dir.path().join("q.png").to_str().unwrap().to_string();
    let json = dir.path().join("q.json").to_str().unwrap().to_string();
    mesh("lshape", "1", &["--out", &msh]).unwrap();
    let outcome = run(&[
        "quality",
        &msh,
        "--quiet",
        "--report",
        &json,
        "--png",
        &format!("{png}@walls"),
    ])
    .unwrap();
    assert_eq!(outcome, Outcome::Valid);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(report["quality"]["max_angle_deg"].as_f64().unwrap() > 60.0);
    assert!(report["problems"].as_array().unwrap().is_empty());
    assert!(tiny_skia::Pixmap::load_png(&png).is_ok());
}

#[test]
fn bad_picture_requests_are_named_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let msh = dir.path().join("m.msh").to_str().unwrap().to_string();
    let png = dir.path().join("p.png").to_str().unwrap().to_string();
    let cases: [(Vec<String>, &str); 4] = [
        (
            vec!["--png".into(), format!("{png}@nowhere")],
            "no view named 'nowhere'",
        ),
        (vec!["--png".into(), format!("{png}@1,2,3")], "four numbers"),
        (vec!["--png".into(), format!("{png}@1,1,0,2")], "x0 < x1"),
        (vec!["--svg".into(), png.clone()], "must end in .svg"),
    ];
    for (extra, words) in cases {
        let mut args = vec!["mesh", "naca0012", "--quiet", "--out", &msh];
        args.extend(extra.iter().map(String::as_str));
        let err = run(&args).expect_err("bad picture request");
        let msg = format!("{err:#}");
        assert!(msg.contains(words), "{msg:?} should mention {words:?}");
        assert!(!std::path::Path::new(&msh).exists() && !std::path::Path::new(&png).exists());
    }
}

#[test]
fn quality_of_a_missing_file_is_a_clear_error() {
    let err = run(&["quality", "/nonexistent/mesh.msh"]).expect_err("missing file");
    assert!(format!("{err:#}").contains("/nonexistent/mesh.msh"));
}

/// The wall line is no thicker than the first layer in view, and a view whose first layers
/// are below a pixel says so.
#[test]
fn the_first_layers_show_or_the_picture_says_they_are_below_a_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let (all, close, msh) = (p("all.svg"), p("close.svg"), p("m.msh"));
    let outcome = mesh(
        "naca0012",
        "1",
        &[
            "--out",
            &msh,
            "--svg",
            &all,
            // 0.01 wide on about 1900 px: the first layer (5e-5) is about 9 px
            "--svg",
            &format!("{close}@-0.002,-0.003,0.008,0.003"),
        ],
    )
    .unwrap();
    assert_eq!(outcome, Outcome::Valid);
    let wall_width = |svg: &str| -> f64 {
        let at = svg.find(r#"<path id="wall""#).expect("a wall path");
        let rest = &svg[at..];
        let w = rest.find("stroke-width=\"").unwrap() + 14;
        rest[w..w + rest[w..].find('"').unwrap()].parse().unwrap()
    };
    let (all, close) = (
        std::fs::read_to_string(all).unwrap(),
        std::fs::read_to_string(close).unwrap(),
    );
    assert!(all.contains("first layers below a pixel"));
    // the note is written above the plot's frame (its first rectangle), not over the cells
    let doc = roxmltree::Document::parse(&all).unwrap();
    let number = |n: roxmltree::Node, a: &str| n.attribute(a).unwrap().parse::<f64>().unwrap();
    let frame = doc
        .descendants()
        .find(|n| n.has_tag_name("rect") && n.attribute("fill") == Some("none"))
        .expect("the plot's frame");
    let note = doc
        .descendants()
        .find(|n| n.has_tag_name("text") && n.text().unwrap().starts_with("first layers"))
        .unwrap();
    let (note_y, font) = (number(note, "y"), number(note, "font-size"));
    assert!(
        note_y + 0.3 * font < number(frame, "y"),
        "{note:?} over {frame:?}"
    );
    assert!(wall_width(&all) < 1.0, "{}", wall_width(&all));
    assert!(!close.contains("below a pixel"));
    assert!(wall_width(&close) >= 2.0, "{}", wall_width(&close));
}

/// The layer colouring counts the layers grown from the walls, from 1; the layers grown from
/// the far field and the filled region are coloured apart, each named in the legend.
#[test]
fn the_layer_colouring_counts_from_the_walls_and_sets_the_far_field_and_fill_apart() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let (svg, msh) = (p("all.svg"), p("m.msh"));
    let outcome = mesh("naca0012", "2", &["--out", &msh, "--svg", &svg]).unwrap();
    assert_eq!(outcome, Outcome::Valid);
    let text = std::fs::read_to_string(&svg).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let texts: Vec<&str> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text())
        .collect();
    for label in ["layer from wall", "1", "far field", "fill"] {
        assert!(texts.contains(&label), "no {label:?} in {texts:?}");
    }
    assert!(!texts.contains(&"0"), "a layer 0 in {texts:?}");
    // cells filled in the far field's light blue and in the fill's grey
    let fills: Vec<&str> = doc
        .descendants()
        .filter(|n| n.has_tag_name("path") && n.attribute("id").is_none())
        .filter_map(|n| n.attribute("fill"))
        .collect();
    for colour in ["#bccce6", "#c8c8c8"] {
        assert!(fills.contains(&colour), "no cells of {colour} in {fills:?}");
    }
}
