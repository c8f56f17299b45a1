//! 3D cases with a far field (issue 46): several bodies in one domain, the layers stopped
//! before the fronts meet, the space to a box or sphere filled with tetrahedra by `tet-fill`.
//! Each case at P1 and P2 through the library: valid (every cell certified at P2, every corner
//! Jacobian positive at P1), conforming (`mesh_model::validate`), the cells' volumes summing to
//! the far field's volume minus the bodies' (the report's volume check, 1e-9), the boundary
//! groups one per body and `farfield` (the front's facets all inner faces now), the far
//! field's nodes on its shape, the fill's tetrahedra within the dihedral bar. A near-body case
//! (no far field) names its outer boundary `outer`; bad far fields are one-line errors.
//!
//! `cargo test -p curvemesh --test integration -- far_field:: --nocapture` prints the figures.

use mesh_model::{Mesh, Role, Shape};

/// The largest dihedral angle the fill's tetrahedra may have (the bar).
const MAX_DIHEDRAL_DEG: f64 = 160.0;

/// `text` (a 3D case file) meshed at `order` through the library; the run must succeed and be
/// valid. The mesh and its report.
pub(crate) fn mesh(text: &str, order: u8) -> (Mesh, curvemesh::report::Report) {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("case.toml");
    std::fs::write(&file, text).unwrap();
    let case = curvemesh::load(file.to_str().unwrap()).unwrap();
    let options = curvemesh::Options {
        order: Some(order),
        ..curvemesh::Options::default()
    };
    let meshed = curvemesh::mesh(&case, &options, &mut curvemesh::Silent)
        .unwrap_or_else(|e| panic!("P{order}: {e}"));
    assert!(
        meshed.report.is_valid(),
        "P{order}: {:?}",
        meshed.report.problems
    );
    (meshed.mesh, meshed.report)
}

/// The checks every far-field case passes: conforming and valid, volume balanced, the groups
/// `groups` (sorted), the far field's nodes where `on_far_field` says, the fill within the bar.
fn check(label: &str, text: &str, groups: &[&str], on_far_field: impl Fn([f64; 3]) -> bool) {
    for order in [1, 2] {
        let (m, report) = mesh(text, order);
        let problems = mesh_model::validate(&m);
        assert!(problems.is_empty(), "{label} P{order}: {}", problems[0]);
        let v = report.volume_check.as_ref().unwrap();
        assert!(v.relative_difference < 1e-9, "{label} P{order}: {v:?}");
        let mut names: Vec<&str> = report.boundary_groups.keys().map(String::as_str).collect();
        names.sort_unstable();
        assert_eq!(names, groups, "{label} P{order}");
        for (f, facet) in m.boundary.iter().enumerate() {
            if m.patches[m.boundary_patch[f] as usize].role == Role::Farfield {
                for &n in facet.corners() {
                    let p = m.nodes[n as usize];
                    assert!(on_far_field(p), "{label} P{order}: far-field node {p:?}");
                }
            }
        }
        let fill = report.fill.unwrap();
        assert!(fill.tets > 0);
        assert!(
            fill.max_dihedral_deg <= MAX_DIHEDRAL_DEG,
            "{label} P{order}: fill dihedral {}",
            fill.max_dihedral_deg
        );
        eprintln!(
            "{label} P{order}: {} cells, fill {} tets ({} pyramids, {} Steiner, {} refinement \
             points), max dihedral {:.1}, volume {:.3e}",
            m.cells.len(),
            fill.tets,
            fill.pyramids,
            fill.steiner_points,
            fill.refinement_points,
            fill.max_dihedral_deg,
            report.volume.unwrap_or(0.0)
        );
    }
}

/// Two spheres of radius 0.5, centred at ±`centre` on x, in a far-field sphere of radius 10:
/// the case file.
fn two_spheres(centre: f64) -> String {
    format!(
        "dimension = 3\n\
        [[surface]]\nbuiltin = \"sphere\"\nradius = 0.5\nrefinement = 2\n\
        translate = [-{centre}, 0.0, 0.0]\nname = \"left\"\n\
        [[surface]]\nbuiltin = \"sphere\"\nradius = 0.5\nrefinement = 2\n\
        translate = [{centre}, 0.0, 0.0]\nname = \"right\"\n\
        [farfield]\nsphere = {{ center = [0.0, 0.0, 0.0], radius = 10.0 }}\n\
        [layers]\nfirst_height = 1e-3\ngrowth = 1.25\nmax_layers = 16\n\
        [cut]\ncells = \"tets\"\n"
    )
}

/// Whether `p` lies on the far-field sphere of [`two_spheres`].
fn on_far_sphere(p: [f64; 3]) -> bool {
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    (r - 10.0).abs() < 1e-9
}

/// Two spheres 0.1 apart inside a far-field sphere: the gap's columns stop, the fill meets
/// them there and reaches the far field.
#[test]
fn two_spheres_in_a_sphere() {
    let groups = ["farfield", "left", "right"];
    check("two spheres", &two_spheres(0.55), &groups, on_far_sphere);
}

/// Two spheres 0.01 apart: the columns facing across the gap stop at the wall itself, so the
/// wall there bounds the fill directly (the cut mesh has no facet on it); the fill stands on
/// it and it stays in its body's group.
#[test]
fn two_spheres_nearly_touching_fill_onto_their_bare_walls() {
    let text = two_spheres(0.505);
    let groups = ["farfield", "left", "right"];
    check("spheres 0.01 apart", &text, &groups, on_far_sphere);
    // every wall facet of the icospheres (320 each) is in its group
    let (_, report) = mesh(&text, 1);
    assert_eq!(report.boundary_groups["left"], 320);
    assert_eq!(report.boundary_groups["right"], 320);
}

