//! The volume fill of a 3D case with a far field (`[farfield]`): the space between the layers'
//! final front and the far field's triangles meshed with tetrahedra (`tet-fill`), then put into
//! the mesh — the front's facets become inner faces, the far field's the `farfield` group.
//!
//! The fill conforms to triangles only, so each quadrilateral of the front (the top of a kept
//! prism or hexahedron) is first capped by a pyramid whose apex stands over its centre, and the
//! pyramid's four sides join the fill's front. At orders 2 and 3 the fill's cells are straight
//! and take the curved mesh's own nodes on the front's edges and faces, so the mesh conforms
//! at every order; their other high-order nodes are new, where the straight cell puts them.

use std::collections::HashMap;

use geom_surface::Surface;
use mesh_model::{CellType, Mesh, NONE, Role, Shape};

use crate::case3d::Case3d;
use crate::error::{Result, bail, input_error};

/// What the fill added to the linear mesh: new points (numbered after the mesh's nodes),
/// cells (pyramid caps, then tetrahedra) and the far field's facets, and its figures.
#[derive(Debug, Clone)]
pub struct Filled {
    /// The linear mesh's node count: the new points are numbered from it.
    pub first_point: usize,
    /// The new points: the pyramids' apexes, the far field's nodes, then the fill's own.
    pub points: Vec<[f64; 3]>,
    /// The new linear cells, each a shape and its corners.
    pub cells: Vec<(Shape, Vec<u32>)>,
    /// The far field's triangles, facing out of the domain (as boundary facets do).
    pub far_facets: Vec<[u32; 3]>,
    /// Wall facets on which no cell stood (columns stopped at the wall): the fill's cells now
    /// stand on them, so they join the mesh's boundary, each with its patch, facing out of the
    /// domain.
    pub wall_facets: Vec<(Vec<u32>, u32)>,
    /// The figures of the fill, for the report.
    pub stats: FillStats,
}

/// The report's `fill` section.
#[derive(Debug, Clone, Copy, Default, serde::Serialize)]
pub struct FillStats {
    /// Tetrahedra made by the fill.
    pub tets: usize,
    /// Pyramids capping the front's quadrilaterals.
    pub pyramids: usize,
    /// Points added off the front to recover its facets.
    pub steiner_points: usize,
    /// Points added by the refinement towards the size field.
    pub refinement_points: usize,
    /// The largest dihedral angle of the fill's tetrahedra, degrees.
    pub max_dihedral_deg: f64,
    /// Triangles of the far field.
    pub farfield_facets: usize,
    /// Front edges capped (two tetrahedra from an apex over their two triangles) because the
    /// fill could not recover them.
    pub caps: usize,
}

/// The fill's front, as it is collected from the mesh's far-field-role facets.
struct Front {
    /// Triangles facing into the fill, over mesh node indices and new points.
    tris: Vec<[u32; 3]>,
    /// The pyramid caps (base quad, then apex).
    pyramids: Vec<[u32; 5]>,
    /// The caps of front edges the fill could not recover (two tetrahedra each, corners
    /// as in the mesh's orientation, [`cap_edge`]).
    caps: Vec<[u32; 4]>,
    /// The apexes' coordinates, numbered from the mesh's node count.
    apexes: Vec<[f64; 3]>,
}

/// Fills the space between the linear layer mesh `mesh`'s final front (its far-field-role
/// boundary facets, and the facets of the wall surface `wall` on which no cell stands) and the
/// far field `far` (triangles facing into the domain).
pub fn fill(
    mesh: &Mesh,
    wall: &Surface,
    far: &Surface,
    options: &tet_fill::FillOptions,
) -> Result<Filled> {
    let bare = bare_wall_facets(mesh, wall);
    let bare_nodes: Vec<Vec<u32>> = bare
        .iter()
        .map(|&f| wall.facets[f].nodes().to_vec())
        .collect();
    let mut front = front(mesh, &bare_nodes)?;
    for round in 0..=MAX_CAPS {
        match fill_once(mesh, &front, far, options)? {
            Attempt::Done(mut filled) => {
                filled.wall_facets = bare
                    .iter()
                    .map(|&f| {
                        let k: Vec<u32> = wall.facets[f].nodes().iter().rev().copied().collect();
                        (k, wall.facet_patch[f])
                    })
                    .collect();
                filled.stats.caps = front.caps.len() / 2;
                return Ok(filled);
            }
            Attempt::Edge(edges, e) if round < MAX_CAPS => {
                // the first edge capped, or the run stops; the others where they still can be
                let [first, rest @ ..] = edges.as_slice() else {
                    bail!("the volume fill: {e}");
                };
                cap_edge(mesh, &mut front, *first)
                    .map_err(|why| input_error!("the volume fill: {e} (and capping it: {why})"))?;
                for &edge in rest {
                    let _ = cap_edge(mesh, &mut front, edge);
                }
            }
            Attempt::Edge(_, e) => bail!("the volume fill: {e} (after {MAX_CAPS} caps)"),
        }
    }
    unreachable!("the loop returns")
}

