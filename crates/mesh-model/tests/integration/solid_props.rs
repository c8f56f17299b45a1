//! Properties of the 3D checks and the face topology on jittered box grids: every column of
//! cells is hexes or prisms (each hex cut along a diagonal of its base), or the whole box is
//! cut into tetrahedra (six per hex along its main diagonal). Such a grid is conforming and
//! positive; inverting any one cell or dropping it is found; its cells, faces, edges and
//! nodes are those of a ball (Euler characteristic 1).

use mesh_model::{CellType, Cells, Dim, Mesh, Patch, Problem, Role, Shape, Topology, validate};
use proptest::prelude::*;

/// How the hexes of the box are cut.
#[derive(Debug, Clone)]
enum Cut {
    /// Per column (`(i, j)`, cycled): a hex column (false) or a prism column (true).
    Columns(Vec<bool>),
    /// Six tetrahedra per hex.
    Tets,
}

/// The six tetrahedra of the unit cube along its diagonal 0–6 (hex corner numbers): one per
/// order of the three axes, walking from corner 0 one axis at a time.
fn kuhn() -> impl Iterator<Item = [usize; 4]> {
    // the hex corner at offsets (x, y, z) ∈ {0, 1}³, Gmsh order
    let at = |p: [usize; 3]| [[0, 3], [1, 2]][p[0]][p[1]] + 4 * p[2];
    let orders = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    orders.into_iter().map(move |axes| {
        let mut p = [0; 3];
        let mut tet = [at(p); 4];
        for (step, &axis) in axes.iter().enumerate() {
            p[axis] = 1;
            tet[step + 1] = at(p);
        }
        tet
    })
}

/// The integer position of hex corner `c` (Gmsh order) of the hex at `(i, j, k)`.
fn corner(i: usize, j: usize, k: usize, c: usize) -> [usize; 3] {
    let (di, dj) = [(0, 0), (1, 0), (1, 1), (0, 1)][c % 4];
    [i + di, j + dj, k + c / 4]
}

fn signed_volume(p: [[f64; 3]; 4]) -> f64 {
    let d = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let (a, b, c) = (d(p[1], p[0]), d(p[2], p[0]), d(p[3], p[0]));
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

/// An n × n × n box of cells cut as `cut`, interior nodes jittered by at most 0.05 of a cell,
/// boundary facets the cells' faces on the box's sides (outward).
fn box_grid(n: [usize; 3], jitter: &[f64], cut: &Cut) -> Mesh {
    let [nx, ny, nz] = n;
    let id = |p: [usize; 3]| (p[0] + (nx + 1) * (p[1] + (ny + 1) * p[2])) as u32;
    let mut m = Mesh::new(Dim::Three, 1);
    let mut grid = Vec::new();
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let interior = i > 0 && i < nx && j > 0 && j < ny && k > 0 && k < nz;
                let at = grid.len();
                let shift = |d: usize| {
                    if interior {
                        0.05 * jitter[(3 * at + d) % jitter.len()]
                    } else {
                        0.0
                    }
                };
                m.nodes.push([
                    i as f64 + shift(0),
                    j as f64 + shift(1),
                    k as f64 + shift(2),
                ]);
                grid.push([i, j, k]);
            }
        }
    }
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let h: Vec<u32> = (0..8).map(|c| id(corner(i, j, k, c))).collect();
                let pick = |l: &[usize]| l.iter().map(|&c| h[c]).collect::<Vec<u32>>();
                match cut {
                    Cut::Columns(mask) if mask[(j * nx + i) % mask.len()] => {
                        let prism = CellType::new(Shape::Prism, 1);
                        m.cells.push(prism, &pick(&[0, 1, 2, 4, 5, 6]));
                        m.cells.push(prism, &pick(&[0, 2, 3, 4, 6, 7]));
                    }
                    Cut::Columns(_) => {
                        m.cells.push(CellType::new(Shape::Hex, 1), &h);
                    }
                    Cut::Tets => {
                        for t in kuhn() {
                            let mut t = pick(&t);
                            let x = [0, 1, 2, 3].map(|c| m.nodes[t[c] as usize]);
                            if signed_volume(x) < 0.0 {
                                t.swap(1, 2);
                            }
                            m.cells.push(CellType::new(Shape::Tet, 1), &t);
                        }
                    }
                }
            }
        }
    }
    let on_side = |f: &[u32]| {
        (0..3).any(|d| {
            let side = |v: u32| grid[v as usize][d];
            let s = side(f[0]);
            (s == 0 || s == n[d]) && f.iter().all(|&v| side(v) == s)
        })
    };
    let mut boundary = Cells::new();
    for c in m.cells.iter() {
        for face in c.ty.shape.faces() {
            let f: Vec<u32> = face.iter().map(|&l| c.nodes[l]).collect();
            if on_side(&f) {
                let shape = if f.len() == 3 {
                    Shape::Tri
                } else {
                    Shape::Quad
                };
                boundary.push(CellType::new(shape, 1), &f);
            }
        }
    }
    m.boundary_patch = vec![0; boundary.len()];
    m.boundary = boundary;
    m.patches.push(Patch {
        name: "box".into(),
        role: Role::Farfield,
    });
    m
}

fn box_strategy() -> impl Strategy<Value = Mesh> {
    let cut = prop_oneof![
        prop::collection::vec(any::<bool>(), 1..6).prop_map(Cut::Columns),
        Just(Cut::Tets),
    ];
    (
        [1usize..4, 1usize..4, 1usize..4],
        prop::collection::vec(-1.0f64..1.0, 1..30),
        cut,
    )
        .prop_map(|(n, jitter, cut)| box_grid(n, &jitter, &cut))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn a_cut_box_is_valid_and_a_ball(m in box_strategy()) {
        prop_assert_eq!(validate(&m), vec![]);
        let t = Topology::new(&m);
        let euler = m.nodes.len() as i64 - t.edges.len() as i64 + t.faces.len() as i64
            - m.cells.len() as i64;
        prop_assert_eq!(euler, 1);
        let uses: usize = (0..t.faces.len() as u32).map(|f| t.faces.cells(f).len()).sum();
        let expected: usize = m.cells.iter().map(|c| c.ty.shape.faces().len()).sum();
        prop_assert_eq!(uses, expected);
    }

    #[test]
    fn an_inverted_cell_is_found(m in box_strategy(), pick in any::<prop::sample::Index>()) {
        let mut m = m;
        let i = pick.index(m.cells.len());
        let c = m.cells.get(i);
        let half = c.ty.shape.corners() / 2;
        // a tet with two corners swapped; a prism or hex with its bottom and top swapped
        let nodes = m.cells.nodes_mut(i);
        if nodes.len() == 4 {
            nodes.swap(0, 1);
        } else {
            nodes.rotate_left(half);
        }
        let found = validate(&m)
            .iter()
            .any(|p| matches!(p, Problem::NotPositiveCorner { cell, .. } if *cell == i));
        prop_assert!(found);
    }

    #[test]
    fn a_dropped_cell_is_found(m in box_strategy(), pick in any::<prop::sample::Index>()) {
        let drop = pick.index(m.cells.len());
        let mut m = m;
        m.cells.retain(|i, _| i != drop);
        let found = validate(&m)
            .iter()
            .any(|p| matches!(p, Problem::NonConformingFace { cells: 0 | 1, .. }));
        prop_assert!(found);
    }
}
