//! The outer boundary of a 3D domain: a box or a sphere, triangulated at a chosen size, its
//! triangles facing into the domain (the fluid is inside), one patch `farfield` of role
//! [`Role::Farfield`]. The volume fill (`tet-fill`) meshes the space between it and the layers'
//! final fronts; its triangles are never split, so their size is the fill's size at the far
//! field.

use crate::{Facet, Surface};
use mesh_model::{Patch, Role};

/// The shape of a far field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FarfieldShape {
    /// An axis-aligned box from `min` to `max`.
    Box {
        /// The lowest corner.
        min: [f64; 3],
        /// The highest corner.
        max: [f64; 3],
    },
    /// A sphere.
    Sphere {
        /// Its centre.
        center: [f64; 3],
        /// Its radius.
        radius: f64,
    },
}

impl FarfieldShape {
    /// The largest extent: the box's longest side, the sphere's diameter.
    pub fn extent(&self) -> f64 {
        match *self {
            FarfieldShape::Box { min, max } => (0..3).map(|d| max[d] - min[d]).fold(0.0, f64::max),
            FarfieldShape::Sphere { radius, .. } => 2.0 * radius,
        }
    }

    /// The volume it encloses (the sphere's exact volume, not its triangulation's).
    pub fn volume(&self) -> f64 {
        match *self {
            FarfieldShape::Box { min, max } => (0..3).map(|d| max[d] - min[d]).product(),
            FarfieldShape::Sphere { radius, .. } => {
                4.0 / 3.0 * std::f64::consts::PI * radius.powi(3)
            }
        }
    }

    /// The distance from `p` to the shape's boundary, positive inside, negative outside.
    pub fn depth(&self, p: [f64; 3]) -> f64 {
        match *self {
            FarfieldShape::Box { min, max } => (0..3)
                .map(|d| (p[d] - min[d]).min(max[d] - p[d]))
                .fold(f64::INFINITY, f64::min),
            FarfieldShape::Sphere { center, radius } => radius - crate::norm(crate::sub(p, center)),
        }
    }

    /// Whether the shape's numbers make a shape: finite, a positive radius, every `max`
    /// above its `min`; else what is wrong.
    pub fn problem(&self) -> Option<String> {
        match *self {
            FarfieldShape::Box { min, max } => {
                if min.iter().chain(&max).any(|x| !x.is_finite()) {
                    return Some("the box's corners must be finite numbers".into());
                }
                (0..3).find(|&d| max[d] <= min[d]).map(|d| {
                    let axis = ["x", "y", "z"][d];
                    format!(
                        "the box's max {axis} ({}) is not above its min ({})",
                        max[d], min[d]
                    )
                })
            }
            FarfieldShape::Sphere { center, radius } => {
                if center.iter().any(|x| !x.is_finite()) || !radius.is_finite() {
                    Some("the sphere's centre and radius must be finite numbers".into())
                } else if radius <= 0.0 {
                    Some(format!("the sphere's radius ({radius}) must be positive"))
                } else {
                    None
                }
            }
        }
    }
}

/// The most triangles a far-field surface is made of (a finer `size` is refused by the case).
pub const MAX_FARFIELD_TRIANGLES: usize = 2_000_000;

impl Surface {
    /// The far field `shape` triangulated with edges of about `size` (no longer than `size`
    /// on the box; on the sphere an icosphere refined until its edges are no longer), its
    /// triangles counter-clockwise seen from inside (facing the fluid), one patch `farfield`
    /// of role far field. `size` must be positive and the shape valid ([`FarfieldShape::problem`]).
    pub fn farfield(shape: &FarfieldShape, size: f64) -> Surface {
        let mut s = match *shape {
            FarfieldShape::Box { min, max } => box_surface(min, max, size),
            FarfieldShape::Sphere { center, radius } => {
                // the icosahedron's edge is 1.0515 r; each refinement halves it
                let mut refinement = 0;
                while 1.0515 * radius / f64::from(1u32 << refinement) > size && refinement < 8 {
                    refinement += 1;
                }
                let mut s = Surface::sphere(radius, refinement);
                for p in &mut s.nodes {
                    *p = std::array::from_fn(|d| p[d] + center[d]);
                }
                // facing in: the fluid is inside
                for f in &mut s.facets {
                    f.0.swap(1, 2);
                }
                s
            }
        };
        s.patches = vec![Patch {
            name: Role::Farfield.name().into(),
            role: Role::Farfield,
        }];
        s
    }
}

