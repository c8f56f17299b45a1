//! Properties of `validate` and of the topology on structured grids of mixed cells: a good
//! grid has no problem and covers its rectangle exactly; flipping any one cell or dropping any
//! one cell is found; its edges are those of a disk (interior edges in two cells, boundary
//! edges in one cell and on one facet, Euler characteristic 1).

use mesh_model::topology::Use;
use mesh_model::{
    CellType, Dim, Mesh, Patch, Problem, Role, Shape, Topology, first_problem, validate,
};
use proptest::prelude::*;

/// An nx × ny grid on [0, w] × [0, h], interior nodes jittered by at most 0.15 of a cell (so
/// that every quad and both triangles of its split stay positive), cells in `tri_mask` split into
/// two triangles, boundary facets counter-clockwise.
fn grid(nx: usize, ny: usize, w: f64, h: f64, jitter: &[f64], tri_mask: &[bool]) -> Mesh {
    let mut m = Mesh::new(Dim::Two, 1);
    let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    for j in 0..=ny {
        for i in 0..=nx {
            let interior = i > 0 && i < nx && j > 0 && j < ny;
            let k = (j * (nx + 1) + i) % jitter.len();
            let (dx, dy) = if interior {
                (jitter[k], jitter[(k + 1) % jitter.len()])
            } else {
                (0.0, 0.0)
            };
            let x = w * (i as f64 + 0.15 * dx) / nx as f64;
            let y = h * (j as f64 + 0.15 * dy) / ny as f64;
            m.nodes.push([x, y, 0.0]);
        }
    }
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if tri_mask[(j * nx + i) % tri_mask.len()] {
                m.cells.push(CellType::new(Shape::Tri, 1), &[a, b, c]);
                m.cells.push(CellType::new(Shape::Tri, 1), &[a, c, d]);
            } else {
                m.cells.push(CellType::new(Shape::Quad, 1), &[a, b, c, d]);
            }
        }
    }
    let line = CellType::new(Shape::Line, 1);
    let mut ring = Vec::new();
    ring.extend((0..nx).map(|i| id(i, 0)));
    ring.extend((0..ny).map(|j| id(nx, j)));
    ring.extend((0..nx).map(|i| id(nx - i, ny)));
    ring.extend((0..ny).map(|j| id(0, ny - j)));
    for k in 0..ring.len() {
        m.boundary
            .push(line, &[ring[k], ring[(k + 1) % ring.len()]]);
        m.boundary_patch.push(0);
    }
    m.patches.push(Patch {
        name: "box".into(),
        role: Role::Farfield,
    });
    m
}

fn grid_strategy() -> impl Strategy<Value = Mesh> {
    (
        1usize..8,
        1usize..8,
        0.1f64..100.0,
        0.1f64..100.0,
        prop::collection::vec(-1.0f64..1.0, 1..20),
        prop::collection::vec(any::<bool>(), 1..10),
    )
        .prop_map(|(nx, ny, w, h, jitter, mask)| grid(nx, ny, w, h, &jitter, &mask))
}

proptest! {
    #[test]
    fn a_jittered_grid_is_valid_and_covers_its_rectangle(m in grid_strategy()) {
        prop_assert_eq!(validate(&m), vec![]);
        let w = m.nodes.iter().map(|p| p[0]).fold(0.0, f64::max);
        let h = m.nodes.iter().map(|p| p[1]).fold(0.0, f64::max);
        prop_assert!((m.linear_area() - w * h).abs() <= 1e-12 * w * h);
    }

    #[test]
    fn flipping_one_cell_is_found(m in grid_strategy(), pick in any::<prop::sample::Index>()) {
        let mut m = m;
        let i = pick.index(m.cells.len());
        m.cells.nodes_mut(i).reverse();
        let expected = Problem::NotPositive { cell: i, area: m.linear_cell_area(i) };
        let found = validate(&m).contains(&expected);
        prop_assert!(found);
    }

    #[test]
    fn dropping_one_cell_is_found(m in grid_strategy(), pick in any::<prop::sample::Index>()) {
        let drop = pick.index(m.cells.len());
        let mut m = m;
        m.cells.retain(|i, _| i != drop);
        let found = validate(&m).iter().any(|p| matches!(p, Problem::NonConforming { .. }));
        prop_assert!(found);
    }

    #[test]
    fn the_edges_of_a_grid_are_those_of_a_disk(m in grid_strategy()) {
        let edges = Topology::new(&m).edges;
        let mut boundary = 0;
        for e in 0..edges.len() as u32 {
            let (cells, facets) = (edges.cells(e).len(), edges.facets(e).len());
            prop_assert!((cells, facets) == (2, 0) || (cells, facets) == (1, 1), "{:?}", edges.nodes(e));
            boundary += facets;
            // the reverse map agrees with the uses
            for &Use { cell, local } in edges.cells(e) {
                prop_assert_eq!(edges.of_cell(cell as usize)[local as usize], e);
                let k = m.cells.get(cell as usize).corners();
                let [a, b] = m.cells.get(cell as usize).ty.shape.edges()[local as usize];
                prop_assert_eq!(edges.nodes(e), &[k[a].min(k[b]), k[a].max(k[b])][..]);
            }
            if e > 0 {
                prop_assert!(edges.key(e - 1) < edges.key(e));
            }
        }
        prop_assert_eq!(boundary, m.boundary.len());
        let euler = m.nodes.len() as i64 - edges.len() as i64 + m.cells.len() as i64;
        prop_assert_eq!(euler, 1);
    }

    #[test]
    fn the_use_counts_are_those_of_the_topology(m in grid_strategy(), pick in any::<prop::sample::Index>()) {
        // with one cell dropped too, so that some counts are not those of a sound mesh
        let mut damaged = m.clone();
        let drop = pick.index(m.cells.len());
        damaged.cells = mesh_model::Cells::default();
        for (_, cell) in m.cells.iter().enumerate().filter(|&(c, _)| c != drop) {
            damaged.cells.push(cell.ty, cell.nodes);
        }
        for mesh in [&m, &damaged] {
            let edges = Topology::new(mesh).edges;
            let mut seen = Vec::new();
            let _ = mesh_model::topology::for_each_use_count::<2, ()>(
                mesh.cells.shapes_and_corners(),
                mesh.boundary.iter().map(|f| f.corners()),
                |k, cells, facets| {
                    seen.push((k.to_vec(), cells, facets));
                    std::ops::ControlFlow::Continue(())
                },
            );
            let expected: Vec<_> = (0..edges.len() as u32)
                .map(|e| (edges.nodes(e).to_vec(), edges.cells(e).len(), edges.facets(e).len()))
                .collect();
            prop_assert_eq!(&seen, &expected);
            // the 2D scatter by lower node: the same calls in the same order
            let mut by_node = Vec::new();
            let _ = mesh_model::topology::for_each_edge_use_count::<()>(
                mesh.cells.shapes_and_corners(),
                mesh.boundary.iter().map(|f| f.corners()),
                |k, cells, facets| {
                    by_node.push((k.to_vec(), cells, facets));
                    std::ops::ControlFlow::Continue(())
                },
            );
            prop_assert_eq!(by_node, expected);
        }
    }

    #[test]
    fn the_first_problem_is_the_first_of_all_problems(m in grid_strategy(), pick in any::<prop::sample::Index>()) {
        let mut m = m;
        let i = pick.index(m.cells.len());
        m.cells.nodes_mut(i).reverse();
        prop_assert_eq!(first_problem(&m), validate(&m).first().cloned());
    }
}
