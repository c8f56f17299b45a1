//! The spring models of the improved AFSF method (dissertation §3.2.2.1 and §4.1), written as
//! data plus assembly functions that add forces and stiffnesses for [`crate::solve()`].
//!
//! Every force is the dissertation's dimensionless force; alongside it each spring adds a
//! stiffness S (force per unit length) such that F/S is the move that would satisfy that spring
//! alone. The solver divides by the summed S, so the spring coefficients set the balance
//! between springs, never the stability of the iteration.
//!
//! Orientation convention (2D): a layer is a polyline A → K → B with the region still to be
//! meshed on its **left**; the ideal extrusion direction at K is the bisector of the left
//! normals of AK and KB.
//!
//! The extrusion spring is generic over the dimension, for reuse in 3D; the neighbour and
//! angle springs here are the 2D ones.

use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

use crate::model::{FiniteDifference, ForceModel, Spring, Triplet, jacobian_of};
use crate::params::SpringParams;
use crate::vec::{norm, sub};

/// Parent–child spring along an extrusion edge:
/// F = C_aniso·K_extru·(l_ideal − l_real)/l_ideal along the edge (§4.1, Eq. 1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ExtrusionSpring {
    /// The parent (lower-layer) node.
    pub lower: u32,
    /// The child (upper-layer) node.
    pub upper: u32,
    /// Ideal length of the edge (length units).
    pub ideal_length: f64,
    /// C_aniso of the lower node (the dissertation uses 1/G_ratio); the upper node's is 1.
    pub lower_share: f64,
}

/// Neighbour spring A–K–B on one layer (§3.2.2.1; strengthened as in §4.1): pushes K, at
/// right angles to its extrusion edge PK, until |AK| is the share `left_share` of
/// |AK| + |KB| (the dissertation's spring evens the two sides: share ½).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct NeighbourSpring {
    /// A, the neighbour before K along the layer.
    pub left: u32,
    /// K, the node pushed.
    pub centre: u32,
    /// B, the neighbour after K along the layer.
    pub right: u32,
    /// P, K's parent (one layer down).
    pub parent: u32,
    /// The share of |AK| + |KB| that |AK| should take, in (0, 1): ½ evens the sides; the
    /// mesher gives the share of the parents' spacing, so graded spacing along a wall is kept
    /// instead of being evened out (which shears the layers).
    pub left_share: f64,
}

/// Angle spring A–K–B–O (§4.1): keeps the extrusion edge KO along the ideal direction (the
/// bisector at K, rotated by `offset_rad` for the children of a fan). The force on O points
/// to O' (on the ideal direction, |KO'| = |KO|); the reaction on K points to A or B.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AngleSpring {
    /// A, the neighbour before K along K's layer.
    pub left: u32,
    /// K, the parent.
    pub centre: u32,
    /// B, the neighbour after K along K's layer.
    pub right: u32,
    /// O, K's child.
    pub child: u32,
    /// Counter-clockwise rotation of the ideal direction from the bisector (radians); 0
    /// except for fan children.
    pub offset_rad: f64,
    /// Ideal length of KO: the spring is off until |KO| reaches
    /// `angle_activation_ratio` of it.
    pub ideal_length: f64,
}

/// All springs of one 2D solve, indexed into the solver's position array.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct SpringSet2d {
    /// Extrusion (parent–child) springs.
    pub extrusion: Vec<ExtrusionSpring>,
    /// Neighbour springs.
    pub neighbour: Vec<NeighbourSpring>,
    /// Angle springs.
    pub angle: Vec<AngleSpring>,
}

impl SpringSet2d {
    /// The influence table of these springs over `n` nodes, for [`crate::solve_active()`]:
    /// each node pushed by a spring depends on every node of that spring.
    pub fn influence(&self, n: usize) -> crate::Influence {
        self.index(n).influence(self, n)
    }

    /// Removes every spring.
    pub fn clear(&mut self) {
        self.extrusion.clear();
        self.neighbour.clear();
        self.angle.clear();
    }
}

/// Adds the forces and stiffnesses of extrusion springs in any dimension.
pub fn assemble_extrusion<const D: usize>(
    springs: &[ExtrusionSpring],
    params: &SpringParams,
    positions: &[[f64; D]],
    force: &mut [[f64; D]],
    stiffness: &mut [f64],
) {
    extrusion_masked(springs, params, positions, None, force, stiffness);
}

/// [`assemble_extrusion`] for [`crate::solve_active()`]: skips the springs that push no
/// node flagged in `active`.
pub fn assemble_extrusion_active<const D: usize>(
    springs: &[ExtrusionSpring],
    params: &SpringParams,
    positions: &[[f64; D]],
    active: crate::Active<'_>,
    force: &mut [[f64; D]],
    stiffness: &mut [f64],
) {
    extrusion_masked(
        springs,
        params,
        positions,
        Some(active.flags),
        force,
        stiffness,
    );
}

fn extrusion_masked<const D: usize>(
    springs: &[ExtrusionSpring],
    params: &SpringParams,
    positions: &[[f64; D]],
    active: Option<&[bool]>,
    force: &mut [[f64; D]],
    stiffness: &mut [f64],
) {
    for s in springs {
        if let Some(active) = active
            && !(active[s.lower as usize] || active[s.upper as usize])
        {
            continue;
        }
        extrusion_into(s, params, positions, &mut direct(force, stiffness));
    }
}

/// Adds one contribution (force `f`, stiffness `k`) to node `node`: `force += f` component by
/// component, then `stiffness += k`.
#[inline(always)]
fn add_to<const D: usize>(
    force: &mut [[f64; D]],
    stiffness: &mut [f64],
    node: u32,
    f: [f64; D],
    k: f64,
) {
    let fo = &mut force[node as usize];
    for i in 0..D {
        fo[i] += f[i];
    }
    stiffness[node as usize] += k;
}

/// The sink that adds each contribution straight into `force` and `stiffness`.
#[inline(always)]
fn direct<'a, const D: usize>(
    force: &'a mut [[f64; D]],
    stiffness: &'a mut [f64],
) -> impl FnMut(u32, [f64; D], f64) + 'a {
    move |node, f, k| add_to(force, stiffness, node, f, k)
}

