//! The cuts on layered cube-spheres: conforming, positive, the volume kept, every piece in
//! its parent's layer and pipe; with every kind of merged cell and adversarial numberings.

use testkit::layered as fixture;

use std::collections::{HashMap, HashSet};

use fixture::{Merge, Spec};
use mesh_model::poly::{CellFace, PolyMesh};
use mesh_model::{Mesh, Shape, validate};
use proptest::prelude::*;

fn triple(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    a[0] * (b[1] * c[2] - b[2] * c[1])
        + a[1] * (b[2] * c[0] - b[0] * c[2])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

/// Six times the flux of `x / 3` through the polygon `k`, fanned from its centroid (the
/// fanning `PolyMesh::cell_volume` uses).
fn flux6(nodes: &[[f64; 3]], k: &[u32]) -> f64 {
    let mut c = [0.0; 3];
    for &v in k {
        (0..3).for_each(|d| c[d] += nodes[v as usize][d] / k.len() as f64);
    }
    (0..k.len())
        .map(|i| {
            triple(
                c,
                nodes[k[i] as usize],
                nodes[k[(i + 1) % k.len()] as usize],
            )
        })
        .sum()
}

/// The volume of the mesh's linear cells, each face fanned from its centroid.
fn mesh_volume(mesh: &Mesh) -> f64 {
    let mut p = PolyMesh::new();
    p.nodes = mesh.nodes.clone();
    for c in mesh.cells.iter() {
        let k = c.corners();
        let faces: Vec<CellFace> =
            c.ty.shape
                .faces()
                .iter()
                .map(|f| {
                    let nodes: Vec<u32> = f.iter().map(|&j| k[j]).collect();
                    CellFace {
                        face: p.push_face(&nodes),
                        reversed: false,
                    }
                })
                .collect();
        p.push_cell(&faces, 0, 0);
    }
    (0..p.cell_count()).map(|c| p.cell_volume(c)).sum()
}

/// The faces of `poly` in one cell, turned out of it.
fn poly_boundary(poly: &PolyMesh) -> Vec<Vec<u32>> {
    let mut uses = vec![0; poly.face_count()];
    for c in 0..poly.cell_count() {
        poly.cell(c).iter().for_each(|f| uses[f.face as usize] += 1);
    }
    let mut out = Vec::new();
    for c in 0..poly.cell_count() {
        for f in poly.cell(c) {
            if uses[f.face as usize] == 1 {
                let mut k = poly.face(f.face as usize).to_vec();
                if f.reversed {
                    k.reverse();
                }
                out.push(k);
            }
        }
    }
    out
}

/// Cell counts by shape and the largest tetrahedron dihedral angle.
struct Stats {
    tets: usize,
    pyramids: usize,
    prisms: usize,
    hexes: usize,
    max_dihedral: f64,
}

impl std::fmt::Display for Stats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "tet {} pyramid {} prism {} hex {} max dihedral {:.1}°",
            self.tets, self.pyramids, self.prisms, self.hexes, self.max_dihedral
        )
    }
}