/// The most rounds of capping [`fill`] tries to get round edges `tet-fill` cannot recover.
pub const MAX_CAPS: usize = 16;

/// What one try of the fill gave: the fill, or the front edges it could not recover (mesh
/// numbering; the one it gave up on first) with its error.
enum Attempt {
    Done(Filled),
    Edge(Vec<[u32; 2]>, tet_fill::FillError),
}

/// One try of the fill over `front` (see [`fill`]).
fn fill_once(
    mesh: &Mesh,
    front: &Front,
    far: &Surface,
    options: &tet_fill::FillOptions,
) -> Result<Attempt> {
    let n0 = mesh.nodes.len();
    // the fill's input: the front's nodes, the apexes, the far field's nodes
    let mut index: HashMap<u32, u32> = HashMap::new();
    let mut global: Vec<u32> = Vec::new();
    let mut points: Vec<[f64; 3]> = Vec::new();
    let far_first = n0 + front.apexes.len();
    let node_at = |v: u32| match v as usize {
        v if v < n0 => mesh.nodes[v],
        v if v < far_first => front.apexes[v - n0],
        v => far.nodes[v - far_first],
    };
    let mut local = |v: u32, points: &mut Vec<[f64; 3]>| {
        *index.entry(v).or_insert_with(|| {
            global.push(v);
            points.push(node_at(v));
            (points.len() - 1) as u32
        })
    };
    let mut facets: Vec<[u32; 3]> = front
        .tris
        .iter()
        .map(|t| t.map(|v| local(v, &mut points)))
        .collect();
    for f in &far.facets {
        let k = f.nodes();
        if k.len() != 3 {
            bail!(
                "the far field has a facet of {} nodes (triangles only)",
                k.len()
            );
        }
        facets.push([0, 1, 2].map(|i| local((far_first as u32) + k[i], &mut points)));
    }
    let input = tet_fill::FillInput {
        points: &points,
        facets: &facets,
    };
    let filled = match tet_fill::fill(&input, options) {
        Ok(f) => f,
        // an edge of the front (not of the far field) it could not recover: cap it and retry
        Err(
            e @ tet_fill::FillError::Unrecoverable {
                edge: Some([a, b]), ..
            },
        ) if [a, b]
            .iter()
            .all(|&v| (global[v as usize] as usize) < far_first) =>
        {
            let on_front = |[u, v]: [u32; 2]| {
                let (u, v) = (global[u as usize], global[v as usize]);
                ((u as usize) < far_first && (v as usize) < far_first).then_some([u, v])
            };
            let mut edges = vec![[global[a as usize], global[b as usize]]];
            if let tet_fill::FillError::Unrecoverable { missing_edges, .. } = &e {
                edges.extend(missing_edges.iter().filter_map(|&m| on_front(m)));
            }
            return Ok(Attempt::Edge(edges, e));
        }
        Err(e) => bail!("the volume fill: {e}"),
    };
    // back to mesh numbering: the input points by `global`, the fill's own after the far field
    let fill_first = far_first + far.nodes.len();
    let to_mesh = |v: u32| -> u32 {
        match global.get(v as usize) {
            Some(&g) => g,
            None => (fill_first + v as usize - points.len()) as u32,
        }
    };
    let mut new_points = front.apexes.clone();
    new_points.extend_from_slice(&far.nodes);
    new_points.extend_from_slice(&filled.points[points.len()..]);
    let mut cells: Vec<(Shape, Vec<u32>)> = front
        .pyramids
        .iter()
        .map(|p| (Shape::Pyramid, p.to_vec()))
        .chain(front.caps.iter().map(|t| (Shape::Tet, t.to_vec())))
        .collect();
    for t in &filled.tets {
        let k = t.map(to_mesh);
        cells.push((
            Shape::Tet,
            positive_tet(k, |v| node_of(mesh, &new_points, n0, v)),
        ));
    }
    // the far field faces the domain; a boundary facet faces out of it
    let far_facets = far
        .facets
        .iter()
        .map(|f| {
            let k = f.nodes();
            let g = |i: usize| (far_first as u32) + k[i];
            [g(0), g(2), g(1)]
        })
        .collect();
    let stats = FillStats {
        tets: filled.tets.len(),
        pyramids: front.pyramids.len(),
        steiner_points: filled.steiner_points,
        refinement_points: filled.refinement_points,
        max_dihedral_deg: filled.max_dihedral_deg,
        farfield_facets: far.facets.len(),
        caps: 0,
    };
    Ok(Attempt::Done(Filled {
        first_point: n0,
        points: new_points,
        cells,
        far_facets,
        wall_facets: Vec::new(),
        stats,
    }))
}