/// The contributions of one extrusion spring, handed to `add` (node, force, stiffness) in
/// the order they are summed: the upper node, then the lower.
#[inline(always)]
fn extrusion_into<const D: usize>(
    s: &ExtrusionSpring,
    params: &SpringParams,
    positions: &[[f64; D]],
    add: &mut impl FnMut(u32, [f64; D], f64),
) {
    let (lo, up) = (s.lower as usize, s.upper as usize);
    let v = sub(&positions[up], &positions[lo]);
    let len = norm(&v);
    if len <= 0.0 || s.ideal_length <= 0.0 {
        return;
    }
    let f = params.k_extrusion * (s.ideal_length - len) / s.ideal_length;
    let k = params.k_extrusion / s.ideal_length;
    let (a_up, a_lo) = (f / len, -s.lower_share * f / len);
    add(s.upper, std::array::from_fn(|i| a_up * v[i]), k);
    add(
        s.lower,
        std::array::from_fn(|i| a_lo * v[i]),
        s.lower_share * k,
    );
}

impl<const D: usize> Spring<D> for ExtrusionSpring {
    fn reads(&self, out: &mut Vec<u32>) {
        out.extend([self.lower, self.upper]);
    }

    fn pushes(&self, out: &mut Vec<u32>) {
        out.extend([self.upper, self.lower]);
    }

    fn add_force(
        &self,
        params: &SpringParams,
        positions: &[[f64; D]],
        force: &mut [[f64; D]],
        stiffness: &mut [f64],
    ) {
        extrusion_into(self, params, positions, &mut direct(force, stiffness));
    }

    /// Closed form: with v = X_upper − X_lower, l = |v| and L the ideal length, the force on
    /// the upper node is K(1/l − 1/L)·v, so ∂F_upper/∂X_upper = K[(1/l − 1/L)·I − v vᵀ/l³]
    /// = −∂F_upper/∂X_lower, and the lower node's rows are −C_aniso times the upper's.
    fn add_jacobian(
        &self,
        params: &SpringParams,
        movable: &[bool],
        fd: &mut FiniteDifference<D>,
        out: &mut Vec<Triplet>,
    ) {
        let positions = fd.positions();
        let (lo, up) = (self.lower as usize, self.upper as usize);
        let v = sub(&positions[up], &positions[lo]);
        let len = norm(&v);
        if len <= 0.0 || self.ideal_length <= 0.0 {
            return;
        }
        let k = params.k_extrusion;
        let diagonal = k * (1.0 / len - 1.0 / self.ideal_length);
        let outer = k / (len * len * len);
        for (row, row_sign) in [(up, 1.0), (lo, -self.lower_share)] {
            for (col, col_sign) in [(up, 1.0), (lo, -1.0)] {
                if !(movable[row] && movable[col]) {
                    continue;
                }
                for a in 0..D {
                    for b in 0..D {
                        let d = if a == b { diagonal } else { 0.0 };
                        out.push(Triplet {
                            row: (D * row + a) as u32,
                            col: (D * col + b) as u32,
                            value: row_sign * col_sign * (d - outer * v[a] * v[b]),
                        });
                    }
                }
            }
        }
    }
}

/// The `Spring<2>` impl of a 2D spring kind: the nodes it reads and pushes, and its force.
macro_rules! spring_2d {
    ($kind:ty, $force:ident, reads: [$($r:ident),*], pushes: [$($p:ident),*]) => {
        impl Spring<2> for $kind {
            fn reads(&self, out: &mut Vec<u32>) {
                out.extend([$(self.$r),*]);
            }

            fn pushes(&self, out: &mut Vec<u32>) {
                out.extend([$(self.$p),*]);
            }

            fn add_force(
                &self,
                params: &SpringParams,
                positions: &[[f64; 2]],
                force: &mut [[f64; 2]],
                stiffness: &mut [f64],
            ) {
                $force(self, params, positions, &mut direct(force, stiffness));
            }
        }
    };
}

spring_2d!(NeighbourSpring, neighbour_into, reads: [left, centre, right, parent], pushes: [centre]);
spring_2d!(AngleSpring, angle_into, reads: [left, centre, right, child], pushes: [child, centre]);

/// The 2D spring set bound to its coefficients and per-node index: the [`ForceModel`] of the
/// 2D mesher. Its active assembly is [`assemble_2d_active`].
#[derive(Debug, Clone)]
pub struct SpringField2d<'a> {
    set: &'a SpringSet2d,
    params: &'a SpringParams,
    index: SpringIndex2d,
    /// With more than one thread and a large solve, the half of every node for the parallel
    /// assembly ([`Halves`]), made when first needed: beside the influence table, which the
    /// first iteration builds beside its assembly on one thread (the halves are not needed
    /// before the second), or by the first assembly in halves. `None` with one thread or a
    /// small solve.
    halves: Option<OnceLock<Halves>>,
}

impl<'a> SpringField2d<'a> {
    /// Binds `set` and `params` for a solve over `n` nodes (the springs' index made now, the
    /// halves when first needed).
    pub fn new(set: &'a SpringSet2d, params: &'a SpringParams, n: usize) -> Self {
        let parallel = rayon::current_num_threads() > 1 && n >= PARALLEL_MIN_ACTIVE;
        SpringField2d {
            set,
            params,
            index: set.index(n),
            halves: parallel.then(OnceLock::new),
        }
    }

    /// The halves, made now if they were not yet; `None` when the assembly is not split.
    fn halves(&self) -> Option<&Halves> {
        let cell = self.halves.as_ref()?;
        // (over the nodes of the solve: those the index covers)
        let n = self.index.offsets.len() - 1;
        Some(cell.get_or_init(|| Halves::new(self.set, n)))
    }
}

/// Active nodes from which an iteration's assembly is split between two threads: below, a
/// fork-join costs more than half the work saves (on the layers of a large 2D mesh, the few
/// iterations with this many active nodes carry some 95 % of the assembly's work).
const PARALLEL_MIN_ACTIVE: usize = 4096;

/// Components of the springs' push graph dealt out to this many at a time to each half, so
/// that a local active set is split about evenly too.
const HALF_BLOCK: usize = 256;

thread_local! {
    /// The second half's force and stiffness arrays, kept between the iterations of a solve
    /// (and the solves of a run) on the thread that last used them.
    static HALF_SCRATCH: std::cell::RefCell<(Vec<[f64; 2]>, Vec<f64>)> =
        const { std::cell::RefCell::new((Vec::new(), Vec::new())) };
}

/// The nodes of a 2D solve in two halves such that every spring is evaluated and pushes
/// within one half: a spring is evaluated from one of the nodes it pushes (an extrusion spring
/// from its upper or lower node, an angle spring from its child or centre, a neighbour spring
/// from its centre, which is all it pushes), so the connected components of the graph joining
/// the nodes each spring pushes are never split. Each half then sums its nodes' forces in the
/// order of the sequential assembly restricted to it — which is that assembly's order for
/// each of its nodes: the same sums to the last bit.
#[derive(Debug, Clone)]
struct Halves {
    /// 0 or 1 per node.
    half: Vec<u8>,
}