/// Every property of a cut: no problem for `validate`, the volume kept (up to the splitting
/// of boundary quadrilaterals, accounted for exactly), each cell inside the polyhedral cell
/// of its layer and pipe, wall facets on the wall.
fn check(poly: &PolyMesh, mesh: &Mesh) -> Stats {
    let problems = validate(mesh);
    assert!(
        problems.is_empty(),
        "{} problems, first: {}",
        problems.len(),
        problems[0]
    );
    let v_poly: f64 = (0..poly.cell_count()).map(|c| poly.cell_volume(c)).sum();
    let f_poly: f64 = poly_boundary(poly)
        .iter()
        .map(|k| flux6(&poly.nodes, k))
        .sum();
    let f_mesh: f64 = mesh
        .boundary
        .iter()
        .map(|f| flux6(&mesh.nodes, f.corners()))
        .sum();
    let v_mesh = mesh_volume(mesh);
    let want = v_poly + (f_mesh - f_poly) / 6.0;
    assert!(
        (v_mesh - want).abs() <= 1e-12 * v_poly,
        "volume {v_mesh} want {want} (poly {v_poly})"
    );
    assert!(
        (f_mesh / 6.0 - v_mesh).abs() <= 1e-12 * v_poly,
        "boundary turned inward"
    );
    // each piece inside its parent, found by (layer, pipe)
    let mut parent: HashMap<(u32, u32), HashSet<u32>> = HashMap::new();
    let mut wall: HashSet<u32> = HashSet::new();
    for c in 0..poly.cell_count() {
        let key = (poly.cell_layer[c], poly.cell_pipe[c]);
        let set = parent.entry(key).or_default();
        assert!(set.is_empty(), "two cells in layer and pipe {key:?}");
        for (i, f) in poly.cell(c).iter().enumerate() {
            set.extend(poly.face(f.face as usize));
            if i == 0 && key.0 == 0 {
                wall.extend(poly.face(f.face as usize));
            }
        }
    }
    assert_eq!(mesh.cell_layer.len(), mesh.cells.len());
    for (i, c) in mesh.cells.iter().enumerate() {
        let set = &parent[&(mesh.cell_layer[i], mesh.cell_pipe[i])];
        assert!(
            c.corners().iter().all(|v| set.contains(v)),
            "cell {i} outside its parent"
        );
    }
    for (i, f) in mesh.boundary.iter().enumerate() {
        let on_wall = f.corners().iter().all(|v| wall.contains(v));
        assert_eq!(
            mesh.boundary_patch[i] == 0,
            on_wall,
            "facet {i} in the wrong patch"
        );
    }
    Stats {
        tets: mesh.count(Shape::Tet),
        pyramids: mesh.count(Shape::Pyramid),
        prisms: mesh.count(Shape::Prism),
        hexes: mesh.count(Shape::Hex),
        max_dihedral: topo_cut::max_dihedral_deg(mesh),
    }
}

/// The tetrahedral and the mixed cut of the spec's mesh, checked; the prism cut checked too
/// (tetrahedra and prisms only, every prism of the mixed cut kept unless its layer has a cut
/// cell, every hexahedron a pair of prisms where its layer has none).
fn both(spec: &Spec) -> (Stats, Stats) {
    let poly = fixture::poly(spec);
    let tets = topo_cut::cut_to_tets(&poly).expect("tets");
    let mixed = topo_cut::cut_to_mixed(&poly).expect("mixed");
    let (t, m) = (check(&poly, &tets), check(&poly, &mixed));
    assert_eq!(t.pyramids + t.prisms + t.hexes, 0);
    let prisms = topo_cut::cut_to_prisms(&poly, &[]).expect("prisms");
    let p = check(&poly, &prisms);
    assert_eq!(p.pyramids + p.hexes, 0, "prism cut: {p}");
    assert!(prisms.boundary.iter().all(|f| f.corners().len() == 3));
    if m.pyramids + m.tets == 0 {
        assert_eq!(
            p.prisms,
            m.prisms + 2 * m.hexes,
            "nothing cut: {m} against {p}"
        );
    }
    (t, m)
}

#[test]
fn plain_prisms_and_hexes_are_kept_or_cut_in_three_and_six() {
    for quads in [false, true] {
        let spec = Spec::new(3, quads, 4);
        let poly = fixture::poly(&spec);
        let (t, m) = both(&spec);
        let cells = poly.cell_count();
        assert_eq!(t.tets, cells * if quads { 6 } else { 3 });
        assert_eq!(
            (m.prisms, m.hexes, m.tets, m.pyramids),
            if quads {
                (0, cells, 0, 0)
            } else {
                (cells, 0, 0, 0)
            }
        );
        println!("quads {quads}: tets: {t}; mixed: {m}");
    }
}