/// Caps the two front triangles on `edge` (which `tet-fill` could not recover: the diagonal
/// of a flat quadrilateral the Delaunay tetrahedralisation splits the other way) with a
/// tetrahedron each from one new apex over them, so the edge leaves the front; the cap's four
/// outer sides join the front in their place. Err: why it cannot.
fn cap_edge(mesh: &Mesh, front: &mut Front, [a, b]: [u32; 2]) -> std::result::Result<(), String> {
    let n0 = mesh.nodes.len();
    let on = |t: &[u32; 3]| t.contains(&a) && t.contains(&b);
    let pair: Vec<usize> = (0..front.tris.len())
        .filter(|&i| on(&front.tris[i]))
        .collect();
    let [i, j] = pair[..] else {
        return Err(format!(
            "edge {a}-{b} is on {} front triangles, not 2",
            pair.len()
        ));
    };
    let x = |v: u32| {
        if (v as usize) < n0 {
            mesh.nodes[v as usize]
        } else {
            front.apexes[v as usize - n0]
        }
    };
    let (t1, t2) = (front.tris[i], front.tris[j]);
    let corners: Vec<u32> = {
        let mut c: Vec<u32> = t1.iter().chain(&t2).copied().collect();
        c.sort_unstable();
        c.dedup();
        c
    };
    let centre: [f64; 3] = std::array::from_fn(|d| {
        corners.iter().map(|&v| x(v)[d]).sum::<f64>() / corners.len() as f64
    });
    let normal = |t: [u32; 3]| {
        geom_predicates::vector::cross3(
            geom_predicates::vector::sub(x(t[1]), x(t[0])),
            geom_predicates::vector::sub(x(t[2]), x(t[0])),
        )
    };
    let (n1, n2) = (normal(t1), normal(t2));
    let n = geom_surface::unit(std::array::from_fn(|d| {
        geom_surface::unit(n1)[d] + geom_surface::unit(n2)[d]
    }));
    let side = [t1, t2]
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .map(|(u, v)| geom_predicates::vector::dist(x(u), x(v)))
        .sum::<f64>()
        / 6.0;
    // the apex strictly on the fill's side of both triangles, its cap clear of the rest of the
    // front (lower, down to 0.4 / 32 of the side, where a front is near)
    let sees = |apex: [f64; 3]| {
        [t1, t2]
            .iter()
            .all(|t| geom_predicates::orient3d(x(t[0]), x(t[1]), x(t[2]), apex) < 0.0)
    };
    let apex = (0..6)
        .map(|k| {
            let h = 0.4 * side / f64::from(1u32 << k);
            std::array::from_fn(|d| centre[d] + h * n[d])
        })
        .find(|&apex| sees(apex) && cap_clear(front, &x, [i, j], &corners, apex))
        .ok_or_else(|| {
            format!("edge {a}-{b}: no apex over its two triangles clear of the front")
        })?;
    let p = (n0 + front.apexes.len()) as u32;
    front.apexes.push(apex);
    let shared = |u: u32, v: u32| (u == a && v == b) || (u == b && v == a);
    let mut sides = Vec::new();
    for t in [t1, t2] {
        front.caps.push([t[0], t[1], t[2], p]);
        for k in 0..3 {
            let (u, v) = (t[k], t[(k + 1) % 3]);
            if !shared(u, v) {
                sides.push([u, v, p]);
            }
        }
    }
    for k in [i.max(j), i.min(j)] {
        front.tris.swap_remove(k);
    }
    front.tris.extend(sides);
    Ok(())
}

/// Node `v`'s coordinates: a mesh node, or a new point numbered from `n0`.
fn node_of(mesh: &Mesh, new: &[[f64; 3]], n0: usize, v: u32) -> [f64; 3] {
    match mesh.nodes.get(v as usize) {
        Some(&p) if (v as usize) < n0 => p,
        _ => new[v as usize - n0],
    }
}

/// The tetrahedron `k` in the mesh's orientation (Gmsh's: `orient3d` negative), two corners
/// swapped where it is the other way.
fn positive_tet(k: [u32; 4], x: impl Fn(u32) -> [f64; 3]) -> Vec<u32> {
    let [a, b, c, d] = k.map(&x);
    if geom_predicates::orient3d(a, b, c, d) > 0.0 {
        vec![k[0], k[2], k[1], k[3]]
    } else {
        k.to_vec()
    }
}