impl Halves {
    fn new(set: &SpringSet2d, n: usize) -> Self {
        let mut parent: Vec<u32> = (0..n as u32).collect();
        let find = |parent: &mut [u32], mut x: u32| {
            while parent[x as usize] != x {
                let up = parent[parent[x as usize] as usize];
                parent[x as usize] = up;
                x = up;
            }
            x
        };
        let mut join = |a: u32, b: u32| {
            if (a as usize) < n && (b as usize) < n {
                let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
                if ra != rb {
                    parent[ra.max(rb) as usize] = ra.min(rb);
                }
            }
        };
        for s in &set.extrusion {
            join(s.lower, s.upper);
        }
        for s in &set.angle {
            join(s.centre, s.child);
        }
        // components numbered in the order of their first node, dealt out in blocks
        let mut rank = vec![u32::MAX; n];
        let mut next = 0u32;
        let mut half = vec![0u8; n];
        for i in 0..n as u32 {
            let root = find(&mut parent, i) as usize;
            if rank[root] == u32::MAX {
                rank[root] = next;
                next += 1;
            }
            half[i as usize] = ((rank[root] as usize / HALF_BLOCK) % 2) as u8;
        }
        Halves { half }
    }
}

impl SpringField2d<'_> {
    /// The active assembly, in halves on two threads when there are enough active nodes,
    /// adding to the active entries or setting them (`sums`).
    fn assemble_active_into(
        &self,
        positions: &[[f64; 2]],
        active: crate::Active<'_>,
        (force, stiffness): (&mut [[f64; 2]], &mut [f64]),
        sums: Sums,
    ) {
        // (a small iteration does not make the halves)
        let halves = if active.nodes.len() >= PARALLEL_MIN_ACTIVE {
            self.halves()
        } else {
            None
        };
        match halves {
            Some(halves) => {
                let eval = ActiveEval {
                    set: self.set,
                    index: &self.index,
                    params: self.params,
                    positions,
                    flags: active.flags,
                };
                eval.in_halves(&halves.half, active.nodes, (force, stiffness), sums);
            }
            None => {
                if sums == Sums::Set {
                    crate::model::zero_active(active.nodes, force, stiffness);
                }
                self.assemble_active_here(positions, active, force, stiffness);
            }
        }
    }
}

/// Whether an assembly adds to the active nodes' entries or sets them to the sums.
#[derive(Clone, Copy, PartialEq)]
enum Sums {
    Add,
    Set,
}

impl ForceModel<2> for SpringField2d<'_> {
    fn assemble(&self, positions: &[[f64; 2]], force: &mut [[f64; 2]], stiffness: &mut [f64]) {
        assemble_2d(self.set, self.params, positions, force, stiffness);
    }

    fn extrusion_axis(&self, node: usize, positions: &[[f64; 2]]) -> Option<[f64; 2]> {
        let index = &self.index;
        let range = *index.offsets.get(node)? as usize..*index.offsets.get(node + 1)? as usize;
        let spring = index.springs[range]
            .iter()
            .filter(|&&id| id >> KIND_SHIFT == 0)
            .map(|&id| &self.set.extrusion[(id & INDEX_MASK) as usize])
            .find(|e| e.upper as usize == node)?;
        let (p, q) = (positions[spring.lower as usize], positions[node]);
        let d = [q[0] - p[0], q[1] - p[1]];
        let l = (d[0] * d[0] + d[1] * d[1]).sqrt();
        (l > 0.0).then(|| [d[0] / l, d[1] / l])
    }

    fn assemble_active(
        &self,
        positions: &[[f64; 2]],
        active: crate::Active<'_>,
        force: &mut [[f64; 2]],
        stiffness: &mut [f64],
    ) {
        self.assemble_active_into(positions, active, (force, stiffness), Sums::Add);
    }

    fn assemble_active_fresh(
        &self,
        positions: &[[f64; 2]],
        active: crate::Active<'_>,
        force: &mut [[f64; 2]],
        stiffness: &mut [f64],
    ) {
        self.assemble_active_into(positions, active, (force, stiffness), Sums::Set);
    }

    fn assemble_active_here(
        &self,
        positions: &[[f64; 2]],
        active: crate::Active<'_>,
        force: &mut [[f64; 2]],
        stiffness: &mut [f64],
    ) {
        assemble_2d_active(
            self.set,
            &self.index,
            self.params,
            positions,
            active,
            force,
            stiffness,
        );
    }

    fn influence(&self, n: usize) -> crate::Influence {
        // the halves, when they are to be made, beside the table: on the thread that ends
        // the first (the first iteration's assembly or this table) while the other works
        if self.halves.as_ref().is_some_and(|c| c.get().is_none()) {
            let (table, _) = rayon::join(|| self.index.influence(self.set, n), || self.halves());
            return table;
        }
        self.index.influence(self.set, n)
    }

    fn jacobian(&self, positions: &[[f64; 2]], movable: &[bool], out: &mut Vec<Triplet>) {
        let mut fd = FiniteDifference::new(positions);
        jacobian_of(&self.set.extrusion, self.params, movable, &mut fd, out);
        jacobian_of(&self.set.neighbour, self.params, movable, &mut fd, out);
        jacobian_of(&self.set.angle, self.params, movable, &mut fd, out);
    }
}

/// The unit left normal of the segment A → B, or `None` when A = B.
#[inline]
pub fn left_normal(a: [f64; 2], b: [f64; 2]) -> Option<[f64; 2]> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let l = (d[0] * d[0] + d[1] * d[1]).sqrt();
    (l > 0.0).then(|| [-d[1] / l, d[0] / l])
}

/// The ideal extrusion direction at K of the layer A → K → B (region to mesh on the left):
/// the bisector of the left normals of AK and KB, or `None` when it is undefined (coincident
/// nodes, or a front folded back on itself).
pub fn bisector(a: [f64; 2], k: [f64; 2], b: [f64; 2]) -> Option<[f64; 2]> {
    bisector_and_sides(a, k, b).map(|(d, _, _)| d)
}

