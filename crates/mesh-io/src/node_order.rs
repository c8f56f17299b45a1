//! Node orderings of the reference cells: Gmsh's (the data model's) and VTK's Lagrange
//! cells', with the explicit permutation between them that the `.vtu` writer applies.
//!
//! Gmsh numbers the nodes of a high-order cell: corners, then the nodes of each edge in edge
//! order and edge direction, then face nodes, then interior nodes, the interior of a face or
//! cell being numbered recursively like a cell of lower order. VTK's Lagrange cells number
//! corners, then edges, then faces, then the interior, but run the third and fourth edges of a
//! quadrilateral along +x and +y (Gmsh runs them around the cell) and number interior points
//! in lexicographic order (Gmsh recursively). The tables here were read off the two tools and
//! are checked by the tests against the reference coordinates dumped from Gmsh 4.15
//! (`gmsh.model.mesh.getElementProperties`) and VTK 9.7 (`vtkLagrange*::InterpolateFunctions`)
//! by `tests/python/dump_reference_nodes.py` into `tests/data/reference_nodes.json`.
//!
//! This module holds tables only; it does no IO.

use std::sync::OnceLock;

use mesh_model::{CellType, Shape};

/// The VTK cell type number of a cell type: the linear VTK cell for order 1, the Lagrange
/// cell for orders 2 and 3, the 14-node pyramid as VTK's 13-node quadratic pyramid (27) and
/// the 30-node one as VTK's linear pyramid (14; see [`vtk_from_gmsh`]); `None` where no
/// verified node ordering exists here.
pub fn vtk_cell_type(ty: CellType) -> Option<u8> {
    vtk_from_gmsh(ty)?;
    let linear = ty.order == 1;
    Some(match ty.shape {
        Shape::Pyramid if ty.order == 2 => 27,
        Shape::Line if linear => 3,
        Shape::Line => 68,
        Shape::Tri if linear => 5,
        Shape::Tri => 69,
        Shape::Quad if linear => 9,
        Shape::Quad => 70,
        Shape::Tet if linear => 10,
        Shape::Tet => 71,
        Shape::Hex if linear => 12,
        Shape::Hex => 72,
        Shape::Prism if linear => 13,
        Shape::Prism => 73,
        Shape::Pyramid => 14,
    })
}

/// The permutation from Gmsh's node order to VTK's: VTK node `k` is Gmsh node `perm[k]`.
/// `None` for cell types without a verified ordering (see [`vtk_cell_type`]).
///
/// The 14-node pyramid has no VTK cell (VTK's Lagrange pyramid is not implemented, its
/// tri-quadratic pyramid has 19 nodes): it maps onto the quadratic pyramid (27), 5 corners
/// and 8 edge nodes in VTK's edge order 0-1, 1-2, 2-3, 3-0, 0-4, 1-4, 2-4, 3-4
/// (`vtkQuadraticPyramid`), leaving out Gmsh's base node 13. That is exact when the base node
/// is the serendipity point of the base's edges, ½ Σ edge nodes − ¼ Σ corners (the node the
/// curving puts there); `crate::vtu` refuses any other. VTK has no cubic pyramid at all: the
/// 30-node pyramid maps onto its 5 corners, VTK's linear pyramid, which is exact when every
/// other node sits where the linear pyramid puts it (a straight-sided pyramid); `crate::vtu`
/// refuses a curved one.
pub fn vtk_from_gmsh(ty: CellType) -> Option<&'static [usize]> {
    const ID: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9];
    const QUAD16: [usize; 16] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8, 11, 10, 12, 13, 15, 14];
    const TET10: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8];
    const TET20: [usize; 20] = [
        0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 10, 15, 14, 13, 12, 17, 19, 18, 16,
    ];
    const HEX27: [usize; 27] = [
        0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15, 22, 23, 21, 24, 20,
        25, 26,
    ];
    const HEX64: [usize; 64] = [
        0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 14, 15, 19, 18, 10, 11, 24, 25, 28, 29, 31, 30, 26, 27, 12,
        13, 16, 17, 20, 21, 22, 23, 40, 43, 41, 42, 44, 45, 47, 46, 36, 37, 39, 38, 49, 48, 50, 51,
        32, 35, 33, 34, 52, 53, 55, 54, 56, 57, 59, 58, 60, 61, 63, 62,
    ];
    const PRISM18: [usize; 18] = [0, 1, 2, 3, 4, 5, 6, 9, 7, 12, 14, 13, 8, 10, 11, 15, 17, 16];
    const PRISM40: [usize; 40] = [
        0, 1, 2, 3, 4, 5, 6, 7, 12, 13, 9, 8, 18, 19, 22, 23, 21, 20, 10, 11, 14, 15, 16, 17, 24,
        25, 26, 27, 29, 28, 34, 35, 37, 36, 33, 30, 32, 31, 38, 39,
    ];
    const PYRAMID13: [usize; 13] = [0, 1, 2, 3, 4, 5, 8, 10, 6, 7, 9, 11, 12];
    let n = ty.node_count();
    match (ty.shape, ty.order) {
        (_, 1) => Some(&ID[..n]),
        (Shape::Line, 2) => Some(&ID[..3]),
        (Shape::Line, 3) => Some(&[0, 1, 2, 3]),
        (Shape::Tri, 2 | 3) | (Shape::Quad, 2) => Some(&ID[..n]),
        (Shape::Quad, 3) => Some(&QUAD16),
        (Shape::Tet, 2) => Some(&TET10),
        (Shape::Tet, 3) => Some(&TET20),
        (Shape::Hex, 2) => Some(&HEX27),
        (Shape::Hex, 3) => Some(&HEX64),
        (Shape::Prism, 2) => Some(&PRISM18),
        (Shape::Prism, 3) => Some(&PRISM40),
        (Shape::Pyramid, 2) => Some(&PYRAMID13),
        (Shape::Pyramid, 3) => Some(&ID[..5]),
        _ => None,
    }
}