/// The mesh's final front as the fill takes it: its triangles, and its quadrilaterals each
/// capped by a pyramid (apex over the centre at 0.6 × the mean side, along the quad's normal)
/// whose four sides join the front.
fn front(mesh: &Mesh, bare: &[Vec<u32>]) -> Result<Front> {
    let n0 = mesh.nodes.len() as u32;
    let mut out = Front {
        tris: Vec::new(),
        pyramids: Vec::new(),
        caps: Vec::new(),
        apexes: Vec::new(),
    };
    // the front's nodes, for the apexes' clearance
    // the last front's facets and the bare wall's, all facing into the fill
    let facets: Vec<Vec<u32>> = mesh
        .boundary
        .iter()
        .enumerate()
        .filter(|&(f, _)| mesh.patches[mesh.boundary_patch[f] as usize].role == Role::Farfield)
        .map(|(_, facet)| facet.corners().to_vec())
        .chain(bare.iter().cloned())
        .collect();
    let mut on_front: Vec<u32> = facets.iter().flatten().copied().collect();
    on_front.sort_unstable();
    on_front.dedup();
    let at: Vec<[f64; 3]> = on_front.iter().map(|&v| mesh.nodes[v as usize]).collect();
    let tree = geom_predicates::PointTree::new(&at);
    for k in &facets {
        match k.len() {
            3 => out.tris.push([k[0], k[1], k[2]]),
            4 => {
                let x: [[f64; 3]; 4] = std::array::from_fn(|i| mesh.nodes[k[i] as usize]);
                let apex = apex_over(&x, |p, r| {
                    tree.within(p, r)
                        .iter()
                        .any(|&(i, _)| !k.contains(&on_front[i]))
                });
                let a = n0 + out.apexes.len() as u32;
                out.apexes.push(apex);
                out.pyramids.push([k[0], k[1], k[2], k[3], a]);
                for i in 0..4 {
                    out.tris.push([k[i], k[(i + 1) % 4], a]);
                }
            }
            n => bail!("the final front has a facet of {n} corners"),
        }
    }
    Ok(out)
}

/// The facets of the wall surface `wall` (whose nodes are `mesh`'s first) on which no cell of
/// `mesh` stands: where the columns of all its nodes stopped at the wall, the cut mesh has no
/// wall facet there, and the wall itself bounds the space the fill meshes. Found as the wall
/// facets none of whose mesh wall facets (itself, or the two triangles a quad was cut into)
/// exists. Each as its index in `wall`.
fn bare_wall_facets(mesh: &Mesh, wall: &Surface) -> Vec<usize> {
    let mut at: Vec<Vec<u32>> = vec![Vec::new(); wall.nodes.len()];
    for (f, facet) in mesh.boundary.iter().enumerate() {
        if mesh.patches[mesh.boundary_patch[f] as usize].role == Role::Wall {
            for &v in facet.corners() {
                if let Some(list) = at.get_mut(v as usize) {
                    list.push(f as u32);
                }
            }
        }
    }
    (0..wall.facets.len())
        .filter(|&s| {
            let nodes = wall.facets[s].nodes();
            !at[nodes[0] as usize].iter().any(|&f| {
                let k = mesh.boundary.get(f as usize).corners();
                k.iter().all(|v| nodes.contains(v))
            })
        })
        .collect()
}

/// The apex of the pyramid capping the quad `x` (facing out of the layers): over its centre,
/// along its normal, 0.6 × its mean side high (a pyramid of equal edges is 0.71 × high), or
/// lower, halved (down to a twentieth of the side) while `crowded(apex, r)` finds another
/// front's node within twice its height `r` of it — across a narrow gap the caps of two
/// facing quads keep apart.
fn apex_over(x: &[[f64; 3]; 4], crowded: impl Fn([f64; 3], f64) -> bool) -> [f64; 3] {
    let c: [f64; 3] = std::array::from_fn(|d| x.iter().map(|p| p[d]).sum::<f64>() / 4.0);
    let n = geom_surface::unit(geom_predicates::vector::cross3(
        geom_predicates::vector::sub(x[2], x[0]),
        geom_predicates::vector::sub(x[3], x[1]),
    ));
    let side = (0..4)
        .map(|i| geom_predicates::vector::dist(x[i], x[(i + 1) % 4]))
        .sum::<f64>()
        / 4.0;
    let mut h = 0.6 * side;
    let at = |h: f64| std::array::from_fn(|d| c[d] + h * n[d]);
    while h > 0.05 * side && crowded(at(h), 2.0 * h) {
        h *= 0.5;
    }
    at(h)
}

