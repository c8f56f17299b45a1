//! The 3D spring set of the dissertation (§5.2.2): the extrusion spring (the generic
//! [`ExtrusionSpring`], shared with 2D), the neighbour spring weighted by the areas of the two
//! front facets beside an edge, the angle spring with f(a) = 8a³ + 0.2a, and the tension
//! spring (ideal length 0.9 × its length after the first balance), each a [`Spring<3>`],
//! gathered in a [`SpringSet3d`] whose [`SpringField3d`] is the [`ForceModel<3>`] that
//! [`crate::solve_model`] balances.
//!
//! Units follow [`crate::springs`]: each force is dimensionless (the dissertation's force
//! divided by its "distance measure", the ideal extrusion length), and each spring adds a
//! stiffness S such that F/S is the move that would satisfy it alone.
//!
//! Coefficients ([`SpringParams3d`], the dissertation's values): K_extru = 2, K_nei = 0.25,
//! K_ang = 1, K_tension = 0.25, C_percent = 0.5. The neighbour, angle and extrusion
//! coefficients travel in a [`SpringParams`] ([`SpringParams3d::core`]); the tension
//! coefficient and C_aniso are folded into each [`TensionSpring`]'s `strength` when the
//! mesher makes it (its l_charac is the longest front edge at either end, fixed then).

use crate::model::{FiniteDifference, ForceModel, Spring, Triplet, influence_pairs, jacobian_of};
use crate::params::SpringParams;
use crate::springs::ExtrusionSpring;

/// The coefficients of the 3D springs (defaults: the dissertation's, §5.4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringParams3d {
    /// K_extru. Default 2.
    pub k_extrusion: f64,
    /// K_nei. Default 0.25.
    pub k_neighbour: f64,
    /// K_ang. Default 1.
    pub k_angle: f64,
    /// K_tension. Default 0.25.
    pub k_tension: f64,
    /// C_percent: the share of the angle force on the child (the parent gets the rest).
    /// Default 0.5.
    pub c_percent: f64,
    /// Ideal length of a tension spring over its length after the first balance. Default 0.9.
    pub tension_ratio: f64,
}

impl Default for SpringParams3d {
    fn default() -> Self {
        SpringParams3d {
            k_extrusion: 2.0,
            k_neighbour: 0.25,
            k_angle: 1.0,
            k_tension: 0.25,
            c_percent: 0.5,
            tension_ratio: 0.9,
        }
    }
}

impl SpringParams3d {
    /// The coefficients as the core's [`SpringParams`] (what [`Spring::add_force`] reads).
    pub fn core(&self) -> SpringParams {
        SpringParams {
            k_extrusion: self.k_extrusion,
            k_neighbour: self.k_neighbour,
            k_angle: self.k_angle,
            c_percent: self.c_percent,
            ..SpringParams::default()
        }
    }
}

/// Neighbour spring on the front edge Q–P (§5.2.2, Fig. 56): pushes the edge, within the
/// front, towards the larger of its two facets until their altitudes from the edge are
/// equal: F = K_nei·C_aniso·(h₁û₁ + h₂û₂)/(h₁ + h₂) on both P and Q, with ûᵢ the unit altitude
/// from the edge's line to the far side of facet i (its opposite node for a triangle, the
/// midpoint of its opposite edge for a quad), hᵢ its length, and
/// C_aniso = min(1, 2·L/(h₁ + h₂)) (L: the ideal extrusion length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeighbourSpring3d {
    /// Q and P, the edge's nodes.
    pub edge: [u32; 2],
    /// The far side of the first facet: its opposite node twice, or its opposite edge.
    pub far1: [u32; 2],
    /// The far side of the second facet.
    pub far2: [u32; 2],
    /// L, the ideal extrusion length at the edge.
    pub extrusion_length: f64,
}

