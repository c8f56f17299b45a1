//! The curving builds its edge table (and the edges' points) and assembles its cells (in
//! chunks of 8192) on every thread of the pool, and `curve_mesh_owned_with` runs a task beside
//! its decisions: the curved mesh (every node to the last bit, every cell, boundary line and
//! per-cell record) and the record of its decisions are the same with 1, 2 and 3 threads, at
//! P2 and P3, mixed and cut into triangles, and the same from `curve_mesh_owned` as from
//! `curve_mesh`.

use mesh_model::{CellType, Mesh};
use test_cases::{Grown, grow, real_case};
use vector_adding::{Curved, CurvingParams, LoopCurve};

/// A mesh's order, node bits, cells, boundary lines and per-cell and per-facet records.
type Bits = (
    u8,
    Vec<[u64; 3]>,
    (Vec<CellType>, Vec<u32>),
    (Vec<CellType>, Vec<u32>),
    (Vec<u32>, Vec<u32>, Vec<u32>),
);

/// Everything of a mesh, its coordinates as bits.
fn bits(mesh: &Mesh) -> Bits {
    let nodes: Vec<[u64; 3]> = mesh.nodes.iter().map(|p| p.map(f64::to_bits)).collect();
    let cells = (
        mesh.cells.types().to_vec(),
        mesh.cells.flat_nodes().to_vec(),
    );
    let boundary = (
        mesh.boundary.types().to_vec(),
        mesh.boundary.flat_nodes().to_vec(),
    );
    let records = (
        mesh.cell_layer.clone(),
        mesh.cell_pipe.clone(),
        mesh.boundary_patch.clone(),
    );
    (mesh.order, nodes, cells, boundary, records)
}

fn curved_on(threads: usize, g: &Grown, params: &CurvingParams, owned: bool) -> Curved {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a pool");
    pool.install(|| {
        if owned {
            let loops: Vec<LoopCurve<'_>> = g
                .curves
                .iter()
                .zip(&g.nodes)
                .map(|(curve, bn)| LoopCurve { curve, t: &bn.t })
                .collect();
            vector_adding::curve_mesh_owned(g.output.layered.clone(), &loops, params)
        } else {
            g.curve(params)
        }
    })
    .expect("the built-in cases curve")
}

#[test]
fn one_two_and_three_threads_curve_to_the_same_bits() {
    for name in ["naca0012", "30p30n"] {
        let g = grow(&real_case(name));
        for (order, triangles) in [(2, false), (3, false), (2, true), (3, true)] {
            let params = CurvingParams {
                order,
                triangles,
                ..g.curving_params(order, triangles)
            };
            let one = curved_on(1, &g, &params, false);
            // more than one chunk of the assembly
            assert!(
                one.mesh.cells.len() > 8192,
                "{name}: {}",
                one.mesh.cells.len()
            );
            let want = bits(&one.mesh);
            for (threads, owned) in [(2, false), (3, false), (2, true), (1, true)] {
                let other = curved_on(threads, &g, &params, owned);
                let at =
                    format!("{name} P{order} cut {triangles}, {threads} threads, owned {owned}");
                assert!(bits(&other.mesh) == want, "{at}: the meshes differ");
                assert_eq!(other.decisions, one.decisions, "{at}");
                assert_eq!(other.stats.curved_edges, one.stats.curved_edges, "{at}");
            }
        }
    }
}