/// [`bisector`] with the lengths |AK| and |KB| it computes on the way.
#[inline(always)]
fn bisector_and_sides(a: [f64; 2], k: [f64; 2], b: [f64; 2]) -> Option<([f64; 2], f64, f64)> {
    let d1 = [k[0] - a[0], k[1] - a[1]];
    let l1 = (d1[0] * d1[0] + d1[1] * d1[1]).sqrt();
    let d2 = [b[0] - k[0], b[1] - k[1]];
    let l2 = (d2[0] * d2[0] + d2[1] * d2[1]).sqrt();
    if !(l1 > 0.0 && l2 > 0.0) {
        return None;
    }
    let n1 = [-d1[1] / l1, d1[0] / l1];
    let n2 = [-d2[1] / l2, d2[0] / l2];
    let s = [n1[0] + n2[0], n1[1] + n2[1]];
    let l = (s[0] * s[0] + s[1] * s[1]).sqrt();
    if l > 1e-9 {
        Some(([s[0] / l, s[1] / l], l1, l2))
    } else {
        left_normal(a, b).map(|d| (d, l1, l2))
    }
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
}

/// Adds the forces and stiffnesses of every spring of `set` (2D).
pub fn assemble_2d(
    set: &SpringSet2d,
    params: &SpringParams,
    positions: &[[f64; 2]],
    force: &mut [[f64; 2]],
    stiffness: &mut [f64],
) {
    extrusion_masked(&set.extrusion, params, positions, None, force, stiffness);
    for s in &set.neighbour {
        neighbour_into(s, params, positions, &mut direct(force, stiffness));
    }
    for s in &set.angle {
        angle_into(s, params, positions, &mut direct(force, stiffness));
    }
}

/// For each node, the springs of a [`SpringSet2d`] that push it (built by
/// [`SpringSet2d::index`]), so that [`assemble_2d_active`] visits only the springs of the
/// active nodes.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SpringIndex2d {
    offsets: Vec<u32>,
    /// Spring kind in the top two bits (0 extrusion, 1 neighbour, 2 angle), index below.
    springs: Vec<u32>,
}

const KIND_SHIFT: u32 = 30;
const INDEX_MASK: u32 = (1 << KIND_SHIFT) - 1;

impl SpringSet2d {
    /// The per-node spring index over `n` nodes, for [`assemble_2d_active`]: for each node
    /// the springs that push it, in the order extrusion springs (each pushing its upper then
    /// its lower node), neighbour springs, angle springs (child then centre), each kind in
    /// its order. Counted, then placed, straight from the springs (a counting sort).
    pub fn index(&self, n: usize) -> SpringIndex2d {
        let mut offsets = vec![0u32; n + 1];
        self.each_push(|node, _| {
            if (node as usize) < n {
                offsets[node as usize + 1] += 1;
            }
        });
        for i in 0..n {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut springs = vec![0u32; offsets[n] as usize];
        self.each_push(|node, id| {
            let node = node as usize;
            if node < n {
                springs[fill[node] as usize] = id;
                fill[node] += 1;
            }
        });
        SpringIndex2d { offsets, springs }
    }

    /// Calls `push(node, id)` for every node each spring pushes, in the index's order, `id`
    /// being the spring's kind (top bits) and its place.
    #[inline(always)]
    fn each_push(&self, mut push: impl FnMut(u32, u32)) {
        for (i, s) in self.extrusion.iter().enumerate() {
            push(s.upper, i as u32);
            push(s.lower, i as u32);
        }
        for (i, s) in self.neighbour.iter().enumerate() {
            push(s.centre, (1 << KIND_SHIFT) | i as u32);
        }
        for (i, s) in self.angle.iter().enumerate() {
            push(s.child, (2 << KIND_SHIFT) | i as u32);
            push(s.centre, (2 << KIND_SHIFT) | i as u32);
        }
    }
}

impl SpringIndex2d {
    /// Calls `dep(r)` for every node `r < n` that a spring pushing `node` reads, `node`
    /// itself left out (repeats possible).
    #[inline(always)]
    fn reads_of(&self, set: &SpringSet2d, node: usize, n: usize, dep: &mut impl FnMut(u32)) {
        let mut read = |r: u32| {
            if r as usize != node && (r as usize) < n {
                dep(r);
            }
        };
        let range = self.offsets[node] as usize..self.offsets[node + 1] as usize;
        for &id in &self.springs[range] {
            let i = (id & INDEX_MASK) as usize;
            match id >> KIND_SHIFT {
                0 => {
                    let s = &set.extrusion[i];
                    read(s.lower);
                    read(s.upper);
                }
                1 => {
                    let s = &set.neighbour[i];
                    [s.left, s.centre, s.right, s.parent]
                        .into_iter()
                        .for_each(&mut read);
                }
                _ => {
                    let s = &set.angle[i];
                    [s.left, s.centre, s.right, s.child]
                        .into_iter()
                        .for_each(&mut read);
                }
            }
        }
    }

    /// The influence table of `set` over `n` nodes (this index being `set.index(n)`): the
    /// same table as [`crate::Influence::from_pairs`] of every (pushed, read) pair, built by
    /// walking the pushed nodes in increasing order, so that each row comes out sorted and
    /// its repeats next to each other (no pair list, no sort).
    fn influence(&self, set: &SpringSet2d, n: usize) -> crate::Influence {
        // the last pushed node counted in each row, to count each pair once
        let mut last = vec![u32::MAX; n];
        let mut offsets = vec![0u32; n + 1];
        for node in 0..n {
            self.reads_of(set, node, n, &mut |r| {
                if last[r as usize] != node as u32 {
                    last[r as usize] = node as u32;
                    offsets[r as usize + 1] += 1;
                }
            });
        }
        for i in 0..n {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut targets = vec![0u32; offsets[n] as usize];
        for node in 0..n {
            self.reads_of(set, node, n, &mut |r| {
                let (start, at) = (offsets[r as usize], fill[r as usize]);
                if at == start || targets[at as usize - 1] != node as u32 {
                    targets[at as usize] = node as u32;
                    fill[r as usize] = at + 1;
                }
            });
        }
        crate::Influence::from_rows(offsets, targets)
    }
}

/// [`assemble_2d`] for [`crate::solve_active()`]: adds the complete force and stiffness of
/// every active node, evaluating only the springs that push an active node (each once; the
/// other nodes may get partial sums). `index` must be `set.index(n)` for the solve's `n`.
pub fn assemble_2d_active(
    set: &SpringSet2d,
    index: &SpringIndex2d,
    params: &SpringParams,
    positions: &[[f64; 2]],
    active: crate::Active<'_>,
    force: &mut [[f64; 2]],
    stiffness: &mut [f64],
) {
    let eval = ActiveEval {
        set,
        index,
        params,
        positions,
        flags: active.flags,
    };
    eval.springs_of(active.nodes, &mut direct(force, stiffness));
}

/// What the active assembly reads: the springs, their index, coefficients, positions and the
/// active flags.
struct ActiveEval<'a> {
    set: &'a SpringSet2d,
    index: &'a SpringIndex2d,
    params: &'a SpringParams,
    positions: &'a [[f64; 2]],
    flags: &'a [bool],
}

impl ActiveEval<'_> {
    /// The contributions of the springs that the active `nodes` evaluate (for each node, those
    /// pushing it that no other active node evaluates first), handed to `add` in order.
    #[inline(always)]
    fn springs_of(&self, nodes: &[u32], add: &mut impl FnMut(u32, [f64; 2], f64)) {
        self.springs_of_where(nodes, |_| true, add);
    }