/// The permutation from Gmsh's node order to the order a `.vtu` file of format version 1.0
/// holds (the version [`crate::vtu`] writes, the newest meshio 5.3.5 reads): VTK's
/// ([`vtk_from_gmsh`]) but for the Lagrange hexahedron, whose edges 10 and 11 (corners 2–6 and
/// 3–7) come exchanged. VTK 9.1 exchanged them in its own numbering, and its reader converts
/// files older than version 2.2 from the order before; written in VTK's present order, a
/// version 1.0 file is read with those edges' nodes swapped, folding every hexahedron.
pub fn vtu_from_gmsh(ty: CellType) -> Option<&'static [usize]> {
    static HEX: [OnceLock<Vec<usize>>; 2] = [const { OnceLock::new() }; 2];
    let perm = vtk_from_gmsh(ty)?;
    if ty.shape != Shape::Hex || ty.order < 2 {
        return Some(perm);
    }
    Some(HEX[ty.order as usize - 2].get_or_init(|| {
        let per = ty.order as usize - 1;
        let mut file = perm.to_vec();
        let (ten, eleven) = (8 + 10 * per, 8 + 11 * per);
        for i in 0..per {
            file.swap(ten + i, eleven + i);
        }
        file
    }))
}

pub use mesh_model::reference::reference_nodes as gmsh_reference_nodes;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::msh::{cell_type_of_gmsh, gmsh_type_id};

    /// One reference element as dumped from Gmsh or VTK.
    struct Reference {
        type_id: u32,
        order: u8,
        nodes: Vec<[f64; 3]>,
    }

    fn load(tool: &str) -> Vec<Reference> {
        let text = include_str!("../tests/data/reference_nodes.json");
        let v: serde_json::Value = serde_json::from_str(text).unwrap();
        v[tool]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| Reference {
                type_id: e["type"].as_u64().unwrap() as u32,
                order: e["order"].as_u64().unwrap() as u8,
                nodes: e["nodes"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|p| {
                        let p = p.as_array().unwrap();
                        [0, 1, 2].map(|k| p[k].as_f64().unwrap())
                    })
                    .collect(),
            })
            .collect()
    }

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-9)
    }

    /// Gmsh's reference coordinates mapped onto VTK's parametric domain: [0, 1] instead of
    /// [−1, 1] along the axes where Gmsh uses the symmetric interval.
    fn gmsh_to_vtk_domain(shape: Shape, p: [f64; 3]) -> [f64; 3] {
        let h = |x: f64| (x + 1.0) / 2.0;
        match shape {
            Shape::Line => [h(p[0]), 0.0, 0.0],
            Shape::Quad => [h(p[0]), h(p[1]), 0.0],
            Shape::Hex => [h(p[0]), h(p[1]), h(p[2])],
            Shape::Prism => [p[0], p[1], h(p[2])],
            Shape::Pyramid => [h(p[0]), h(p[1]), p[2]],
            Shape::Tri | Shape::Tet => p,
        }
    }

    #[test]
    fn element_types_match_gmsh_reference() {
        let refs = load("gmsh");
        assert!(refs.len() >= 20);
        for r in &refs {
            let ty = cell_type_of_gmsh(r.type_id)
                .unwrap_or_else(|| panic!("Gmsh type {} unknown", r.type_id));
            assert_eq!(ty.order, r.order, "type {}", r.type_id);
            assert_eq!(ty.node_count(), r.nodes.len(), "type {}", r.type_id);
            assert_eq!(gmsh_type_id(ty), Some(r.type_id));
        }
    }

    #[test]
    fn generated_gmsh_nodes_match_gmsh_itself() {
        let mut checked = 0;
        for r in load("gmsh") {
            let ty = cell_type_of_gmsh(r.type_id).unwrap();
            let ours = gmsh_reference_nodes(ty).unwrap();
            assert_eq!(ours.len(), r.nodes.len(), "{ty:?}");
            for (k, (a, b)) in ours.iter().zip(&r.nodes).enumerate() {
                assert!(close(*a, *b), "{ty:?} node {k}: ours {a:?}, Gmsh {b:?}");
            }
            checked += 1;
        }
        assert_eq!(checked, 21);
    }

    #[test]
    fn permuted_gmsh_nodes_land_where_vtk_expects_them() {
        let gmsh = load("gmsh");
        let mut checked = 0;
        for v in load("vtk") {
            let shape = match v.type_id {
                5 | 69 => Shape::Tri,
                9 | 70 => Shape::Quad,
                10 | 71 => Shape::Tet,
                12 | 72 => Shape::Hex,
                13 | 73 => Shape::Prism,
                14 => Shape::Pyramid,
                other => panic!("unexpected VTK type {other}"),
            };
            let ty = CellType::new(shape, v.order);
            let perm = vtk_from_gmsh(ty).unwrap();
            assert_eq!(vtk_cell_type(ty), Some(v.type_id as u8), "{ty:?}");
            let g = gmsh
                .iter()
                .find(|g| g.type_id == gmsh_type_id(ty).unwrap())
                .unwrap();
            assert_eq!(perm.len(), v.nodes.len(), "{ty:?}");
            let mut seen = vec![false; perm.len()];
            for (k, &gi) in perm.iter().enumerate() {
                assert!(!seen[gi], "{ty:?}: Gmsh node {gi} used twice");
                seen[gi] = true;
                let at = gmsh_to_vtk_domain(shape, g.nodes[gi]);
                assert!(
                    close(at, v.nodes[k]),
                    "{ty:?}: VTK node {k} expects {:?}, Gmsh node {gi} is at {at:?}",
                    v.nodes[k]
                );
            }
            checked += 1;
        }
        assert_eq!(checked, 16);
    }

    #[test]
    fn the_14_node_pyramid_maps_onto_vtks_quadratic_pyramid() {
        // vtkQuadraticPyramid's edges (VTK's documentation), in its corner numbering, which
        // is Gmsh's
        const VTK_EDGES: [[usize; 2]; 8] = [
            [0, 1],
            [1, 2],
            [2, 3],
            [3, 0],
            [0, 4],
            [1, 4],
            [2, 4],
            [3, 4],
        ];
        let ty = CellType::new(Shape::Pyramid, 2);
        assert_eq!(vtk_cell_type(ty), Some(27));
        let perm = vtk_from_gmsh(ty).unwrap();
        let g = gmsh_reference_nodes(ty).unwrap();
        assert_eq!(perm[..5], [0, 1, 2, 3, 4]);
        for (k, [a, b]) in VTK_EDGES.into_iter().enumerate() {
            let mid = [0, 1, 2].map(|d| 0.5 * (g[a][d] + g[b][d]));
            assert!(close(g[perm[5 + k]], mid), "VTK node {}", 5 + k);
        }
        // every Gmsh node but the base's centre (13), once
        let mut used = perm.to_vec();
        used.sort_unstable();
        assert_eq!(used, (0..13).collect::<Vec<_>>());
        assert_eq!(g[13], [0.0; 3]);
    }

    #[test]
    fn a_vtu_file_holds_the_hexahedra_in_vtks_order_before_9_1() {
        // VTK 9.7's hexahedron edges 10 and 11 run along 2–6 and 3–7 (x = 1 and x = 0 at
        // y = 1); a version 1.0 file has them the other way round
        for p in [2, 3] {
            let ty = CellType::new(Shape::Hex, p);
            let (vtk, file) = (vtk_from_gmsh(ty).unwrap(), vtu_from_gmsh(ty).unwrap());
            let g = gmsh_reference_nodes(ty).unwrap();
            let per = usize::from(p) - 1;
            for i in 0..per {
                let (ten, eleven) = (8 + 10 * per + i, 8 + 11 * per + i);
                assert_eq!((file[ten], file[eleven]), (vtk[eleven], vtk[ten]));
                assert_eq!(g[file[ten]][..2], [-1.0, 1.0], "P{p}: edge 10 at x = −1");
            }
            let same = (0..vtk.len()).filter(|&k| vtk[k] == file[k]).count();
            assert_eq!(same, vtk.len() - 2 * per);
        }
        let tet = CellType::new(Shape::Tet, 3);
        assert_eq!(vtu_from_gmsh(tet), vtk_from_gmsh(tet));
    }

    #[test]
    fn the_30_node_pyramid_maps_onto_vtks_linear_pyramid() {
        let ty = CellType::new(Shape::Pyramid, 3);
        assert_eq!(vtk_cell_type(ty), Some(14));
        assert_eq!(vtk_from_gmsh(ty), Some(&[0, 1, 2, 3, 4][..]));
        assert_eq!(vtk_cell_type(CellType::new(Shape::Tet, 4)), None);
    }
}