/// Cells the caller flags are cut even though they are standard; the others stay prisms
/// (pyramids over their sides towards the cut cells), the whole conforming and positive.
#[test]
fn flagged_standard_cells_are_cut_and_the_rest_kept() {
    for quads in [false, true] {
        let spec = Spec::new(3, quads, 4);
        let poly = fixture::poly(&spec);
        let cells = poly.cell_count();
        let flags: Vec<bool> = (0..cells).map(|c| c % 7 == 3).collect();
        let flagged = flags.iter().filter(|&&f| f).count();
        let mesh = topo_cut::cut_to_mixed_cutting(&poly, &flags).expect("mixed");
        let m = check(&poly, &mesh);
        let kept = if quads { m.hexes } else { m.prisms };
        assert!(kept < cells - flagged + 1, "quads {quads}: {m}");
        // a node cut around takes the standard cells around it with it, not every one
        assert!(kept > 0, "quads {quads}: {m}");
        for (i, &c) in mesh.cell_pipe.iter().enumerate() {
            let shape = mesh.cells.get(i).ty.shape;
            let standard = matches!(shape, Shape::Prism | Shape::Hex);
            let parent = (0..cells)
                .find(|&p| poly.cell_pipe[p] == c && poly.cell_layer[p] == mesh.cell_layer[i]);
            if let Some(p) = parent {
                assert!(
                    !(flags[p] && standard),
                    "quads {quads}: flagged cell {p} kept as {shape:?}"
                );
            }
        }
        // no flags: the plain mixed cut
        assert_eq!(
            topo_cut::cut_to_mixed_cutting(&poly, &[]).expect("mixed"),
            topo_cut::cut_to_mixed(&poly).expect("mixed")
        );
        println!("quads {quads}: {flagged} of {cells} flagged: {m}");
    }
}

/// The prisms and hexahedra under a corner scaled Jacobian are flagged
/// (`quality::low_corner_cells`) and cut: the mixed mesh keeps none below the limit, the
/// rest as the plain cut keeps them, conforming and positive.
#[test]
fn cells_with_a_low_corner_are_flagged_and_none_is_kept() {
    use mesh_model::measure3d::min_corner_scaled_jacobian;
    for quads in [false, true] {
        let spec = Spec::new(3, quads, 4);
        let poly = fixture::poly(&spec);
        let plain = topo_cut::cut_to_mixed(&poly).expect("mixed");
        let mut corners: Vec<f64> = (0..plain.cells.len())
            .filter_map(|i| min_corner_scaled_jacobian(&plain, i))
            .collect();
        corners.sort_by(f64::total_cmp);
        let limit = corners[corners.len() / 2];
        assert!(corners[0] < limit, "quads {quads}: the corners vary");
        // below every corner: nothing flagged
        assert!(topo_cut::quality::low_corner_cells(&poly, corners[0] * 0.99).is_empty());
        let flags = topo_cut::quality::low_corner_cells(&poly, limit);
        assert_eq!(flags.len(), poly.cell_count());
        let flagged = flags.iter().filter(|&&f| f).count();
        assert_eq!(
            topo_cut::quality::flagged_layer_shapes(&poly, &flags),
            flagged
        );
        assert!(flagged > 0 && flagged < poly.cell_count(), "quads {quads}");
        let mesh = topo_cut::cut_to_mixed_cutting(&poly, &flags).expect("mixed");
        let m = check(&poly, &mesh);
        let mut kept = 0;
        for i in 0..mesh.cells.len() {
            if let Some(q) = min_corner_scaled_jacobian(&mesh, i) {
                assert!(q >= limit, "quads {quads}: cell {i} kept at {q} < {limit}");
                kept += 1;
            }
        }
        assert!(kept > 0, "quads {quads}: {m}");
        println!("quads {quads}: limit {limit:.3}, {flagged} flagged: {m}");
    }
}

#[test]
fn merged_children_are_cut_conforming() {
    for quads in [false, true] {
        for p in [0.1, 0.3, 0.6] {
            let mut spec = Spec::new(4, quads, 6);
            (spec.h0, spec.growth) = (0.15, 1.2);
            spec.merge = Merge::Random(p);
            let (t, m) = both(&spec);
            println!("quads {quads} merge {p}: tets: {t}; mixed: {m}");
            assert!(m.pyramids > 0 || m.tets > 0);
        }
    }
}

