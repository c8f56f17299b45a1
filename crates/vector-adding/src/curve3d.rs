//! P2 and P3 curving of a 3D layered mesh by Vector-Adding (dissertation §5.3; issue 13,
//! item 4; issue 47, item 4):
//! the linear mesh `topo-cut` makes of `afsf3d`'s layers (tetrahedra, or tetrahedra,
//! pyramids, prisms and hexahedra) with its `cell_layer` and `cell_pipe`, the columns of the
//! layering (each wall node and its children, bottom-up) and a [`SurfaceProjector`] onto
//! the true wall, in; a P2 or P3 mesh, out.
//!
//! The mid-edge node of every wall edge goes onto the true surface. Every other edge takes
//! the displacement (curved minus straight mid-edge node) of the edge below it — the edge
//! whose ends are the parents of its ends in the layer below (an end already in that layer
//! stays) — which is the dissertation's adding of half the extrusion vectors: the mid node
//! of PB over PQ is mid(PQ) + ½·QB. Where merged children give an edge several edges below,
//! their displacements are averaged; extrusion edges (a node and its parent) and the edges
//! of the outer front stay straight where the cells below them are valid so. The marching goes layer by layer (`march3d`), with the
//! stops of the 2D curving: above `min_curved_layers` an edge goes straight when every
//! cell below it is then certified valid with a scaled Jacobian of at least
//! `stop_min_scaled_jacobian`; an edge that would make a cell invalid takes ½ or ¼ of the
//! displacement, or none; an edge with nothing below it (merged children) stays straight,
//! and so does everything above a straight edge. Every decision rests on `jacobian-check`'s
//! certificate. Quadrilateral faces get their centre node from their four edges
//! (the Coons patch: ½ Σ edge nodes − ¼ Σ corners), a hexahedron its centre likewise. At P3
//! each edge carries its two nodes' displacements together, the wall's at equal arc length
//! on the surface, and the faces' and cells' interior nodes come from `nodes3d`.
//!
//! Pyramids are curved like every other cell (the 14- and 30-node pyramids are certified in
//! Gmsh's Bergot space by `jacobian_check`, the base's nodes Coons points of its edges).
//! An earlier version kept every edge of a pyramid above the wall straight, and with it
//! its neighbours' shared faces: in the mixed cut of the finer wing cases the cells next to
//! those straight faces, over curved edges below, were left invalid (153 cells in case 2).
//! The final certification judges every cell.
//! This module does no IO and does not certify the final mesh as a whole (the caller runs
//! `jacobian_check::check_mesh`).

use mesh_model::topology::{Edges, Faces};
use mesh_model::{CellType, Cells, Dim, Mesh, NONE, Role, Shape};

use crate::error::CurvingError;
use crate::params::CurvingParams;
pub use crate::projector::{SphereProjector, SurfaceProjector};
use crate::stats::StopCounts;

/// The P2 or P3 mesh and the figures of a 3D curving.
#[derive(Debug, Clone)]
pub struct Curved3d {
    /// The curved mesh: the linear nodes first (same indices), then the edges' inner nodes (in
    /// `mesh_model::topology` order); at P2 one node per quadrilateral face of a prism or
    /// hexahedron, then one per hexahedron; at P3 every face's interior nodes (one a
    /// triangle, four a quadrilateral), then the cells' (`nodes3d`).
    pub mesh: Mesh,
    /// What was done.
    pub stats: Curving3dStats,
}

/// What [`curve_mesh_3d`] did.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Curving3dStats {
    /// Edges of the mesh.
    pub edges: usize,
    /// Edges whose mid node is off the chord.
    pub curved_edges: usize,
    /// `curved_edges / edges`.
    pub curved_edge_fraction: f64,
    /// Wall edges put onto the true surface.
    pub wall_edges: usize,
    /// Where the marching stopped, by cause: `jacobian` — straight, every cell below certified
    /// good enough; `collapsed` — no edge below (merged children); `pipe_ended` — the outer
    /// front, left straight; `invalid` — no choice made the cells below valid (the full displacement kept).
    pub stops: StopCounts,
    /// Edges given only ½ or ¼ of the displacement below them.
    pub reduced: usize,
    /// The highest layer of nodes with a curved edge (the wall is layer 0).
    pub deepest_curved_layer: u32,
    /// Cells the marching left invalid that the repair mended (`march3d`'s `repair`).
    pub repaired: usize,
    /// Cells still invalid after the repair (the caller's certification reports them).
    pub unrepaired: usize,
}

