//! The marching of the 3D curving ([`crate::curve3d`]), the mirror of `march` where the
//! algorithm truly differs: in 2D a layered cell has one bottom and one top edge, in 3D a cell
//! cut from a layer has edges of every kind (bottom, top, diagonals, extrusion edges), so the
//! displacement travels from edge to edge — each edge reads the edge between its ends'
//! parents — and the decisions are taken per edge, layer of nodes by layer of nodes, each
//! certified on the cells below the edge. The stops and the fractions (1, ½, ¼) are the 2D
//! ones.
//!
//! An edge has `order − 1` inner nodes, each with its displacement from its straight place
//! (the edge's slots, listed from its lower-numbered end): one at P2, two at P3, both
//! carried up together. At P3 the faces' interior nodes follow their edges, plus the residual
//! each inherits from the face below it (`march3d::nodes`).

pub(crate) mod nodes;

use jacobian_check::{Certificate, certify_cell};
use mesh_model::topology::Edges;
use mesh_model::{CellType, Mesh, NONE, Shape};

use crate::error::CurvingError;
use crate::params::CurvingParams;
use crate::projector::SurfaceProjector;
use crate::stats::StopCounts;
use nodes::FaceNodes;

/// The layer of every node and its parents (the nodes below it in its columns).
#[derive(Debug, Clone)]
pub(crate) struct Layers {
    pub layer: Vec<u32>,
    parent_start: Vec<u32>,
    parents: Vec<u32>,
}

impl Layers {
    /// From the columns (each a wall node and its children, bottom-up).
    pub(crate) fn new(mesh: &Mesh, columns: &[Vec<u32>]) -> Result<Layers, CurvingError> {
        let n = mesh.nodes.len();
        let mut layer = vec![NONE; n];
        let mut below: Vec<Vec<u32>> = vec![Vec::new(); n];
        for (c, column) in columns.iter().enumerate() {
            for (k, &node) in column.iter().enumerate() {
                let bad = |what: &str| {
                    CurvingError::BadLayers(format!("column {c}, level {k}: node {node} {what}"))
                };
                let slot = layer.get_mut(node as usize).ok_or(bad("does not exist"))?;
                if *slot != NONE && *slot != k as u32 {
                    return Err(bad("is at another level in another column"));
                }
                *slot = k as u32;
                if k > 0 && !below[node as usize].contains(&column[k - 1]) {
                    below[node as usize].push(column[k - 1]);
                }
            }
        }
        if let Some(node) = layer.iter().position(|&l| l == NONE) {
            return Err(CurvingError::BadLayers(format!(
                "node {node} is in no column"
            )));
        }
        let mut parent_start = vec![0u32];
        let mut parents = Vec::new();
        for b in below {
            parents.extend(b);
            parent_start.push(parents.len() as u32);
        }
        Ok(Layers {
            layer,
            parent_start,
            parents,
        })
    }

    pub(crate) fn parents(&self, node: u32) -> &[u32] {
        let i = node as usize;
        &self.parents[self.parent_start[i] as usize..self.parent_start[i + 1] as usize]
    }

    /// Where an end at `node` of an edge at `level` comes from one layer down: its parents
    /// when it is at `level`, else itself.
    pub(crate) fn lower<'s>(&'s self, node: &'s u32, level: u32) -> &'s [u32] {
        if self.layer[*node as usize] == level {
            self.parents(*node)
        } else {
            std::slice::from_ref(node)
        }
    }
}

/// The state of the marching: the displacement of every edge's inner nodes from their
/// straight places, and the figures.
pub(crate) struct March<'a> {
    pub(crate) mesh: &'a Mesh,
    pub(crate) edges: &'a Edges,
    pub(crate) layers: &'a Layers,
    params: &'a CurvingParams,
    /// Inner nodes per edge: the order − 1.
    pub(crate) per: usize,
    /// Per edge slot (edge `e`'s at `e · per ..`, from its lower-numbered end): curved minus
    /// straight inner node.
    pub dev: Vec<[f64; 3]>,
    /// At P3, the faces' interior nodes (`nodes3d`); `None` at P2.
    pub(crate) faces: Option<FaceNodes<'a>>,
    pub stops: StopCounts,
    pub reduced: usize,
    pub deepest: u32,
    scratch: Vec<[f64; 3]>,
}