/// Grown until the outer layers are tall enough for Coe_shrink to merge children (0.65, the
/// dissertation's value), and twice as eager; printed with `--nocapture`.
#[test]
fn quality_on_radial_extrusions() {
    for quads in [false, true] {
        for (coe, h0, growth, layers) in [
            (0.0, 0.02, 1.25, 12),
            (0.65, 0.05, 1.3, 16),
            (1.3, 0.02, 1.25, 20),
        ] {
            let mut spec = Spec::new(8, quads, layers);
            (spec.h0, spec.growth) = (h0, growth);
            spec.merge = Merge::Shrink(coe);
            let (t, m) = both(&spec);
            println!("quads {quads} Coe_shrink {coe}: tets: {t}; mixed: {m}");
            assert!(t.max_dihedral < 160.0 && m.max_dihedral < 160.0, "{t}; {m}");
        }
    }
}

#[test]
fn a_long_face_is_a_clear_error() {
    let mut p = PolyMesh::new();
    // a pentagonal prism
    for z in [0.0, 1.0] {
        for i in 0..5 {
            let a = i as f64 * std::f64::consts::TAU / 5.0;
            p.nodes.push([a.cos(), a.sin(), z]);
        }
    }
    let out = |face| CellFace {
        face,
        reversed: false,
    };
    let mut faces = vec![
        out(p.push_face(&[4, 3, 2, 1, 0])),
        out(p.push_face(&[5, 6, 7, 8, 9])),
    ];
    for i in 0..5u32 {
        let j = (i + 1) % 5;
        faces.push(out(p.push_face(&[i, j, j + 5, i + 5])));
    }
    p.push_cell(&faces, 0, 0);
    assert!(p.validate().is_empty());
    let e = topo_cut::cut_to_tets(&p).unwrap_err().to_string();
    assert_eq!(
        e,
        "cell 0: face 0 has 5 nodes, only triangles and quadrilaterals can be cut"
    );
    assert!(topo_cut::cut_to_mixed(&p).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn any_numbering_and_merge_set_cuts_conforming(
        seed in any::<u64>(), quads in any::<bool>(), p in 0.0f64..0.7, n in 2usize..4,
        layers in 2usize..6,
    ) {
        let mut spec = Spec::new(n, quads, layers);
        (spec.h0, spec.growth) = (0.15, 1.2);
        spec.seed = seed;
        spec.merge = Merge::Random(p);
        both(&spec);
    }
}

/// A merged cell by hand: over the bottom triangle (0, 1, 2) nodes 0 and 1 have one child 4,
/// node 2 the child 5, so the cell has no top (faces: the bottom, the triangle (0, 1, 4), two
/// quadrilaterals); next to it a prism over (1, 3, 2) with the children 4, 6, 5, kept by the
/// mixed cut. The quadrilateral they share is twisted by `lift` (child 5 raised): twisted far
/// enough, the pyramid over it is no longer positive, and the prism has to be cut as well.
fn merged_pair(lift: f64) -> PolyMesh {
    let mut p = PolyMesh::new();
    p.nodes = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.5, -0.1, 0.4],
        [-0.05, 1.0, 0.3 + lift],
        [1.05, 1.05, 0.35],
    ];
    let face = |p: &mut PolyMesh, k: &[u32], reversed: bool| CellFace {
        face: p.push_face(k),
        reversed,
    };
    // faces turned out of their cell; the shared one out of the merged cell
    let shared = face(&mut p, &[1, 2, 5, 4], false);
    let a = [
        face(&mut p, &[0, 2, 1], false),
        face(&mut p, &[0, 1, 4], false),
        shared,
        face(&mut p, &[2, 0, 4, 5], false),
    ];
    p.push_cell(&a, 0, 0);
    let b = [
        face(&mut p, &[1, 2, 3], false),
        face(&mut p, &[4, 6, 5], false),
        CellFace {
            reversed: true,
            ..shared
        },
        face(&mut p, &[1, 3, 6, 4], false),
        face(&mut p, &[3, 2, 5, 6], false),
    ];
    p.push_cell(&b, 0, 1);
    p
}