/// A cube of quads (4 × 4 per face) in a box 9 across, 8 layers, cut into `cells`: the case
/// file.
fn cube_in_a_box(cells: &str) -> String {
    format!(
        "dimension = 3\n\
        [surface]\nbuiltin = \"cube\"\ndivisions = 4\n\
        [farfield]\nbox = {{ min = [-4.0, -4.0, -4.0], max = [5.0, 5.0, 5.0] }}\n\
        [layers]\nfirst_height = 1e-2\ngrowth = 1.2\nmax_layers = 8\n\
        [cut]\ncells = \"{cells}\"\n"
    )
}

/// Whether `p` lies on the box of [`cube_in_a_box`].
fn on_the_box(p: [f64; 3]) -> bool {
    p.iter().any(|&x| x == -4.0 || x == 5.0)
}

/// A cube of quads (the mixed cut keeps hexahedra, so the front has quadrilaterals, capped by
/// pyramids) inside a box.
#[test]
fn a_cube_of_hexahedra_in_a_box() {
    let groups = ["farfield", "wall"];
    check(
        "cube in a box",
        &cube_in_a_box("mixed"),
        &groups,
        on_the_box,
    );
}

/// The prism cut of the same cube: every hexahedron halved into two prisms, the wall's and the
/// front's quadrilaterals split, no pyramid anywhere (the fill meets triangles only).
#[test]
fn the_prism_cut_of_a_cube_of_hexahedra_has_no_pyramid() {
    let text = cube_in_a_box("prisms");
    check(
        "cube in a box, prisms",
        &text,
        &["farfield", "wall"],
        on_the_box,
    );
    let (m, report) = mesh(&text, 1);
    let (mixed, _) = mesh(&cube_in_a_box("mixed"), 1);
    assert_eq!(m.count(Shape::Pyramid) + m.count(Shape::Hex), 0);
    assert_eq!(m.count(Shape::Prism), 2 * mixed.count(Shape::Hex));
    assert!(m.boundary.iter().all(|f| f.corners().len() == 3));
    assert_eq!(report.fill.unwrap().pyramids, 0);
}

/// The prism cut of two spheres whose gap stops columns: the layers under the first stop keep
/// their prisms, those from it up are tetrahedra (a prism beside a cut cell would need a
/// pyramid), and no pyramid is left.
#[test]
fn the_prism_cut_keeps_the_layers_under_the_first_stop() {
    let text = two_spheres(0.55).replace("\"tets\"", "\"prisms\"");
    let (m, _) = mesh(&text, 1);
    assert_eq!(m.count(Shape::Pyramid) + m.count(Shape::Hex), 0);
    let layers = m
        .cell_layer
        .iter()
        .filter(|&&l| l != mesh_model::NONE)
        .max()
        .unwrap();
    let prism_layers: Vec<u32> = (0..m.cells.len())
        .filter(|&i| m.cells.get(i).ty.shape == Shape::Prism)
        .map(|i| m.cell_layer[i])
        .collect();
    let top = *prism_layers.iter().max().unwrap();
    assert!(
        top > 0 && top < *layers,
        "prisms up to layer {top} of {layers}"
    );
    // every cell of a layer under the top prism layer is a prism
    for i in 0..m.cells.len() {
        if m.cell_layer[i] <= top {
            assert_eq!(m.cells.get(i).ty.shape, Shape::Prism, "cell {i}");
        }
    }
}

/// Without a far field the domain is the layers' shell, its outer boundary `outer`.
#[test]
fn a_near_body_mesh_names_its_outer_boundary_outer() {
    let text = "dimension = 3\n[surface]\nbuiltin = \"sphere\"\nrefinement = 1\n\
        [layers]\nmax_layers = 3\n";
    let (_, report) = mesh(text, 1);
    let names: Vec<&str> = report.boundary_groups.keys().map(String::as_str).collect();
    assert_eq!(names, ["outer", "wall"]);
    assert!(report.fill.is_none());
}

/// A far field that does not hold every body, or is not a shape, is one line naming why.
#[test]
fn bad_far_fields_are_one_line_errors() {
    let body = "dimension = 3\n[surface]\nbuiltin = \"sphere\"\nrefinement = 1\n";
    let cases = [
        (
            "[farfield]\nsphere = { center = [0.0, 0.0, 0.0], radius = 0.5 }\n",
            "not inside the far field",
        ),
        (
            "[farfield]\nbox = { min = [0.0, -2.0, -2.0], max = [2.0, 2.0, 2.0] }\n",
            "not inside the far field",
        ),
        (
            "[farfield]\nsphere = { center = [0.0, 0.0, 0.0], radius = -3.0 }\n",
            "must be positive",
        ),
        (
            "[farfield]\nbox = { min = [0.0, 0.0, 0.0], max = [2.0, 0.0, 2.0] }\n",
            "is not above its min",
        ),
        ("[farfield]\nmax_size = 1.0\n", "give box"),
        (
            "[farfield]\nsphere = { center = [0.0, 0.0, 0.0], radius = 9.0 }\nmax_size = 1e-4\n",
            "too small",
        ),
    ];
    for (far, want) in cases {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("case.toml");
        std::fs::write(&file, format!("{body}{far}")).unwrap();
        let err = curvemesh::load(file.to_str().unwrap())
            .and_then(|case| {
                curvemesh::mesh(
                    &case,
                    &curvemesh::Options::default(),
                    &mut curvemesh::Silent,
                )
            })
            .err()
            .unwrap_or_else(|| panic!("{far}: no error"))
            .to_string();
        assert!(err.contains(want), "{far}: {err}");
        assert!(!err.contains('\n'), "{err}");
    }
}