/// Puts the fill into the linear `mesh` it was made from: the new points and cells (layer and
/// pipe [`NONE`]), the front's facets dropped from the boundary, the far field's in the mesh's
/// `farfield` patch.
pub fn apply_linear(mesh: &mut Mesh, filled: &Filled) {
    mesh.nodes.extend_from_slice(&filled.points);
    for (shape, k) in &filled.cells {
        mesh.cells.push(CellType::new(*shape, 1), k);
        mesh.cell_layer.push(NONE);
        mesh.cell_pipe.push(NONE);
    }
    let far = replace_front(mesh);
    for t in &filled.far_facets {
        mesh.boundary.push(CellType::new(Shape::Tri, 1), t);
        mesh.boundary_patch.push(far);
    }
    for (k, patch) in &filled.wall_facets {
        mesh.boundary.push(CellType::new(facet_shape(k), 1), k);
        mesh.boundary_patch.push(*patch);
    }
}

/// A facet's shape by its corner count.
fn facet_shape(k: &[u32]) -> Shape {
    if k.len() == 4 {
        Shape::Quad
    } else {
        Shape::Tri
    }
}

/// Drops the far-field-role facets (the final front) from `mesh`'s boundary; the index of the
/// patch they were in (`outer`), renamed `farfield`, which the far field's facets join.
fn replace_front(mesh: &mut Mesh) -> u32 {
    let far = mesh
        .patches
        .iter()
        .position(|p| p.role == Role::Farfield)
        .unwrap_or(mesh.patches.len()) as u32;
    if far as usize == mesh.patches.len() {
        mesh.patches.push(mesh_model::Patch {
            name: String::new(),
            role: Role::Farfield,
        });
    }
    mesh.patches[far as usize].name = Role::Farfield.name().into();
    let patches = &mesh.patches;
    let drop: Vec<usize> = (0..mesh.boundary.len())
        .filter(|&f| patches[mesh.boundary_patch[f] as usize].role == Role::Farfield)
        .collect();
    mesh.boundary.remove_sorted(&drop);
    mesh_model::cells::remove_sorted(&mut mesh.boundary_patch, &drop);
    far
}

/// Puts the fill into the curved mesh (order 2 or 3) made from the linear mesh it was made
/// from (whose nodes are its first): each new cell and far-field facet straight, at the curved
/// mesh's order, its high-order nodes on the front the curved mesh's own (found by their
/// weights on the front facets' corners), the others new.
pub fn apply_curved(curved: &mut Mesh, filled: &Filled) -> Result<Mended> {
    let order = curved.order;
    let shift = curved.nodes.len() - filled.first_point;
    let renum = |v: u32| -> u32 {
        if (v as usize) < filled.first_point {
            v
        } else {
            v + shift as u32
        }
    };
    curved.nodes.extend_from_slice(&filled.points);
    let free_from = curved.nodes.len();
    // the front's high-order nodes by their weights on its corners
    let mut nodes: HashMap<Vec<(u32, i64)>, u32> = HashMap::new();
    // (every boundary facet's: a bare wall facet's edges are its neighbours')
    for facet in curved.boundary.iter() {
        let refs = reference(facet.ty)?;
        let k = facet.corners();
        for (r, &v) in refs.iter().zip(facet.nodes) {
            nodes.insert(key(&weights(facet.ty.shape, *r), k), v);
        }
    }
    let far = replace_front(curved);
    let mut buf = Vec::new();
    let mut lift = |shape: Shape, corners: &[u32], curved: &mut Mesh| -> Result<Vec<u32>> {
        let ty = CellType::new(shape, order);
        let k: Vec<u32> = corners.iter().map(|&v| renum(v)).collect();
        buf.clear();
        for r in reference(ty)? {
            let w = weights(shape, r);
            let id = key(&w, &k);
            let v = *nodes.entry(id).or_insert_with(|| {
                let x = place(&w, &k, &curved.nodes);
                curved.nodes.push(x);
                (curved.nodes.len() - 1) as u32
            });
            buf.push(v);
        }
        Ok(buf.clone())
    };
    for (shape, k) in &filled.cells {
        let all = lift(*shape, k, curved)?;
        curved.cells.push(CellType::new(*shape, order), &all);
        curved.cell_layer.push(NONE);
        curved.cell_pipe.push(NONE);
    }
    for t in &filled.far_facets {
        let all = lift(Shape::Tri, t, curved)?;
        curved.boundary.push(CellType::new(Shape::Tri, order), &all);
        curved.boundary_patch.push(far);
    }
    for (k, patch) in &filled.wall_facets {
        let shape = facet_shape(k);
        let all = lift(shape, k, curved)?;
        curved.boundary.push(CellType::new(shape, order), &all);
        curved.boundary_patch.push(*patch);
    }
    let first_fill = curved.cells.len() - filled.cells.len();
    // the far field's and the bare wall's new facets keep their straight high-order nodes
    let first_new = curved.boundary.len() - filled.far_facets.len() - filled.wall_facets.len();
    let fixed: std::collections::HashSet<u32> = (first_new..curved.boundary.len())
        .flat_map(|f| curved.boundary.get(f).nodes.to_vec())
        .collect();
    extend_curving(curved, first_fill, |v| {
        v as usize >= free_from && !fixed.contains(&v)
    });
    Ok(mend(curved, first_fill))
}