pub(crate) fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(crate) fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    a.map(|v| s * v)
}

fn mid(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|k| 0.5 * (a[k] + b[k]))
}

/// Displacements of an edge's inner nodes (the first `per` used).
pub(crate) type Slots = [[f64; 3]; 2];

const STRAIGHT: Slots = [[0.0; 3]; 2];

impl<'a> March<'a> {
    /// The marching of `mesh` to `params.order`; `faces` (its face table) is needed at P3.
    pub(crate) fn new(
        mesh: &'a Mesh,
        edges: &'a Edges,
        faces: &'a mesh_model::topology::Faces,
        layers: &'a Layers,
        params: &'a CurvingParams,
    ) -> March<'a> {
        let per = params.order as usize - 1;
        March {
            mesh,
            edges,
            layers,
            params,
            per,
            dev: vec![[0.0; 3]; edges.len() * per],
            faces: (per == 2).then(|| FaceNodes::new(mesh, faces, layers)),
            stops: StopCounts::default(),
            reduced: 0,
            deepest: 0,
            scratch: Vec::new(),
        }
    }

    pub(crate) fn ends(&self, e: u32) -> [u32; 2] {
        let k = self.edges.nodes(e);
        [k[0], k[1]]
    }

    pub(crate) fn x(&self, n: u32) -> [f64; 3] {
        self.mesh.nodes[n as usize]
    }

    /// The slots of edge `e`.
    pub(crate) fn slots(&self, e: u32) -> &[[f64; 3]] {
        let i = e as usize * self.per;
        &self.dev[i..i + self.per]
    }

    /// Whether every inner node of edge `e` is on its chord.
    pub(crate) fn is_straight(&self, e: u32) -> bool {
        self.slots(e).iter().all(|d| *d == [0.0; 3])
    }

    /// Sets the slots of edge `e` (the first `per` of `d`).
    fn set(&mut self, e: u32, d: &Slots) {
        let i = e as usize * self.per;
        self.dev[i..i + self.per].copy_from_slice(&d[..self.per]);
    }

    /// Sets every slot of edge `e` to `d`.
    fn set_all(&mut self, e: u32, d: [f64; 3]) {
        let i = e as usize * self.per;
        self.dev[i..i + self.per].fill(d);
    }

    /// The mid node of edge `e`.
    pub(crate) fn edge_node(&self, e: u32) -> [f64; 3] {
        let [a, b] = self.ends(e);
        add(mid(self.x(a), self.x(b)), self.dev[e as usize])
    }

    /// The centre node of the quadrilateral with corners `k` (in cyclic order): the Coons
    /// patch of its four edges at the centre.
    pub(crate) fn face_node(&self, k: &[u32]) -> [f64; 3] {
        let mut p = [0.0; 3];
        for i in 0..4 {
            let e = self.edges.find(&[k[i], k[(i + 1) % 4]]);
            let m = self.edge_node(e.expect("a face's sides are edges"));
            p = add(p, add(scale(m, 0.5), scale(self.x(k[i]), -0.25)));
        }
        p
    }

    /// The centre node of hexahedron `c`: ½ Σ face nodes − ¼ Σ edge nodes + ⅛ Σ corners.
    pub(crate) fn hex_centre(&self, c: usize) -> [f64; 3] {
        let cell = self.mesh.cells.get(c);
        let k = cell.corners();
        let mut p = [0.0; 3];
        for f in Shape::Hex.faces() {
            let corners: Vec<u32> = f.iter().map(|&j| k[j]).collect();
            p = add(p, scale(self.face_node(&corners), 0.5));
        }
        for &e in self.edges.of_cell(c) {
            p = add(p, scale(self.edge_node(e), -0.25));
        }
        for &n in k {
            p = add(p, scale(self.x(n), 0.125));
        }
        p
    }

    /// The P2 nodes of cell `c` as the edges stand now, in Gmsh order, into `out`.
    fn cell_nodes(&self, c: usize, out: &mut Vec<[f64; 3]>) {
        let cell = self.mesh.cells.get(c);
        let shape = cell.ty.shape;
        let k = cell.corners();
        out.clear();
        out.extend(k.iter().map(|&n| self.x(n)));
        out.extend(self.edges.of_cell(c).iter().map(|&e| self.edge_node(e)));
        for f in shape.faces().iter().filter(|f| f.len() == 4) {
            let corners: Vec<u32> = f.iter().map(|&j| k[j]).collect();
            out.push(self.face_node(&corners));
        }
        if shape == Shape::Hex {
            out.push(self.hex_centre(c));
        }
    }

    /// The certificate of cell `c` as the edges stand now.
    fn certify(&mut self, c: usize) -> Result<Certificate<[f64; 3]>, CurvingError> {
        let mut buf = std::mem::take(&mut self.scratch);
        if self.faces.is_some() {
            self.cell_nodes_p3(c, &mut buf);
        } else {
            self.cell_nodes(c, &mut buf);
        }
        let ty = CellType::new(self.mesh.cells.get(c).ty.shape, self.per as u8 + 1);
        let result = certify_cell(ty, &buf, &self.params.certify)
            .map_err(|source| CurvingError::Check { cell: c, source });
        self.scratch = buf;
        result
    }

    /// Puts the mid node (P2) or the two inner nodes (P3, at a third and two thirds of the arc
    /// length, [`SurfaceProjector::edge_point`]) of every wall edge (both ends in layer 0)
    /// onto the true surface; returns how many.
    pub(crate) fn place_wall(&mut self, surface: &dyn SurfaceProjector) -> usize {
        let mut count = 0;
        for e in 0..self.edges.len() as u32 {
            let [a, b] = self.ends(e);
            if self.layers.layer[a as usize] != 0 || self.layers.layer[b as usize] != 0 {
                continue;
            }
            let facet = self
                .edges
                .cells(e)
                .iter()
                .map(|u| u.cell as usize)
                .find(|&c| self.mesh.cell_layer[c] == 0)
                .and_then(|c| self.mesh.cell_pipe.get(c).copied())
                .filter(|&p| p != NONE);
            let Some(facet) = facet else { continue };
            if self.per == 1 {
                let m = mid(self.x(a), self.x(b));
                let on = surface.project(m, facet as usize);
                self.dev[e as usize] = [0, 1, 2].map(|k| on[k] - m[k]);
            } else {
                // at equal arc length along the surface's curve over the edge (`march3d::nodes`)
                for i in 0..self.per {
                    let s = (i + 1) as f64 / (self.per + 1) as f64;
                    let on = surface.edge_point(self.x(a), self.x(b), s, facet as usize);
                    let m = self.straight_point(e, i);
                    self.dev[e as usize * self.per + i] = [0, 1, 2].map(|k| on[k] - m[k]);
                }
            }
            count += 1;
        }
        if self.faces.is_some() {
            self.place_wall_faces(surface);
        }
        count
    }

    /// The displacements an edge at `level` receives from below: the mean over the edges
    /// joining the nodes its ends come from, each read from the end under this edge's first
    /// end. `None` when no such edge exists.
    fn source_below(&self, e: u32, level: u32) -> Option<Slots> {
        let [a, b] = self.ends(e);
        let (mut sum, mut count) = (STRAIGHT, 0);
        for &x in self.layers.lower(&a, level) {
            for &y in self.layers.lower(&b, level) {
                if x == y {
                    continue;
                }
                if let Some(lower) = self.edges.find(&[x, y]) {
                    let d = self.slots(lower);
                    let along = self.edges.nodes(lower)[0] == x;
                    for (i, s) in sum.iter_mut().enumerate().take(self.per) {
                        let j = if along { i } else { self.per - 1 - i };
                        *s = add(*s, d[j]);
                    }
                    count += 1;
                }
            }
        }
        (count > 0).then(|| sum.map(|v| scale(v, 1.0 / count as f64)))
    }

    /// Marches up the layers: every edge above the wall gets the displacement below it, or a
    /// part of it, or none (module docs). `outer[n]`: node n is on the outer front.
    pub(crate) fn march(&mut self, outer: &[bool]) -> Result<(), CurvingError> {
        let layer = &self.layers.layer;
        let levels: Vec<u32> = (0..self.edges.len() as u32)
            .map(|e| {
                let [a, b] = self.ends(e);
                layer[a as usize].max(layer[b as usize])
            })
            .collect();
        let level_of = |e: u32| levels[e as usize];
        let mut by_level: Vec<u32> = (0..self.edges.len() as u32)
            .filter(|&e| level_of(e) > 0)
            .collect();
        by_level.sort_by_key(|&e| level_of(e));
        let mut pending = Vec::new();
        let mut i = 0;
        while i < by_level.len() {
            let level = level_of(by_level[i]);
            if self.faces.is_some() {
                self.inherit_faces(level);
            }
            pending.clear();
            while i < by_level.len() && level_of(by_level[i]) == level {
                let e = by_level[i];
                i += 1;
                let [a, b] = self.ends(e);
                if self.layers.parents(a).contains(&b) || self.layers.parents(b).contains(&a) {
                    continue; // an extrusion edge stays straight
                }
                let Some(source) = self.source_below(e, level) else {
                    self.stops.collapsed += 1;
                    continue;
                };
                if source == STRAIGHT {
                    continue;
                }
                // where the layer may stop, its edges wait straight (so that the stop of one
                // edge is judged with its neighbours straight too), else with the full source
                let at_outer = outer[a as usize] && outer[b as usize];
                let waiting = if at_outer || self.may_stop(level) {
                    STRAIGHT
                } else {
                    source
                };
                self.set(e, &waiting);
                pending.push((e, source, at_outer));
            }
            // an edge found with no valid choice is decided again once its neighbours are
            // (they may have been waiting straight); what still fails is counted
            let mut retry = Vec::new();
            for &(e, source, at_outer) in &pending {
                if !self.decide(e, source, level, at_outer)? {
                    retry.push((e, source, at_outer));
                }
            }
            for (e, source, at_outer) in retry {
                if !self.decide(e, source, level, at_outer)? {
                    self.stops.invalid += 1;
                }
            }
        }
        Ok(())
    }

    /// Whether every cell of edge `e` at or below `level` is certified valid, with a scaled
    /// Jacobian of at least `min_sj`.
    fn cells_below_good(&mut self, e: u32, level: u32, min_sj: f64) -> Result<bool, CurvingError> {
        let uses: Vec<usize> = self
            .edges
            .cells(e)
            .iter()
            .map(|u| u.cell as usize)
            .collect();
        for c in uses {
            let top = self
                .mesh
                .cells
                .get(c)
                .corners()
                .iter()
                .map(|&n| self.layers.layer[n as usize])
                .max();
            if top > Some(level) {
                continue;
            }
            let ok = self
                .certify(c)?
                .scaled_jacobian_lower_bound()
                .is_some_and(|q| q >= min_sj);
            if !ok {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// Whether edges at `level` may go straight: above `min_curved_layers` (the wall counts
    /// as the first curved layer, as in 2D).
    fn may_stop(&self, level: u32) -> bool {
        level >= self.params.min_curved_layers.max(1)
    }

    /// The decision for edge `e` at `level` given the displacement `source` below it; false
    /// when no choice leaves the cells below valid (the full displacement is kept). An edge
    /// of the outer front stays straight whenever its cells are valid so (the outer boundary
    /// keeps its facets), else it is curved like any other.
    fn decide(
        &mut self,
        e: u32,
        source: Slots,
        level: u32,
        at_outer: bool,
    ) -> Result<bool, CurvingError> {
        if at_outer || self.may_stop(level) {
            self.set(e, &STRAIGHT);
            let threshold = if at_outer {
                f64::MIN_POSITIVE
            } else {
                self.params.stop_min_scaled_jacobian
            };
            if self.cells_below_good(e, level, threshold)? {
                if at_outer {
                    self.stops.pipe_ended += 1;
                } else {
                    self.stops.jacobian += 1;
                }
                return Ok(true);
            }
        }
        self.deepest = self.deepest.max(level);
        for fraction in [1.0, 0.5, 0.25] {
            self.set(e, &source.map(|d| scale(d, fraction)));
            if self.cells_below_good(e, level, f64::MIN_POSITIVE)? {
                if fraction < 1.0 {
                    self.reduced += 1;
                }
                return Ok(true);
            }
        }
        self.set(e, &STRAIGHT);
        if self.cells_below_good(e, level, f64::MIN_POSITIVE)? {
            self.stops.jacobian += 1;
            return Ok(true);
        }
        self.set(e, &source);
        Ok(false)
    }

    /// Whether cell `c` is certified valid as the edges stand now.
    fn valid(&mut self, c: usize) -> Result<bool, CurvingError> {
        Ok(self
            .certify(c)?
            .scaled_jacobian_lower_bound()
            .is_some_and(|q| q > 0.0))
    }

    /// Mends the cells the marching left invalid — thin cells at the wing's tip rims, where
    /// the side's layers turn onto the flat cap's and edges of one cell took displacements
    /// from different pipes. As the 2D repair: an edge of the cell above the wall takes the
    /// displacement of the cell's most curved edge (Vector-Adding from the cell itself rather
    /// than up a pipe), or goes straight; the first such choice (edge by edge, then every edge
    /// above the wall at once) that leaves the cell valid and no cell of the changed edges
    /// newly invalid is kept. Pass after pass while a pass mends a cell; then the same for
    /// the cells left, a choice also kept when the neighbours it breaks can each be mended
    /// so. Returns the cells mended and those left invalid.
    pub(crate) fn repair(&mut self) -> Result<(usize, usize), CurvingError> {
        let mut bad = Vec::new();
        for c in 0..self.mesh.cells.len() {
            let curved = self.edges.of_cell(c).iter().any(|&e| !self.is_straight(e));
            if curved && !self.valid(c)? {
                bad.push(c);
            }
        }
        let mut repaired = 0;
        // single cells first; chains of two only for the cells that are left (so that every
        // mesh the single-cell repair mends is as it was)
        for depth in [0, 1] {
            for _ in 0..4 {
                let before = bad.len();
                let mut still = Vec::new();
                for &c in &bad {
                    if self.valid(c)? || self.mend(c, depth)? {
                        repaired += 1;
                    } else {
                        still.push(c);
                    }
                }
                bad = still;
                if bad.len() == before {
                    break;
                }
            }
        }
        Ok((repaired, bad.len()))
    }

    /// One invalid cell's repair ([`March::repair`]); whether it is valid after. With
    /// `depth` 1, a choice that leaves the cell valid but makes neighbours invalid is kept
    /// when each of those can be mended in turn by a choice of its own that breaks nothing
    /// ([`March::mend_to`] one level down): a chain of two cells, where every single-edge
    /// choice at a tip rim breaks a thin neighbour.
    fn mend(&mut self, c: usize, depth: usize) -> Result<bool, CurvingError> {
        let mut journal = Vec::new();
        self.mend_to(c, depth, &mut journal)
    }

    /// [`March::mend`] with `depth` levels of neighbours mended in turn; every slot changed
    /// is recorded in `journal` (slot, previous displacement) when the cell ends valid, and
    /// nothing is changed when it does not.
    fn mend_to(
        &mut self,
        c: usize,
        depth: usize,
        journal: &mut Vec<(u32, [f64; 3])>,
    ) -> Result<bool, CurvingError> {
        for choice in self.choices(c) {
            if choice
                .iter()
                .all(|&(e, d)| self.slots(e).iter().all(|&v| v == d))
            {
                continue;
            }
            let mut around: Vec<usize> = choice
                .iter()
                .flat_map(|&(e, _)| self.edges.cells(e).iter().map(|u| u.cell as usize))
                .collect();
            around.sort_unstable();
            around.dedup();
            let mut was = Vec::with_capacity(around.len());
            for &d in &around {
                was.push(self.valid(d)?);
            }
            let per = self.per;
            let mut local: Vec<(u32, [f64; 3])> = choice
                .iter()
                .flat_map(|&(e, _)| (0..per).map(move |i| e * per as u32 + i as u32))
                .map(|slot| (slot, self.dev[slot as usize]))
                .collect();
            for &(e, d) in &choice {
                self.set_all(e, d);
            }
            let mut broken = Vec::new();
            let mut ok = self.valid(c)?;
            for (&d, &w) in around.iter().zip(&was) {
                if !ok {
                    break;
                }
                if d != c && w && !self.valid(d)? {
                    if depth == 0 {
                        ok = false;
                    }
                    broken.push(d);
                }
            }
            // the neighbours this choice broke, mended one level down (each keeps `c` and
            // every other valid cell valid, as this level does)
            for &d in &broken {
                if !ok {
                    break;
                }
                ok = self.valid(d)? || (depth > 0 && self.mend_to(d, depth - 1, &mut local)?);
            }
            // (`c` was certified above; only a neighbour's mending can have changed it since)
            if ok && (broken.is_empty() || self.valid(c)?) {
                journal.extend(local);
                return Ok(true);
            }
            for &(slot, d) in local.iter().rev() {
                self.dev[slot as usize] = d;
            }
        }
        Ok(false)
    }

    /// The repair's choices for cell `c` ([`March::repair`]): each edge above the wall given
    /// the displacement of the cell's most curved edge (the mean of its slots, which belongs to
    /// no end, for every slot), or straight; then every such edge given it at once; then every
    /// such edge straight at once.
    fn choices(&self, c: usize) -> Vec<Vec<(u32, [f64; 3])>> {
        let layer = &self.layers.layer;
        let own = self.edges.of_cell(c);
        let above: Vec<u32> = own
            .iter()
            .copied()
            .filter(|&e| self.ends(e).iter().any(|&n| layer[n as usize] > 0))
            .collect();
        let size = |e: u32| {
            let norm = |d: &[f64; 3]| d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            self.slots(e).iter().map(norm).sum::<f64>()
        };
        let Some(most) = own
            .iter()
            .copied()
            .max_by(|&a, &b| size(a).total_cmp(&size(b)))
        else {
            return Vec::new();
        };
        let sum = self.slots(most).iter().fold([0.0; 3], |s, d| add(s, *d));
        let target = scale(sum, 1.0 / self.per as f64);
        let mut choices: Vec<Vec<(u32, [f64; 3])>> = Vec::new();
        for &e in &above {
            choices.push(vec![(e, target)]);
            choices.push(vec![(e, [0.0; 3])]);
        }
        choices.push(above.iter().map(|&e| (e, target)).collect());
        // last, every edge above the wall straight: a cell left almost flat at P1 (at a sharp
        // trailing edge's tip corner, 3e-6 thick under 2e-3 edges) cannot take any of its
        // pipes' bulges, and straight above its wall it is its valid linear self
        if above.len() > 1 {
            choices.push(above.iter().map(|&e| (e, [0.0; 3])).collect());
        }
        choices
    }
}