#[test]
fn a_merged_cell_by_hand_is_cut_conforming_and_positive() {
    for lift in [0.0, 0.6, 1.2, 2.0] {
        let p = merged_pair(lift);
        assert!(p.validate().is_empty(), "{:?}", p.validate());
        let tets = check(&p, &topo_cut::cut_to_tets(&p).expect("tets"));
        let mixed = check(&p, &topo_cut::cut_to_mixed(&p).expect("mixed"));
        println!("lift {lift}: tets: {tets}; mixed: {mixed}");
        assert!(tets.max_dihedral < 170.0 && mixed.max_dihedral < 170.0);
        assert_eq!(mixed.prisms, usize::from(lift < 1.0), "{mixed}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10))]
    /// From any order of the nodes, the refined cut is conforming and positive, and no worse
    /// than the order's own cut.
    #[test]
    fn refining_any_cut_keeps_it_conforming_and_never_worse(
        seed in any::<u64>(), quads in any::<bool>(), p in 0.0f64..0.7, layers in 2usize..4,
    ) {
        let mut spec = Spec::new(3, quads, layers);
        (spec.h0, spec.growth) = (0.15, 1.2);
        spec.seed = seed;
        spec.merge = Merge::Random(p);
        let poly = fixture::poly(&spec);
        let mut rng = fixture::Rng(seed ^ 0x9e37_79b9);
        let mut rank: Vec<u32> = (0..poly.nodes.len() as u32).collect();
        rng.shuffle(&mut rank);
        let mut cut = topo_cut::refine::Cut::from_ranks(&poly, &rank);
        let before = topo_cut::max_dihedral_deg(&topo_cut::assemble_cut(&poly, &cut).unwrap());
        let start = cut.clone();
        let worst = topo_cut::refine::refine(&poly, &mut cut, 120.0, 4, 1);
        let mesh = topo_cut::assemble_cut(&poly, &cut).unwrap();
        let s = check(&poly, &mesh);
        prop_assert!(s.max_dihedral <= before + 1e-9, "{} > {before}", s.max_dihedral);
        prop_assert!((s.max_dihedral - worst).abs() < 1e-9 || worst == 0.0, "{s} vs {worst}");
        // the mixed cut's refining (sides may be kept whole) too
        let mut cut = start;
        let worst = topo_cut::refine::refine_mixed(&poly, &mut cut, 120.0, 4, 1);
        let mesh = topo_cut::assemble_cut(&poly, &cut).unwrap();
        let s = check(&poly, &mesh);
        prop_assert!(s.max_dihedral <= before + 1e-9, "{} > {before}", s.max_dihedral);
        prop_assert!((s.max_dihedral - worst).abs() < 1e-9 || worst == 0.0, "{s} vs {worst}");
    }
}

/// Two right prisms over the equilateral triangles (0, 1, 2) and (1, 3, 2) of a rhombus,
/// `h` high, children `i + 4`; they share the side (1, 2, 6, 5).
fn prism_pair(h: f64) -> PolyMesh {
    let mut p = PolyMesh::new();
    let y = 0.75f64.sqrt();
    let base = [[0.0, 0.0], [1.0, 0.0], [0.5, y], [1.5, y]];
    p.nodes = [0.0, h]
        .iter()
        .flat_map(|&z| base.iter().map(move |b| [b[0], b[1], z]))
        .collect();
    let face = |p: &mut PolyMesh, k: &[u32]| CellFace {
        face: p.push_face(k),
        reversed: false,
    };
    let shared = face(&mut p, &[1, 2, 6, 5]);
    let a = [
        face(&mut p, &[0, 2, 1]),
        face(&mut p, &[4, 5, 6]),
        face(&mut p, &[0, 1, 5, 4]),
        shared,
        face(&mut p, &[2, 0, 4, 6]),
    ];
    p.push_cell(&a, 0, 0);
    let b = [
        face(&mut p, &[1, 2, 3]),
        face(&mut p, &[5, 7, 6]),
        face(&mut p, &[1, 3, 7, 5]),
        face(&mut p, &[3, 2, 6, 7]),
        CellFace {
            reversed: true,
            ..shared
        },
    ];
    p.push_cell(&b, 0, 1);
    p
}

/// The mixed cut's refining may keep a side between two cut cells whole (a pyramid's base on
/// both sides): two right prisms cut into tetrahedra, refined towards 91°, become a
/// tetrahedron and a pyramid each (the tetrahedron a right corner, 90°), the shared side
/// whole on both sides, conforming and the volume kept; refined as the tetrahedral cut is
/// (every side split), each stays three tetrahedra over 91°.
#[test]
fn the_mixed_refining_keeps_a_shared_side_whole_where_every_tet_cut_is_worse() {
    let poly = prism_pair(0.5);
    assert!(poly.validate().is_empty(), "{:?}", poly.validate());
    let rank: Vec<u32> = (0..poly.nodes.len() as u32).collect();
    let start = topo_cut::refine::Cut::from_ranks(&poly, &rank);
    let mut tets = start.clone();
    let old = topo_cut::refine::refine(&poly, &mut tets, 91.0, 4, 2);
    let t = check(&poly, &topo_cut::assemble_cut(&poly, &tets).unwrap());
    let mut mixed = start;
    let new = topo_cut::refine::refine_mixed(&poly, &mut mixed, 91.0, 4, 2);
    let m = check(&poly, &topo_cut::assemble_cut(&poly, &mixed).unwrap());
    println!("tets: {t} ({old:.2}); mixed: {m} ({new:.2})");
    assert!(old > 91.0 && t.tets == 6, "{t}");
    assert!(new <= 90.0 + 1e-9 && m.max_dihedral <= 90.0 + 1e-9, "{m}");
    assert_eq!((m.tets, m.pyramids), (2, 2), "{m}");
    assert_eq!(
        mixed.split[0],
        topo_cut::cone::UNRANKED,
        "the shared side is whole"
    );
}

/// The prism cut with one cell flagged in a layer: the triangles' layers without a flag keep
/// every prism, the flagged layer is tetrahedra whole (a prism beside a cut cell would need a
/// pyramid); the hexahedra are halved into prisms, and one flag cuts every hexahedron joined
/// to it by quadrilaterals (their columns and the layers beside them: the whole shell).
#[test]
fn the_prism_cut_cuts_a_layer_with_a_flag_whole_and_keeps_the_others() {
    for quads in [false, true] {
        let spec = Spec::new(3, quads, 4);
        let poly = fixture::poly(&spec);
        let flagged_layer = 2;
        let first = (0..poly.cell_count())
            .find(|&c| poly.cell_layer[c] == flagged_layer)
            .unwrap();
        let flags: Vec<bool> = (0..poly.cell_count()).map(|c| c == first).collect();
        let mesh = topo_cut::cut_to_prisms(&poly, &flags).expect("prisms");
        let p = check(&poly, &mesh);
        assert_eq!(p.pyramids + p.hexes, 0, "quads {quads}: {p}");
        for i in 0..mesh.cells.len() {
            let shape = mesh.cells.get(i).ty.shape;
            let want = if quads || mesh.cell_layer[i] == flagged_layer {
                Shape::Tet
            } else {
                Shape::Prism
            };
            assert_eq!(
                shape, want,
                "quads {quads}: cell {i} in layer {}",
                mesh.cell_layer[i]
            );
        }
        let unflagged = topo_cut::cut_to_prisms(&poly, &[]).expect("prisms");
        let u = check(&poly, &unflagged);
        let cells = poly.cell_count();
        assert_eq!((u.prisms, u.tets), (cells * if quads { 2 } else { 1 }, 0));
        println!("quads {quads}: flagged {p}; unflagged {u}");
    }
}