/// Rounds of averaging that carry the front's curving into the fill.
const EXTEND_ROUNDS: usize = 30;

/// The fill's cells curved as the front beside them: each of their high-order nodes that is
/// `free` (made for the fill, not on the far field) takes the mean displacement (node minus
/// its place on the straight cell) of the high-order nodes it shares a cell with, over
/// [`EXTEND_ROUNDS`] rounds, starting straight; the front's nodes keep their curving and the
/// far field's stay straight. So a thin fill cell on a curved front edge bends with it instead
/// of folding; the certification judges the result.
fn extend_curving(m: &mut Mesh, first_fill: usize, free: impl Fn(u32) -> bool) {
    let mut straight: HashMap<u32, [f64; 3]> = HashMap::new();
    let mut cells: Vec<Vec<u32>> = Vec::new();
    for c in first_fill..m.cells.len() {
        let cell = m.cells.get(c);
        let Ok(refs) = reference(cell.ty) else {
            continue;
        };
        let k = cell.corners();
        let high: Vec<u32> = cell.nodes[k.len()..].to_vec();
        for (r, &v) in refs.iter().zip(cell.nodes).skip(k.len()) {
            straight
                .entry(v)
                .or_insert_with(|| place(&weights(cell.ty.shape, *r), k, &m.nodes));
        }
        cells.push(high);
    }
    let disp = |m: &Mesh, v: u32| -> [f64; 3] {
        let (x, s) = (m.nodes[v as usize], straight[&v]);
        std::array::from_fn(|d| x[d] - s[d])
    };
    let mut delta: HashMap<u32, [f64; 3]> = straight
        .keys()
        .map(|&v| (v, if free(v) { [0.0; 3] } else { disp(m, v) }))
        .collect();
    if delta.values().all(|d| *d == [0.0; 3]) {
        return;
    }
    for _ in 0..EXTEND_ROUNDS {
        let mut sum: HashMap<u32, ([f64; 3], usize)> = HashMap::new();
        for high in &cells {
            for &v in high.iter().filter(|&&v| free(v)) {
                let e = sum.entry(v).or_insert(([0.0; 3], 0));
                for &u in high.iter().filter(|&&u| u != v) {
                    let du = delta[&u];
                    (0..3).for_each(|d| e.0[d] += du[d]);
                    e.1 += 1;
                }
            }
        }
        for (v, (s, n)) in sum {
            delta.insert(v, s.map(|x| x / n.max(1) as f64));
        }
    }
    for (&v, d) in &delta {
        if free(v) {
            let s = straight[&v];
            m.nodes[v as usize] = std::array::from_fn(|k| s[k] + d[k]);
        }
    }
}

/// How many front edges and faces [`mend`] straightened, in part or whole.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct Mended {
    /// Fill cells the certified check found invalid on the curved front.
    pub invalid_fill_cells: usize,
    /// Curved front edges and faces whose displacement was scaled down (to ½, ¼ or 0).
    pub straightened: usize,
    /// Fill cells still invalid after it (the mesh's certification reports them).
    pub still_invalid: usize,
}

/// The fill's straight cells on a curved front are invalid where a thin one sits on an edge
/// curved more than its height (a column stopped low, its wall or first layers curved): for
/// each such cell (from `first_fill` on), the displacement of each of its curved edges and
/// faces (curved minus straight node) is scaled to ½, ¼, then 0 — the first that leaves every
/// cell holding those nodes certified valid is kept (the curving's own rule for the layers).
fn mend(curved: &mut Mesh, first_fill: usize) -> Mended {
    let params = jacobian_check::CertifyParams::default();
    let valid = |m: &Mesh, c: usize| {
        let cell = m.cells.get(c);
        let x: Vec<[f64; 3]> = cell.nodes.iter().map(|&v| m.nodes[v as usize]).collect();
        jacobian_check::certify_cell(cell.ty, &x, &params).is_ok_and(|c| c.is_valid())
    };
    let bad: Vec<usize> = (first_fill..curved.cells.len())
        .filter(|&c| !valid(curved, c))
        .collect();
    let mut out = Mended {
        invalid_fill_cells: bad.len(),
        ..Mended::default()
    };
    if bad.is_empty() {
        return out;
    }
    // the cells around each node of the bad cells
    let mut around: HashMap<u32, Vec<usize>> = HashMap::new();
    for &c in &bad {
        for &v in curved.cells.get(c).nodes {
            around.entry(v).or_default();
        }
    }
    for c in 0..curved.cells.len() {
        for &v in curved.cells.get(c).nodes {
            if let Some(list) = around.get_mut(&v) {
                list.push(c);
            }
        }
    }
    for &c in &bad {
        for (nodes, straight) in curved_entities(curved, c) {
            if valid(curved, c) {
                break;
            }
            let cells: Vec<usize> = nodes.iter().flat_map(|v| around[v].clone()).collect();
            let was: Vec<[f64; 3]> = nodes.iter().map(|&v| curved.nodes[v as usize]).collect();
            for scale in [0.5, 0.25, 0.0] {
                for (k, &v) in nodes.iter().enumerate() {
                    curved.nodes[v as usize] = std::array::from_fn(|d| {
                        straight[k][d] + scale * (was[k][d] - straight[k][d])
                    });
                }
                if cells.iter().all(|&o| valid(curved, o)) {
                    out.straightened += 1;
                    break;
                }
                if scale == 0.0 {
                    // no scale mends it: back as it was
                    for (k, &v) in nodes.iter().enumerate() {
                        curved.nodes[v as usize] = was[k];
                    }
                }
            }
        }
        if !valid(curved, c) {
            out.still_invalid += 1;
        }
    }
    out
}