    /// [`ActiveEval::springs_of`] on two threads, each evaluating the active nodes of one of
    /// the `half`s ([`Halves`]): the first into `force` and `stiffness` (its active entries
    /// zeroed first on its thread when they are to be set), the second into arrays of its own
    /// whose sums then go to its active nodes (set, or added).
    fn in_halves(
        &self,
        half: &[u8],
        nodes: &[u32],
        (force, stiffness): (&mut [[f64; 2]], &mut [f64]),
        sums: Sums,
    ) {
        let n = force.len();
        // the second half's sums go to the arrays on both threads, each taking the nodes of
        // one range of numbers (the entries are written apart, so the same bits either way)
        let mid = crate::solver::middle_node(nodes);
        let ((), (force_1, stiffness_1, [low, high])) = rayon::join(
            || {
                if sums == Sums::Set {
                    for &i in nodes.iter().filter(|&&i| half[i as usize] == 0) {
                        force[i as usize] = [0.0; 2];
                        stiffness[i as usize] = 0.0;
                    }
                }
                self.springs_of_where(nodes, |i| half[i] == 0, &mut direct(force, stiffness));
            },
            || {
                // the arrays of the last call on this thread, its active entries zeroed (the
                // others may hold anything: they are not read); its active nodes listed by
                // range for the merge
                let (mut f, mut s) = HALF_SCRATCH.with(|c| std::mem::take(&mut *c.borrow_mut()));
                f.resize(n, [0.0; 2]);
                s.resize(n, 0.0);
                let mut ranges = [Vec::new(), Vec::new()];
                for &i in nodes.iter().filter(|&&i| half[i as usize] == 1) {
                    f[i as usize] = [0.0; 2];
                    s[i as usize] = 0.0;
                    ranges[usize::from(i as usize >= mid)].push(i);
                }
                self.springs_of_where(nodes, |i| half[i] == 1, &mut direct(&mut f, &mut s));
                (f, s, ranges)
            },
        );
        let (force_low, force_high) = force.split_at_mut(mid);
        let (stiffness_low, stiffness_high) = stiffness.split_at_mut(mid);
        let merge = |from: usize, own: &[u32], force: &mut [[f64; 2]], stiffness: &mut [f64]| {
            for &i in own {
                let i = i as usize;
                let (f, s) = (&mut force[i - from], &mut stiffness[i - from]);
                match sums {
                    Sums::Set => {
                        *f = force_1[i];
                        *s = stiffness_1[i];
                    }
                    Sums::Add => {
                        *f = [f[0] + force_1[i][0], f[1] + force_1[i][1]];
                        *s += stiffness_1[i];
                    }
                }
            }
        };
        rayon::join(
            || merge(0, &low, force_low, stiffness_low),
            || merge(mid, &high, force_high, stiffness_high),
        );
        HALF_SCRATCH.with(|c| *c.borrow_mut() = (force_1, stiffness_1));
    }

    /// The contributions of the springs that the active `nodes` for which `take` holds
    /// evaluate, handed to `add` in order.
    #[inline(always)]
    fn springs_of_where(
        &self,
        nodes: &[u32],
        take: impl Fn(usize) -> bool,
        add: &mut impl FnMut(u32, [f64; 2], f64),
    ) {
        let (set, params, positions, flags) = (self.set, self.params, self.positions, self.flags);
        for &node in nodes {
            let n = node as usize;
            if !take(n) {
                continue;
            }
            let range = self.index.offsets[n] as usize..self.index.offsets[n + 1] as usize;
            for &id in &self.index.springs[range] {
                let i = (id & INDEX_MASK) as usize;
                match id >> KIND_SHIFT {
                    0 => {
                        // pushed both ways: evaluated from the upper node when it is active
                        let s = &set.extrusion[i];
                        if s.upper == node || !flags[s.upper as usize] {
                            extrusion_into(s, params, positions, add);
                        }
                    }
                    1 => neighbour_into(&set.neighbour[i], params, positions, add),
                    _ => {
                        // pushes child and centre: evaluated from the child when it is active
                        let s = &set.angle[i];
                        if s.child == node || !flags[s.child as usize] {
                            angle_into(s, params, positions, add);
                        }
                    }
                }
            }
        }
    }
}

/// The contribution of one neighbour spring (to its centre), handed to `add`.
#[inline(always)]
fn neighbour_into(
    s: &NeighbourSpring,
    params: &SpringParams,
    positions: &[[f64; 2]],
    add: &mut impl FnMut(u32, [f64; 2], f64),
) {
    let (a, k, b, p) = (
        positions[s.left as usize],
        positions[s.centre as usize],
        positions[s.right as usize],
        positions[s.parent as usize],
    );
    let d = [k[0] - p[0], k[1] - p[1]];
    let h = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let (la, lb) = (dist(a, k), dist(k, b));
    if h <= 0.0 || la + lb <= 0.0 {
        return;
    }
    let mut t = [-d[1] / h, d[0] / h];
    if t[0] * (b[0] - a[0]) + t[1] * (b[1] - a[1]) < 0.0 {
        t = [-t[0], -t[1]];
    }
    let aspect = (la + lb) / (2.0 * h);
    let threshold = params.neighbour_boost_below_aspect;
    let boost = if aspect < threshold {
        1.0 + (params.neighbour_boost - 1.0) * (1.0 - aspect / threshold)
    } else {
        1.0
    };
    let f = params.k_neighbour * boost * 2.0 * (s.left_share - la / (la + lb));
    add(
        s.centre,
        [f * t[0], f * t[1]],
        params.k_neighbour * boost * 2.0 / (la + lb),
    );
}

