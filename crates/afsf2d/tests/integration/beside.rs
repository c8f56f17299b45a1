//! `grow_mesh_with`'s task sees the layered cells as the layer growth left them, in the
//! mesh's numbers: the mesh's cells are those cells less the ones it is told were peeled,
//! then the fill's triangles, whatever the number of threads.

use crate::common;

use afsf2d::grow_mesh_with;
use common::real::{mesher_input, real_case};
use mesh_model::Cells;

#[test]
fn the_mesh_is_the_cells_seen_less_the_peeled_then_the_fill() {
    let mut peeled = 0;
    for name in ["naca0012", "30p30n", "two-element", "bat", "lshape"] {
        let (loops, params) = mesher_input(&real_case(name));
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a thread pool");
            let (out, beside) = pool
                .install(|| grow_mesh_with(&loops, &params, |cells, n| (cells.clone(), n)))
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            let (seen, nodes) = beside.made;
            let left_out = &beside.left_out;
            assert!(
                left_out.windows(2).all(|w| w[0] < w[1]),
                "{name}: {left_out:?}"
            );
            let mesh = &out.layered.mesh;
            let layered = out.layered.layering.layered_cells;
            assert_eq!(layered, seen.len() - left_out.len(), "{name}");
            let mut want = Cells::new();
            for i in (0..seen.len()).filter(|&i| left_out.binary_search(&(i as u32)).is_err()) {
                let c = seen.get(i);
                want.push(c.ty, c.nodes);
            }
            for i in layered..mesh.cells.len() {
                let c = mesh.cells.get(i);
                want.push(c.ty, c.nodes);
            }
            assert!(want == mesh.cells, "{name} at {threads} threads");
            // the seen cells' nodes are the mesh's first
            assert!(nodes <= mesh.nodes.len(), "{name}");
            let highest = (0..seen.len())
                .flat_map(|i| seen.get(i).nodes.to_vec())
                .max();
            assert!(highest.is_some_and(|h| (h as usize) < nodes), "{name}");
            peeled += left_out.len();
        }
    }
    // (some case peels: the left-out cells are exercised)
    assert!(peeled > 0, "no case peeled a cell");
}