/// Cell `c`'s curved high-order nodes, grouped by the edge or face they lie on (nodes with the
/// same corners), each with the straight places of its nodes.
fn curved_entities(m: &Mesh, c: usize) -> Vec<(Vec<u32>, Vec<[f64; 3]>)> {
    let cell = m.cells.get(c);
    let Ok(refs) = reference(cell.ty) else {
        return Vec::new();
    };
    let k = cell.corners();
    // (the corners a group lies on, its nodes, their straight places)
    type Group = (Vec<u32>, Vec<u32>, Vec<[f64; 3]>);
    let mut groups: Vec<Group> = Vec::new();
    for (r, &v) in refs.iter().zip(cell.nodes).skip(k.len()) {
        let w = weights(cell.ty.shape, *r);
        let straight = place(&w, k, &m.nodes);
        if geom_predicates::vector::dist(straight, m.nodes[v as usize]) == 0.0 {
            continue;
        }
        let mut on: Vec<u32> = w.iter().map(|&(i, _)| k[i]).collect();
        on.sort_unstable();
        match groups.iter_mut().find(|g| g.0 == on) {
            Some(g) => {
                g.1.push(v);
                g.2.push(straight);
            }
            None => groups.push((on, vec![v], vec![straight])),
        }
    }
    // edges before faces: an edge's change may mend the cell alone
    groups.sort_by_key(|g| g.0.len());
    groups.into_iter().map(|(_, v, x)| (v, x)).collect()
}

/// The reference coordinates of `ty`'s nodes.
fn reference(ty: CellType) -> Result<Vec<[f64; 3]>> {
    mesh_model::reference::reference_nodes(ty)
        .ok_or_else(|| input_error!("the volume fill: no reference nodes for {ty:?}"))
}