/// The contributions of one angle spring, handed to `add`: its child, then its centre.
#[inline(always)]
fn angle_into(
    s: &AngleSpring,
    params: &SpringParams,
    positions: &[[f64; 2]],
    add: &mut impl FnMut(u32, [f64; 2], f64),
) {
    let deg_per_rad = 180.0 / std::f64::consts::PI;
    let (a, k, b, o) = (
        positions[s.left as usize],
        positions[s.centre as usize],
        positions[s.right as usize],
        positions[s.child as usize],
    );
    let v = [o[0] - k[0], o[1] - k[1]];
    let len = (v[0] * v[0] + v[1] * v[1]).sqrt();
    if len <= 0.0 || len < params.angle_activation_ratio * s.ideal_length {
        return;
    }
    let Some((bis, side_a, side_b)) = bisector_and_sides(a, k, b) else {
        return;
    };
    // most springs have no fan offset: skip the rotation (and its sin/cos) for them
    let ideal = if s.offset_rad == 0.0 {
        bis
    } else {
        let (sn, cs) = s.offset_rad.sin_cos();
        [cs * bis[0] - sn * bis[1], sn * bis[0] + cs * bis[1]]
    };
    let cos_a = (v[0] * ideal[0] + v[1] * ideal[1]) / len;
    let sin_a = (ideal[0] * v[1] - ideal[1] * v[0]) / len;
    let shape = ((side_a + side_b) / (2.0 * len)).min(params.fac_b);
    let gain = params.k_angle * deg_per_rad / params.fac_a * shape;
    let k_len = gain / len;
    let (f_mag, dir_o) = if cos_a >= 0.0 {
        let target = [k[0] + len * ideal[0], k[1] + len * ideal[1]];
        let c = [target[0] - o[0], target[1] - o[1]];
        let cl = (c[0] * c[0] + c[1] * c[1]).sqrt();
        if cl <= 0.0 {
            return;
        }
        (gain * sin_a.abs(), [c[0] / cl, c[1] / cl])
    } else {
        // Beyond 90°: push O at right angles to KO, back toward the ideal side (§4.1).
        let perp = if sin_a > 0.0 {
            [v[1] / len, -v[0] / len]
        } else {
            [-v[1] / len, v[0] / len]
        };
        (gain, perp)
    };
    let share_o = 1.0 - params.c_percent;
    add(
        s.child,
        [share_o * f_mag * dir_o[0], share_o * f_mag * dir_o[1]],
        share_o * k_len,
    );
    if params.c_percent > 0.0 {
        let dir_k = if cos_a >= 0.0 {
            // O leans toward A when it is counter-clockwise of the ideal direction.
            let toward = if sin_a > 0.0 { a } else { b };
            let d = [toward[0] - k[0], toward[1] - k[1]];
            let dl = (d[0] * d[0] + d[1] * d[1]).sqrt();
            if dl <= 0.0 {
                return;
            }
            [d[0] / dl, d[1] / dl]
        } else {
            [-dir_o[0], -dir_o[1]]
        };
        add(
            s.centre,
            [
                params.c_percent * f_mag * dir_k[0],
                params.c_percent * f_mag * dir_k[1],
            ],
            params.c_percent * k_len,
        );
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::{SolverParams, solve};

    /// Two fixed base nodes and a free child above each: the child of the middle of a flat
    /// layer goes straight up to its ideal length.
    #[test]
    fn a_child_over_a_flat_layer_goes_along_the_normal_to_its_ideal_length() {
        // base: 0 (A), 1 (K), 2 (B) fixed; child 3 of K starts tilted and short.
        let mut x = vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [1.3, 0.05]];
        let set = SpringSet2d {
            extrusion: vec![ExtrusionSpring {
                lower: 1,
                upper: 3,
                ideal_length: 0.1,
                lower_share: 1.0 / 1.3,
            }],
            neighbour: vec![],
            angle: vec![AngleSpring {
                left: 0,
                centre: 1,
                right: 2,
                child: 3,
                offset_rad: 0.0,
                ideal_length: 0.1,
            }],
        };
        let params = SpringParams::default();
        let movable = [false, false, false, true];
        let scale = [0.1; 4];
        let out = solve(
            &mut x,
            &scale,
            &movable,
            &SolverParams::default(),
            |p, f, s| assemble_2d(&set, &params, p, f, s),
        )
        .unwrap();
        assert!(out.converged, "{out:?}");
        assert!((x[3][0] - 1.0).abs() < 1e-3, "{:?}", x[3]);
        assert!((x[3][1] - 0.1).abs() < 1e-3, "{:?}", x[3]);
        assert_eq!(x[1], [1.0, 0.0]);
    }

    #[test]
    fn the_neighbour_spring_pushes_toward_the_longer_side() {
        let x = [[0.0, 1.0], [1.0, 1.0], [4.0, 1.0], [1.0, 0.0]];
        let set = SpringSet2d {
            neighbour: vec![NeighbourSpring {
                left: 0,
                centre: 1,
                right: 2,
                parent: 3,
                left_share: 0.5,
            }],
            ..SpringSet2d::default()
        };
        let mut f = [[0.0; 2]; 4];
        let mut s = [0.0; 4];
        assemble_2d(&set, &SpringParams::default(), &x, &mut f, &mut s);
        assert!(f[1][0] > 0.0 && f[1][1].abs() < 1e-15, "{f:?}");
        // the Jacobi move F/S evens the two sides
        assert!((f[1][0] / s[1] - 1.0).abs() < 1e-12, "{}", f[1][0] / s[1]);
    }

    #[test]
    fn the_angle_reaction_on_the_parent_points_to_the_side_the_child_leans_to() {
        // child leans toward A (left, negative x): K is pushed toward A, O back toward +x.
        let x = [[-1.0, 0.0], [0.0, 0.0], [1.0, 0.0], [-0.02, 0.1]];
        let set = SpringSet2d {
            angle: vec![AngleSpring {
                left: 0,
                centre: 1,
                right: 2,
                child: 3,
                offset_rad: 0.0,
                ideal_length: 0.1,
            }],
            ..SpringSet2d::default()
        };
        let mut f = [[0.0; 2]; 4];
        let mut s = [0.0; 4];
        assemble_2d(&set, &SpringParams::default(), &x, &mut f, &mut s);
        assert!(f[1][0] < 0.0, "{f:?}");
        assert!(f[3][0] > 0.0, "{f:?}");
    }

    /// Two layers of four nodes over a fixed base of four, every kind of spring
    /// (jitter: 16 offsets of the upper nodes).
    pub(crate) fn two_layers(
        jitter: &[f64],
        left_share: f64,
        angle_ideal: f64,
    ) -> (Vec<[f64; 2]>, SpringSet2d) {
        let mut x: Vec<[f64; 2]> = (0..12)
            .map(|i| [(i % 4) as f64, (i / 4) as f64 * 0.3])
            .collect();
        for i in 4..12 {
            x[i][0] += jitter[2 * (i - 4)];
            x[i][1] += 0.5 * jitter[2 * (i - 4) + 1];
        }
        let mut set = SpringSet2d::default();
        for child in 4..12u32 {
            let parent = child - 4;
            set.extrusion.push(ExtrusionSpring {
                lower: parent,
                upper: child,
                ideal_length: 0.3,
                lower_share: 0.8,
            });
            let col = child % 4;
            if col > 0 && col < 3 {
                set.neighbour.push(NeighbourSpring {
                    left: child - 1,
                    centre: child,
                    right: child + 1,
                    parent,
                    left_share,
                });
                set.angle.push(AngleSpring {
                    left: parent - 1,
                    centre: parent,
                    right: parent + 1,
                    child,
                    offset_rad: if col == 1 { 0.0 } else { 0.1 },
                    ideal_length: angle_ideal,
                });
            }
        }
        (x, set)
    }

    #[test]
    fn the_extrusion_axis_runs_from_the_parent_and_only_children_have_one() {
        let (x, set) = two_layers(&[0.0; 16], 0.5, 0.3);
        let params = SpringParams::default();
        let model = SpringField2d::new(&set, &params, x.len());
        for e in &set.extrusion {
            let (p, q) = (x[e.lower as usize], x[e.upper as usize]);
            let l = (q[0] - p[0]).hypot(q[1] - p[1]);
            let u = model.extrusion_axis(e.upper as usize, &x).unwrap();
            assert!((u[0] - (q[0] - p[0]) / l).abs() < 1e-15);
            assert!((u[1] - (q[1] - p[1]) / l).abs() < 1e-15);
        }
        let children: Vec<u32> = set.extrusion.iter().map(|e| e.upper).collect();
        for n in (0..x.len()).filter(|n| !children.contains(&(*n as u32))) {
            assert_eq!(model.extrusion_axis(n, &x), None);
        }
        assert_eq!(model.extrusion_axis(x.len() + 5, &x), None);
    }

    proptest::proptest! {
        /// The indexed assembly gives every active node the same force and stiffness as the
        /// full assembly, whichever nodes are active.
        #[test]
        fn indexed_assembly_matches_the_full_one_on_active_nodes(
            jitter in proptest::collection::vec(-0.2f64..0.2, 16),
            active_bits in 0u16..,
        ) {
            let (x, set) = two_layers(&jitter, 0.5, 0.3);
            let params = SpringParams::default();
            let mut f_full = vec![[0.0; 2]; 12];
            let mut s_full = vec![0.0; 12];
            assemble_2d(&set, &params, &x, &mut f_full, &mut s_full);
            let flags: Vec<bool> = (0..12).map(|i| active_bits & (1 << i) != 0).collect();
            let nodes: Vec<u32> = (0..12u32).filter(|&i| flags[i as usize]).collect();
            let index = set.index(12);
            let mut f = vec![[0.0; 2]; 12];
            let mut s = vec![0.0; 12];
            assemble_2d_active(&set, &index, &params, &x, crate::Active { flags: &flags, nodes: &nodes }, &mut f, &mut s);
            for &i in &nodes {
                let i = i as usize;
                proptest::prop_assert!((f[i][0] - f_full[i][0]).abs() < 1e-12 && (f[i][1] - f_full[i][1]).abs() < 1e-12, "node {i}: {:?} vs {:?}", f[i], f_full[i]);
                proptest::prop_assert!((s[i] - s_full[i]).abs() < 1e-12);
            }
        }
    }

    /// A ring of `n` fixed wall nodes under two moving layers, jittered, with every fifth
    /// node of the second layer also the child of its first layer's right neighbour (a merge,
    /// which joins two columns of the push graph) and every seventh first-layer node also the
    /// parent of the second-layer node two columns on (two children, as a fan's).
    fn big_ring(n: usize) -> (Vec<[f64; 2]>, Vec<bool>, Vec<f64>, SpringSet2d) {
        let mut seed = 11u64;
        let mut noise = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 2e-3
        };
        let mut pos = Vec::new();
        for k in 0..3 {
            for i in 0..n {
                let t = -std::f64::consts::TAU * i as f64 / n as f64;
                let r = 1.0 + 0.004 * k as f64;
                let (dx, dy) = if k == 0 {
                    (0.0, 0.0)
                } else {
                    (noise(), noise())
                };
                pos.push([r * t.cos() + dx, r * t.sin() + dy]);
            }
        }
        let at = |k: usize, i: usize| (k * n + i % n) as u32;
        let mut set = SpringSet2d::default();
        let child_of = |set: &mut SpringSet2d, parent: u32, child: u32, l: u32, r: u32| {
            set.extrusion.push(ExtrusionSpring {
                lower: parent,
                upper: child,
                ideal_length: 0.004,
                lower_share: 0.8,
            });
            set.angle.push(AngleSpring {
                left: l,
                centre: parent,
                right: r,
                child,
                offset_rad: 0.05,
                ideal_length: 0.004,
            });
        };
        for k in 1..3 {
            for i in 0..n {
                let (parent, child) = (at(k - 1, i), at(k, i));
                child_of(
                    &mut set,
                    parent,
                    child,
                    at(k - 1, i + n - 1),
                    at(k - 1, i + 1),
                );
                if k == 2 && i % 5 == 0 {
                    let other = at(1, i + 1);
                    child_of(&mut set, other, child, at(1, i), at(1, i + 2));
                }
                set.neighbour.push(NeighbourSpring {
                    left: at(k, i + n - 1),
                    centre: child,
                    right: at(k, i + 1),
                    parent,
                    left_share: 0.5,
                });
            }
        }
        for i in (0..n).step_by(7) {
            child_of(
                &mut set,
                at(1, i),
                at(2, i + 2),
                at(1, i + n - 1),
                at(1, i + 1),
            );
        }
        let movable: Vec<bool> = (0..3 * n).map(|g| g >= n).collect();
        let scale = vec![0.004; 3 * n];
        (pos, movable, scale, set)
    }

    #[test]
    fn two_threads_solve_to_the_same_bits_as_one() {
        let (pos, movable, scale, set) = big_ring(3000);
        let params = SpringParams::default();
        let solver = crate::SolverParams::default();
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let model = SpringField2d::new(&set, &params, pos.len());
                assert_eq!(model.halves.is_some(), threads > 1);
                let mut x = pos.clone();
                let outcome =
                    crate::solve_model_active(&mut x, &scale, &movable, &model, &solver).unwrap();
                // made beside the influence table, or by the first assembly in halves
                let made = model.halves.as_ref().and_then(OnceLock::get).is_some();
                assert_eq!(made, threads > 1);
                (x, outcome)
            })
        };
        let (one, one_outcome) = run(1);
        let (two, two_outcome) = run(2);
        assert!(one_outcome.iterations > 10);
        assert_eq!(one_outcome, two_outcome);
        assert!(
            one.iter()
                .zip(&two)
                .all(|(a, b)| a[0].to_bits() == b[0].to_bits() && a[1].to_bits() == b[1].to_bits())
        );
    }

    #[test]
    fn the_halves_keep_every_spring_whole_and_split_the_nodes_about_evenly() {
        let (pos, _, _, set) = big_ring(3000);
        let half = Halves::new(&set, pos.len()).half;
        for s in &set.extrusion {
            assert_eq!(half[s.lower as usize], half[s.upper as usize]);
        }
        for s in &set.angle {
            assert_eq!(half[s.centre as usize], half[s.child as usize]);
        }
        let ones = half.iter().filter(|&&h| h == 1).count();
        assert!(
            ones > pos.len() / 3 && ones < 2 * pos.len() / 3,
            "{ones} of {}",
            pos.len()
        );
    }

    proptest::proptest! {
        /// The assembly in halves gives every active node the forces and stiffnesses of the
        /// sequential one, to the last bit, whichever nodes are active: added to zeroed
        /// arrays, or set over whatever the arrays held.
        #[test]
        fn the_assembly_in_halves_matches_the_sequential_one_to_the_bit(
            active_mod in 1usize..5,
            offset in 0usize..5,
        ) {
            let (x, _, _, set) = big_ring(3000);
            let params = SpringParams::default();
            let n = x.len();
            let index = set.index(n);
            let flags: Vec<bool> = (0..n).map(|i| i >= 3000 && (i + offset) % active_mod == 0).collect();
            let nodes: Vec<u32> = (0..n as u32).rev().filter(|&i| flags[i as usize]).collect();
            let active = crate::Active { flags: &flags, nodes: &nodes };
            let (mut f, mut s) = (vec![[0.0; 2]; n], vec![0.0; n]);
            assemble_2d_active(&set, &index, &params, &x, active, &mut f, &mut s);
            let eval = ActiveEval { set: &set, index: &index, params: &params, positions: &x, flags: &flags };
            let half = Halves::new(&set, n).half;
            for (start, sums) in [(0.0, Sums::Add), (7.5, Sums::Set)] {
                let (mut f2, mut s2) = (vec![[start; 2]; n], vec![start; n]);
                eval.in_halves(&half, &nodes, (&mut f2, &mut s2), sums);
                for &i in &nodes {
                    let i = i as usize;
                    proptest::prop_assert_eq!(f[i][0].to_bits(), f2[i][0].to_bits());
                    proptest::prop_assert_eq!(f[i][1].to_bits(), f2[i][1].to_bits());
                    proptest::prop_assert_eq!(s[i].to_bits(), s2[i].to_bits());
                }
            }
        }
    }

    proptest::proptest! {
        /// The index lists for each node the springs that push it, in the order they are
        /// met kind by kind (a stable sort by node of every push), nodes past `n` left out.
        #[test]
        fn the_index_is_a_stable_sort_of_the_pushes_by_node(
            nodes in 8usize..200,
            cut in 0usize..6,
        ) {
            let (positions, _, _, set) = big_ring(nodes);
            let n = positions.len().saturating_sub(cut);
            let mut pushes: Vec<(u32, u32)> = Vec::new();
            for (i, e) in set.extrusion.iter().enumerate() {
                pushes.extend([(e.upper, i as u32), (e.lower, i as u32)]);
            }
            for (i, e) in set.neighbour.iter().enumerate() {
                pushes.push((e.centre, (1 << KIND_SHIFT) | i as u32));
            }
            for (i, e) in set.angle.iter().enumerate() {
                let id = (2 << KIND_SHIFT) | i as u32;
                pushes.extend([(e.child, id), (e.centre, id)]);
            }
            pushes.retain(|&(node, _)| (node as usize) < n);
            pushes.sort_by_key(|&(node, _)| node);
            let index = set.index(n);
            proptest::prop_assert_eq!(index.offsets.len(), n + 1);
            for node in 0..n {
                let want: Vec<u32> =
                    pushes.iter().filter(|p| p.0 as usize == node).map(|p| p.1).collect();
                let got = &index.springs[index.offsets[node] as usize..index.offsets[node + 1] as usize];
                proptest::prop_assert_eq!(got, &want[..]);
            }
        }
    }

    /// The influence table from the (pushed, read) pairs of every spring, the plain way.
    fn influence_by_pairs(set: &SpringSet2d, n: usize) -> crate::Influence {
        let mut pairs = Vec::new();
        crate::model::influence_pairs::<2, _>(&set.extrusion, &mut pairs);
        crate::model::influence_pairs(&set.neighbour, &mut pairs);
        crate::model::influence_pairs(&set.angle, &mut pairs);
        crate::Influence::from_pairs(n, pairs)
    }

    proptest::proptest! {
        /// The influence table walked from the spring index is the table of the pairs, row for
        /// row, whatever springs are dropped or made degenerate (a node named twice), and over
        /// fewer nodes than the springs name.
        #[test]
        fn the_influence_table_from_the_index_is_that_of_the_pairs(
            drop_mod in 2usize..9,
            degenerate_mod in 3usize..13,
            cut in 0usize..200,
        ) {
            let (x, _, _, mut set) = big_ring(150);
            let keep = |k: usize| k % drop_mod != 1;
            let mut k = 0;
            set.extrusion.retain(|_| { k += 1; keep(k) });
            set.neighbour.retain(|_| { k += 1; keep(k) });
            set.angle.retain(|_| { k += 1; keep(k) });
            for (k, s) in set.angle.iter_mut().enumerate().filter(|(k, _)| k % degenerate_mod == 0) {
                if k % 2 == 0 { s.left = s.child } else { s.right = s.centre }
            }
            for (_, s) in set.extrusion.iter_mut().enumerate().filter(|(k, _)| k % degenerate_mod == 1) {
                s.lower = s.upper;
            }
            for n in [x.len(), x.len() - cut] {
                let fast = SpringField2d::new(&set, &SpringParams::default(), n).influence(n);
                proptest::prop_assert_eq!(&fast, &influence_by_pairs(&set, n));
                proptest::prop_assert_eq!(&set.influence(n), &fast);
            }
        }
    }

    #[test]
    fn bisector_of_a_right_angle_corner() {
        // A → K → B turning left (the region on the left is the inside of the corner)
        let s = bisector([0.0, -1.0], [0.0, 0.0], [-1.0, 0.0]).unwrap();
        let r = std::f64::consts::FRAC_1_SQRT_2;
        assert!(
            (s[0] + r).abs() < 1e-12 && (s[1] + r).abs() < 1e-12,
            "{s:?}"
        );
    }
}