/// The box's six faces, each a grid of squares split into two triangles along alternating
/// diagonals (no node with only two triangles), `n[d]` divisions along axis `d` so that no
/// edge is longer than `size`; counter-clockwise seen from inside.
fn box_surface(min: [f64; 3], max: [f64; 3], size: f64) -> Surface {
    let n: [usize; 3] =
        std::array::from_fn(|d| (((max[d] - min[d]) / size).ceil() as usize).max(1));
    let mut index = std::collections::HashMap::new();
    let mut nodes: Vec<[f64; 3]> = Vec::new();
    let mut node = |g: [usize; 3]| -> u32 {
        *index.entry(g).or_insert_with(|| {
            nodes.push(std::array::from_fn(|d| {
                // the last grid line exactly on max, so the box's volume is exact
                if g[d] == n[d] {
                    max[d]
                } else {
                    min[d] + (max[d] - min[d]) * g[d] as f64 / n[d] as f64
                }
            }));
            (nodes.len() - 1) as u32
        })
    };
    let mut facets = Vec::new();
    for axis in 0..3 {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for side in [0, n[axis]] {
            for i in 0..n[u] {
                for j in 0..n[v] {
                    let at = |di: usize, dj: usize| {
                        let mut g = [0; 3];
                        g[axis] = side;
                        g[u] = i + di;
                        g[v] = j + dj;
                        g
                    };
                    let k = [at(0, 0), at(1, 0), at(1, 1), at(0, 1)].map(&mut node);
                    // (u, v, axis) is right-handed: (0,0),(1,0),(1,1) turns counter-clockwise
                    // seen from +axis, which faces in on the low side
                    let k = if side == 0 {
                        k
                    } else {
                        [k[0], k[3], k[2], k[1]]
                    };
                    if (i + j) % 2 == 0 {
                        facets.push(Facet::tri(k[0], k[1], k[2]));
                        facets.push(Facet::tri(k[0], k[2], k[3]));
                    } else {
                        facets.push(Facet::tri(k[0], k[1], k[3]));
                        facets.push(Facet::tri(k[1], k[2], k[3]));
                    }
                }
            }
        }
    }
    let facet_patch = vec![0; facets.len()];
    Surface {
        nodes,
        facets,
        facet_patch,
        patches: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The far field encloses a negative volume (it faces in) of the shape's size, is closed
    /// and manifold, and no edge is longer than the size asked for.
    #[test]
    fn box_and_sphere_face_in_at_their_size() {
        let shapes = [
            FarfieldShape::Box {
                min: [-1.0, -2.0, -0.5],
                max: [3.0, 2.0, 0.5],
            },
            FarfieldShape::Sphere {
                center: [1.0, 0.0, -1.0],
                radius: 2.0,
            },
        ];
        for shape in shapes {
            let s = Surface::farfield(&shape, 0.4);
            assert!(shape.problem().is_none());
            let v = -s.enclosed_volume();
            let exact = shape.volume();
            let tol = match shape {
                FarfieldShape::Box { .. } => 1e-12 * exact,
                FarfieldShape::Sphere { .. } => 0.05 * exact,
            };
            assert!((v - exact).abs() < tol, "{v} vs {exact}");
            // reversed, it is a valid closed outward surface
            let mut out = s.clone();
            for f in &mut out.facets {
                f.0.swap(1, 2);
            }
            out.patches[0].role = Role::Wall;
            out.check().unwrap();
            let longest = s
                .facets
                .iter()
                .flat_map(|f| {
                    let k = f.nodes().to_vec();
                    (0..3).map(move |i| (k[i], k[(i + 1) % 3]))
                })
                .map(|(a, b)| crate::norm(crate::sub(s.nodes[a as usize], s.nodes[b as usize])))
                .fold(0.0, f64::max);
            // (the box's squares' diagonals are √2 × their sides)
            assert!(longest <= 0.4 * 1.42, "{longest}");
            assert!(s.patches[0].role == Role::Farfield);
        }
    }

    #[test]
    fn depth_and_problems() {
        let b = FarfieldShape::Box {
            min: [0.0; 3],
            max: [2.0, 4.0, 6.0],
        };
        assert_eq!(b.depth([1.0, 1.0, 1.0]), 1.0);
        assert!(b.depth([3.0, 1.0, 1.0]) < 0.0);
        assert_eq!(b.extent(), 6.0);
        let bad = FarfieldShape::Box {
            min: [0.0; 3],
            max: [2.0, 0.0, 6.0],
        };
        assert!(bad.problem().unwrap().contains("max y"));
        let s = FarfieldShape::Sphere {
            center: [0.0; 3],
            radius: -1.0,
        };
        assert!(s.problem().unwrap().contains("positive"));
    }
}