/// Curves the linear 3D mesh `mesh` to P2 or P3. `columns[i]` lists a wall node and its children
/// bottom-up (`afsf3d::Grown3d::columns`); every node of the mesh must be in a column.
/// `params.order` must be 2.
///
/// # Errors
/// Bad parameters, a mesh that is not linear 3D, columns that do not match the mesh, a cell
/// the certified check cannot evaluate.
pub fn curve_mesh_3d(
    mesh: &Mesh,
    columns: &[Vec<u32>],
    surface: &dyn SurfaceProjector,
    params: &CurvingParams,
) -> Result<Curved3d, CurvingError> {
    params.check()?;
    check_input(mesh)?;
    let layers = crate::march3d::Layers::new(mesh, columns)?;
    let edges = Edges::build(mesh.cells.shapes_and_corners(), []);
    let faces = Faces::build(mesh.cells.shapes_and_corners(), []);
    let outer = outer_nodes(mesh);
    let mut m = crate::march3d::March::new(mesh, &edges, &faces, &layers, params);
    let wall_edges = m.place_wall(surface);
    m.march(&outer)?;
    let (repaired, unrepaired) = m.repair()?;
    let curved_edges = (0..edges.len() as u32)
        .filter(|&e| !m.is_straight(e))
        .count();
    let stats = Curving3dStats {
        wall_edges,
        curved_edge_fraction: crate::stats::share(curved_edges, edges.len()),
        curved_edges,
        edges: edges.len(),
        stops: m.stops,
        reduced: m.reduced,
        deepest_curved_layer: m.deepest,
        repaired,
        unrepaired,
    };
    let out = if params.order == 2 {
        assemble(mesh, &edges, &faces, &m)
    } else {
        crate::march3d::nodes::assemble_p3(mesh, &edges, &m)
    };
    Ok(Curved3d { mesh: out, stats })
}

/// The input is a sound linear 3D mesh of tetrahedra, pyramids, prisms and hexahedra with a
/// layer per cell.
fn check_input(mesh: &Mesh) -> Result<(), CurvingError> {
    let shapes = [Shape::Tet, Shape::Prism, Shape::Hex, Shape::Pyramid];
    crate::sound_linear(mesh, Dim::Three, &shapes, CurvingError::Unsupported3d)?;
    if mesh.cell_layer.len() != mesh.cells.len() || mesh.cell_layer.contains(&NONE) {
        return Err(CurvingError::BadLayers(
            "every cell needs its layer (cell_layer)".into(),
        ));
    }
    if mesh.cell_pipe.len() != mesh.cells.len() {
        return Err(CurvingError::BadLayers(
            "every cell needs its pipe (cell_pipe)".into(),
        ));
    }
    Ok(())
}

/// Whether each node is on a far-field boundary facet (the outer front).
fn outer_nodes(mesh: &Mesh) -> Vec<bool> {
    let mut out = vec![false; mesh.nodes.len()];
    for (f, facet) in mesh.boundary.iter().enumerate() {
        let patch = mesh.boundary_patch.get(f).copied().unwrap_or(NONE);
        let role = mesh.patches.get(patch as usize).map(|p| p.role);
        if role == Some(Role::Farfield) {
            for &n in facet.corners() {
                out[n as usize] = true;
            }
        }
    }
    out
}

/// The P2 mesh: linear nodes, edge nodes, quadrilateral face nodes, hexahedron centres.
fn assemble(mesh: &Mesh, edges: &Edges, faces: &Faces, m: &crate::march3d::March<'_>) -> Mesh {
    let n0 = mesh.nodes.len() as u32;
    // the linear mesh's nodes, patches, layers and pipes; new cells and facets
    let mut out = Mesh {
        order: 2,
        cells: Cells::new(),
        boundary: Cells::new(),
        ..mesh.clone()
    };
    out.nodes
        .extend((0..edges.len() as u32).map(|e| m.edge_node(e)));
    // quadrilateral faces of cells with face nodes get one node each, in face order
    let mut face_node = vec![NONE; faces.len()];
    for f in 0..faces.len() as u32 {
        if faces.nodes(f).len() == 4 {
            // the corners in cyclic order, from the first cell on the face
            let u = faces.cells(f)[0];
            let cell = mesh.cells.get(u.cell as usize);
            let corners: Vec<u32> = cell.ty.shape.faces()[u.local as usize]
                .iter()
                .map(|&j| cell.nodes[j])
                .collect();
            face_node[f as usize] = out.nodes.len() as u32;
            out.nodes.push(m.face_node(&corners));
        }
    }
    let mut buf = Vec::new();
    for (c, cell) in mesh.cells.iter().enumerate() {
        let shape = cell.ty.shape;
        buf.clear();
        buf.extend_from_slice(cell.corners());
        buf.extend(edges.of_cell(c).iter().map(|&e| n0 + e));
        if shape != Shape::Tet {
            for (j, &f) in faces.of_cell(c).iter().enumerate() {
                if shape.faces()[j].len() == 4 {
                    buf.push(face_node[f as usize]);
                }
            }
        }
        if shape == Shape::Hex {
            buf.push(out.nodes.len() as u32);
            out.nodes.push(m.hex_centre(c));
        }
        out.cells.push(CellType::new(shape, 2), &buf);
    }
    for facet in mesh.boundary.iter() {
        let k = facet.corners();
        buf.clear();
        buf.extend_from_slice(k);
        for i in 0..k.len() {
            let e = edges.find(&[k[i], k[(i + 1) % k.len()]]);
            buf.push(n0 + e.expect("a boundary facet's edges are cell edges"));
        }
        if k.len() == 4 {
            let f = faces.find(k).expect("a boundary facet is a cell face");
            buf.push(face_node[f as usize]);
        }
        out.boundary.push(CellType::new(facet.ty.shape, 2), &buf);
    }
    out
}