/// Angle spring (§5.2.2, Fig. 57): keeps the extrusion edge P → A along the ideal direction;
/// F = K_ang·f(sin α), f(a) = 8a³ + 0.2a, at right angles to PA in the plane of PA and the
/// ideal direction, the share C_percent on A towards the ideal, the rest on P the other way.
/// Beyond 90° sin α is taken as 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngleSpring3d {
    /// P, the parent.
    pub parent: u32,
    /// A, the child.
    pub child: u32,
    /// The ideal direction (unit).
    pub direction: [f64; 3],
}

/// Tension spring on the front edge Q–P (§5.2.2): F = strength·(l_ideal − l)·(P − Q)/l on P
/// and the opposite on Q, strength = K_tension·C_aniso·L/l_charac with C_aniso =
/// L/l_charac (L: the ideal extrusion length, l_charac: the longest front edge at P or Q,
/// both when the spring is made), and l_ideal = 0.9 × its length after the first balance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TensionSpring {
    /// Q and P.
    pub edge: [u32; 2],
    /// l_ideal.
    pub ideal_length: f64,
    /// K_tension·C_aniso/l_charac (per unit length).
    pub strength: f64,
}

impl TensionSpring {
    /// The tension spring of edge Q–P of current length `length`, with ideal extrusion
    /// length `extrusion_length` and characteristic length `l_charac`.
    pub fn new(
        edge: [u32; 2],
        length: f64,
        extrusion_length: f64,
        l_charac: f64,
        params: &SpringParams3d,
    ) -> Self {
        let c_aniso = (extrusion_length / l_charac).min(1.0);
        TensionSpring {
            edge,
            ideal_length: params.tension_ratio * length,
            strength: params.k_tension * c_aniso / l_charac,
        }
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|d| a[d] - b[d])
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn add_scaled(f: &mut [f64; 3], s: f64, v: [f64; 3]) {
    (0..3).for_each(|d| f[d] += s * v[d]);
}

/// The altitude vector from the line through `q`, `p` to `m`.
fn altitude(q: [f64; 3], p: [f64; 3], m: [f64; 3]) -> [f64; 3] {
    let e = sub(p, q);
    let ee = dot(e, e);
    let w = sub(m, q);
    let t = if ee > 0.0 { dot(w, e) / ee } else { 0.0 };
    std::array::from_fn(|d| w[d] - t * e[d])
}

fn neighbour_force(
    s: &NeighbourSpring3d,
    params: &SpringParams,
    x: &[[f64; 3]],
    force: &mut [[f64; 3]],
    stiffness: &mut [f64],
) {
    let [q, p] = s.edge.map(|v| x[v as usize]);
    let mid = |f: [u32; 2]| -> [f64; 3] {
        let (a, b) = (x[f[0] as usize], x[f[1] as usize]);
        std::array::from_fn(|d| (a[d] + b[d]) / 2.0)
    };
    let (u1, u2) = (altitude(q, p, mid(s.far1)), altitude(q, p, mid(s.far2)));
    let (h1, h2) = (dot(u1, u1).sqrt(), dot(u2, u2).sqrt());
    if !(h1 > 0.0 && h2 > 0.0) {
        return;
    }
    let c_aniso = (2.0 * s.extrusion_length / (h1 + h2)).min(1.0);
    let k = params.k_neighbour * c_aniso;
    // (h₁û₁ + h₂û₂)/(h₁ + h₂) = (u₁ + u₂)/(h₁ + h₂)
    let f: [f64; 3] = std::array::from_fn(|d| k * (u1[d] + u2[d]) / (h1 + h2));
    for v in s.edge {
        add_scaled(&mut force[v as usize], 1.0, f);
        stiffness[v as usize] += k * 2.0 / (h1 + h2);
    }
}

fn angle_force(
    s: &AngleSpring3d,
    params: &SpringParams,
    x: &[[f64; 3]],
    force: &mut [[f64; 3]],
    stiffness: &mut [f64],
) {
    let v = sub(x[s.child as usize], x[s.parent as usize]);
    let len = dot(v, v).sqrt();
    if len <= 0.0 {
        return;
    }
    let u = v.map(|c| c / len);
    let d = s.direction;
    // towards the ideal direction, at right angles to PA
    let w: [f64; 3] = std::array::from_fn(|k| d[k] - dot(d, u) * u[k]);
    let wl = dot(w, w).sqrt();
    if wl <= 0.0 {
        return;
    }
    let sin = if dot(d, u) >= 0.0 {
        dot(cross(d, u), cross(d, u)).sqrt().min(1.0)
    } else {
        1.0
    };
    let f = params.k_angle * (8.0 * sin * sin * sin + 0.2 * sin);
    // F/S = len·sin α, the move that turns PA onto the ideal direction
    let k = params.k_angle * (8.0 * sin * sin + 0.2) / len;
    let share = params.c_percent;
    add_scaled(&mut force[s.child as usize], share * f / wl, w);
    stiffness[s.child as usize] += share * k;
    add_scaled(&mut force[s.parent as usize], -(1.0 - share) * f / wl, w);
    stiffness[s.parent as usize] += (1.0 - share) * k;
}

fn tension_force(
    s: &TensionSpring,
    _params: &SpringParams,
    x: &[[f64; 3]],
    force: &mut [[f64; 3]],
    stiffness: &mut [f64],
) {
    let [q, p] = s.edge;
    let e = sub(x[p as usize], x[q as usize]);
    let len = dot(e, e).sqrt();
    if len <= 0.0 {
        return;
    }
    let f = s.strength * (s.ideal_length - len) / len;
    add_scaled(&mut force[p as usize], f, e);
    add_scaled(&mut force[q as usize], -f, e);
    stiffness[p as usize] += s.strength;
    stiffness[q as usize] += s.strength;
}

/// A spring's node field: one node or several.
trait Nodes {
    fn push_to(&self, out: &mut Vec<u32>);
}

impl Nodes for u32 {
    fn push_to(&self, out: &mut Vec<u32>) {
        out.push(*self);
    }
}

impl<const N: usize> Nodes for [u32; N] {
    fn push_to(&self, out: &mut Vec<u32>) {
        out.extend_from_slice(self);
    }
}

/// The `Spring<3>` impl of a 3D spring kind: the nodes it reads and pushes, and its force.
macro_rules! spring_3d {
    ($kind:ty, $force:ident, reads: [$($r:ident),*], pushes: [$($p:ident),*]) => {
        impl Spring<3> for $kind {
            fn reads(&self, out: &mut Vec<u32>) {
                $(Nodes::push_to(&self.$r, out);)*
            }

            fn pushes(&self, out: &mut Vec<u32>) {
                $(Nodes::push_to(&self.$p, out);)*
            }

            fn add_force(
                &self,
                params: &SpringParams,
                x: &[[f64; 3]],
                force: &mut [[f64; 3]],
                stiffness: &mut [f64],
            ) {
                $force(self, params, x, force, stiffness);
            }
        }
    };
}

spring_3d!(NeighbourSpring3d, neighbour_force, reads: [edge, far1, far2], pushes: [edge]);
spring_3d!(AngleSpring3d, angle_force, reads: [parent, child], pushes: [child, parent]);
spring_3d!(TensionSpring, tension_force, reads: [edge], pushes: [edge]);

/// All springs of one 3D solve, indexed into the solver's position array.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SpringSet3d {
    /// Extrusion (parent–child) springs, the same type as in 2D.
    pub extrusion: Vec<ExtrusionSpring>,
    /// Neighbour springs (one per front edge between two facets).
    pub neighbour: Vec<NeighbourSpring3d>,
    /// Angle springs (one per extrusion edge).
    pub angle: Vec<AngleSpring3d>,
    /// Tension springs (one per front edge, made after the first balance).
    pub tension: Vec<TensionSpring>,
}