/// Whether the cap from `apex` over front triangles `pair` (corners `corners`, coordinates by
/// `x`) is clear of the rest of the front: no segment from the apex to a corner meets a front
/// triangle without that corner, and no front edge away from the cap's base meets one of the
/// cap's sides (two triangles meet exactly when an edge of one meets the other; pairs sharing
/// a corner are left to `tet-fill`'s own check).
fn cap_clear(
    front: &Front,
    x: &impl Fn(u32) -> [f64; 3],
    pair: [usize; 2],
    corners: &[u32],
    apex: [f64; 3],
) -> bool {
    use geom_predicates::segment_meets_triangle as meets;
    let mut lo = apex;
    let mut hi = apex;
    for &v in corners {
        let p = x(v);
        for d in 0..3 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    let sides: Vec<[u32; 2]> = pair
        .iter()
        .flat_map(|&k| {
            let t = front.tris[k];
            (0..3).map(move |i| [t[i], t[(i + 1) % 3]])
        })
        .collect();
    front.tris.iter().enumerate().all(|(k, t)| {
        if pair.contains(&k) {
            return true;
        }
        let p = t.map(x);
        let outside =
            (0..3).any(|d| p.iter().all(|q| q[d] < lo[d]) || p.iter().all(|q| q[d] > hi[d]));
        if outside {
            return true;
        }
        let spokes_clear = corners
            .iter()
            .filter(|v| !t.contains(v))
            .all(|&v| !meets(apex, x(v), p[0], p[1], p[2]));
        let edges_clear = (0..3).all(|i| {
            let (u, w) = (t[i], t[(i + 1) % 3]);
            sides
                .iter()
                .filter(|s| !s.contains(&u) && !s.contains(&w))
                .all(|s| !meets(x(u), x(w), x(s[0]), x(s[1]), apex))
        });
        spokes_clear && edges_clear
    })
}

/// The weights of a straight cell's corners at reference point `r` (Gmsh's reference cells):
/// barycentric on triangles and tetrahedra, bilinear on quadrilaterals, and on the pyramid the
/// base's bilinear weights shrunk towards the apex. Zero weights left out.
fn weights(shape: Shape, r: [f64; 3]) -> Vec<(usize, f64)> {
    let [x, y, z] = r;
    let bilinear = |x: f64, y: f64| {
        [
            (1.0 - x) * (1.0 - y) / 4.0,
            (1.0 + x) * (1.0 - y) / 4.0,
            (1.0 + x) * (1.0 + y) / 4.0,
            (1.0 - x) * (1.0 + y) / 4.0,
        ]
    };
    let w: Vec<f64> = match shape {
        Shape::Tri => vec![1.0 - x - y, x, y],
        Shape::Tet => vec![1.0 - x - y - z, x, y, z],
        Shape::Quad => bilinear(x, y).to_vec(),
        Shape::Pyramid if z >= 1.0 => vec![0.0, 0.0, 0.0, 0.0, 1.0],
        Shape::Pyramid => {
            let s = 1.0 - z;
            let mut w: Vec<f64> = bilinear(x / s, y / s).iter().map(|b| b * s).collect();
            w.push(z);
            w
        }
        _ => Vec::new(),
    };
    w.into_iter()
        .enumerate()
        .filter(|&(_, wi)| wi.abs() > 1e-12)
        .collect()
}

/// The point of corners `corners` (of `nodes`) with weights `w` ([`weights`]): a high-order
/// node's place on its straight cell.
fn place(w: &[(usize, f64)], corners: &[u32], nodes: &[[f64; 3]]) -> [f64; 3] {
    w.iter().fold([0.0; 3], |acc, &(i, wi)| {
        let p = nodes[corners[i] as usize];
        std::array::from_fn(|d| acc[d] + wi * p[d])
    })
}

/// A node's key: its corners' global numbers with their weights (to 1e-9), sorted.
fn key(w: &[(usize, f64)], corners: &[u32]) -> Vec<(u32, i64)> {
    let mut k: Vec<(u32, i64)> = w
        .iter()
        .map(|&(i, wi)| (corners[i], (wi * 1e9).round() as i64))
        .collect();
    k.sort_unstable();
    k
}

/// Growth stops before a layer higher than this × the front's mean edge where a fill follows:
/// the layers end about isotropic, the fill's first tetrahedra as tall as they are wide.
pub const STOP_ASPECT: f64 = 1.0;

/// The far field of `case` (`[farfield]` `f`) triangulated, and the thickness the layers must
/// stay under: half the least depth of a wall node inside it. A body not strictly inside it
/// is refused, naming the body's first node outside.
pub fn farfield_for(
    case: &Case3d,
    f: &crate::case3d::Farfield,
    wall: &Surface,
) -> Result<(Surface, f64)> {
    let mut least = f64::INFINITY;
    for (i, &p) in wall.nodes.iter().enumerate() {
        let depth = f.shape.depth(p);
        if depth <= 0.0 {
            bail!(
                "{}: [farfield]: the wall's node {i} at ({:.4}, {:.4}, {:.4}) is not inside the far field: every body must lie strictly inside it",
                case.origin,
                p[0],
                p[1],
                p[2]
            );
        }
        least = least.min(depth);
    }
    Ok((Surface::farfield(&f.shape, f.max_size), least / 2.0))
}

/// Where a fill follows, a column facing another front nearer than this × its next layer's
/// height stops ([`afsf3d::LayerParams::stop_gap`]): both fronts could still grow a layer, and
/// a gap of a layer's height is left for the fill.
pub const STOP_GAP: f64 = 3.0;

/// Where a fill follows, the gap kept between facing fronts is at least this × the front's
/// spacing there ([`afsf3d::LayerParams::stop_gap_spacing`]): the fill's cells across it stay
/// thicker than the P2 front's bulge.
pub const STOP_GAP_SPACING: f64 = 0.5;

/// `case` with its layers set to stop before the fill: at [`STOP_ASPECT`], facing another
/// front at [`STOP_GAP`], and under `max_thickness`.
pub fn layers_before_fill(case: &Case3d, max_thickness: f64) -> Case3d {
    let mut c = case.clone();
    c.layers.stop_aspect = STOP_ASPECT;
    c.layers.stop_gap = STOP_GAP;
    c.layers.stop_gap_spacing = STOP_GAP_SPACING;
    c.layers.max_thickness = max_thickness;
    c
}

/// The fill's options for `case`: its far field's `max_size`, the crate's defaults otherwise.
pub fn options(case: &Case3d) -> tet_fill::FillOptions {
    tet_fill::FillOptions {
        max_size: case.farfield.map_or(f64::INFINITY, |f| f.max_size),
        ..tet_fill::FillOptions::default()
    }
}