/// A [`SpringSet3d`] bound to its coefficients: the [`ForceModel<3>`] of the 3D mesher.
#[derive(Debug, Clone)]
pub struct SpringField3d<'a> {
    set: &'a SpringSet3d,
    params: SpringParams,
}

impl<'a> SpringField3d<'a> {
    /// Binds `set` to `params`.
    pub fn new(set: &'a SpringSet3d, params: &SpringParams3d) -> Self {
        SpringField3d {
            set,
            params: params.core(),
        }
    }
}

fn add_all<S: Spring<3>>(
    springs: &[S],
    params: &SpringParams,
    x: &[[f64; 3]],
    force: &mut [[f64; 3]],
    stiffness: &mut [f64],
) {
    for s in springs {
        s.add_force(params, x, force, stiffness);
    }
}

impl ForceModel<3> for SpringField3d<'_> {
    fn assemble(&self, x: &[[f64; 3]], force: &mut [[f64; 3]], stiffness: &mut [f64]) {
        let p = &self.params;
        add_all(&self.set.extrusion, p, x, force, stiffness);
        add_all(&self.set.neighbour, p, x, force, stiffness);
        add_all(&self.set.angle, p, x, force, stiffness);
        add_all(&self.set.tension, p, x, force, stiffness);
    }

    fn influence(&self, n: usize) -> crate::Influence {
        let mut pairs = Vec::new();
        influence_pairs::<3, _>(&self.set.extrusion, &mut pairs);
        influence_pairs(&self.set.neighbour, &mut pairs);
        influence_pairs(&self.set.angle, &mut pairs);
        influence_pairs(&self.set.tension, &mut pairs);
        crate::Influence::from_pairs(n, pairs)
    }

    fn jacobian(&self, x: &[[f64; 3]], movable: &[bool], out: &mut Vec<Triplet>) {
        let mut fd = FiniteDifference::new(x);
        let p = &self.params;
        jacobian_of(&self.set.extrusion, p, movable, &mut fd, out);
        jacobian_of(&self.set.neighbour, p, movable, &mut fd, out);
        jacobian_of(&self.set.angle, p, movable, &mut fd, out);
        jacobian_of(&self.set.tension, p, movable, &mut fd, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A 3×3 grid of fixed parents (spacing 1) at z = 0 and their children at z = `l`, with the
    /// children's 2×2 quads as the front: every spring of the 3D set, at its ideal.
    fn grid(l: f64, jitter: &[f64]) -> (Vec<[f64; 3]>, SpringSet3d) {
        let mut x = Vec::new();
        for layer in 0..2 {
            for j in 0..3 {
                for i in 0..3 {
                    x.push([i as f64, j as f64, layer as f64 * l]);
                }
            }
        }
        for (k, c) in jitter.chunks(3).enumerate() {
            (0..3).for_each(|d| x[9 + k][d] += c[d]);
        }
        let child = |i: u32, j: u32| 9 + 3 * j + i;
        let params = SpringParams3d::default();
        let mut set = SpringSet3d::default();
        for k in 0..9 {
            set.extrusion.push(ExtrusionSpring {
                lower: k,
                upper: k + 9,
                ideal_length: l,
                lower_share: 0.0,
            });
            set.angle.push(AngleSpring3d {
                parent: k,
                child: k + 9,
                direction: [0.0, 0.0, 1.0],
            });
        }
        // the four interior edges from the centre, each between two quads
        let c = child(1, 1);
        let quads = [
            ([c, child(2, 1)], [(1, 0), (2, 0)], [(1, 2), (2, 2)]),
            ([c, child(0, 1)], [(0, 0), (1, 0)], [(0, 2), (1, 2)]),
            ([c, child(1, 2)], [(0, 1), (0, 2)], [(2, 1), (2, 2)]),
            ([c, child(1, 0)], [(0, 0), (0, 1)], [(2, 0), (2, 1)]),
        ];
        for (edge, f1, f2) in quads {
            set.neighbour.push(NeighbourSpring3d {
                edge,
                far1: f1.map(|(i, j)| child(i, j)),
                far2: f2.map(|(i, j)| child(i, j)),
                extrusion_length: l,
            });
        }
        for [a, b] in [
            [c, child(2, 1)],
            [c, child(0, 1)],
            [c, child(1, 2)],
            [c, child(1, 0)],
        ] {
            set.tension.push(TensionSpring::new(
                [a, b],
                1.0 / params.tension_ratio,
                l,
                1.0,
                &params,
            ));
        }
        (x, set)
    }

    fn forces(set: &SpringSet3d, x: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let model = SpringField3d::new(set, &SpringParams3d::default());
        let mut f = vec![[0.0; 3]; x.len()];
        let mut s = vec![0.0; x.len()];
        model.assemble(x, &mut f, &mut s);
        f
    }

    #[test]
    fn every_force_vanishes_at_the_ideal_configuration() {
        let (x, set) = grid(0.3, &[]);
        for (i, f) in forces(&set, &x).iter().enumerate() {
            assert!(f.iter().all(|c| c.abs() < 1e-14), "node {i}: {f:?}");
        }
    }

    #[test]
    fn each_spring_pushes_back_towards_its_ideal() {
        // the centre child moved sideways (+x), up and the tension edge stretched
        let (mut x, set) = grid(0.3, &[]);
        x[13][0] += 0.1;
        let f = forces(&set, &x);
        assert!(f[13][0] < 0.0, "{:?}", f[13]);
        let (mut x, _) = grid(0.3, &[]);
        x[13][2] += 0.1;
        assert!(forces(&set, &x)[13][2] < 0.0);
    }

    #[test]
    fn the_balance_returns_to_the_ideal() {
        let jitter: Vec<f64> = (0..27).map(|k| 0.04 * ((k * 7 % 5) as f64 - 2.0)).collect();
        let (mut x, set) = grid(0.3, &jitter);
        let model = SpringField3d::new(&set, &SpringParams3d::default());
        let movable: Vec<bool> = (0..18).map(|i| i >= 9).collect();
        let solver = crate::SolverParams {
            max_iterations: 5000,
            tolerance: 1e-9,
            ..Default::default()
        };
        let out = crate::solve_model(&mut x, &[0.3; 18], &movable, &model, &solver).unwrap();
        assert!(out.converged, "{out:?}");
        let (ideal, _) = grid(0.3, &[]);
        for k in 9..18 {
            let d = (0..3)
                .map(|c| (x[k][c] - ideal[k][c]).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(d < 1e-5, "node {k}: {:?}", x[k]);
        }
    }

    proptest! {
        /// The model's Jacobian (per spring) equals the central difference of its whole
        /// assembly, away from the angle spring's switch at 90°.
        #[test]
        fn the_jacobian_matches_finite_differences(jitter in proptest::collection::vec(-0.08f64..0.08, 27)) {
            let (x, set) = grid(0.3, &jitter);
            let model = SpringField3d::new(&set, &SpringParams3d::default());
            let movable: Vec<bool> = (0..18).map(|i| i >= 9).collect();
            let mut t = Vec::new();
            model.jacobian(&x, &movable, &mut t);
            let n = 18 * 3;
            let mut sparse = vec![vec![0.0; n]; n];
            for e in &t {
                sparse[e.row as usize][e.col as usize] += e.value;
            }
            let h = 1e-6;
            for j in 9..18 {
                for b in 0..3 {
                    let mut p = x.clone();
                    p[j][b] += h;
                    let fp = forces(&set, &p);
                    p[j][b] -= 2.0 * h;
                    let fm = forces(&set, &p);
                    for i in 9..18 {
                        for a in 0..3 {
                            let whole = (fp[i][a] - fm[i][a]) / (2.0 * h);
                            let got = sparse[3 * i + a][3 * j + b];
                            prop_assert!((got - whole).abs() < 1e-4 * (1.0 + whole.abs()), "({i},{a})/({j},{b}): {got} vs {whole}");
                        }
                    }
                }
            }
        }
    }
}
