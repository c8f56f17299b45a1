//! The boundary groups of a 3D mesh: one per patch of its wall surface, then `outer` (the
//! final front; `farfield` once a fill reaches a far field). A surface read from a file gets a
//! patch per group the file gives (an STL's solids, a `.msh`'s physical surfaces:
//! `mesh_io::stl::GroupedSurface`), named as 2D names its walls (`case::wall_group_name`:
//! identifiers, unique; an unnamed solid is `wall`, `wall_2`, …), and an unnamed group holding
//! several closed bodies (a binary STL of two spheres) a patch per body; the built-in surfaces bring their own (`wall`; the wing's `wall`, `tip-root`
//! and `tip-far`). The cut mesh's wall facets are put back in their surface facet's patch
//! ([`wall_groups`]), so the `.msh` physical groups, `.vtu` `boundary_group` and SU2 markers
//! follow the surface's patches.

use geom_surface::{Facet, Surface};
use mesh_io::stl::GroupedSurface;
use mesh_model::{Mesh, Patch, Role};

use crate::case::wall_group_name;
use crate::error::{Result, input_error};

/// The wall surface of a file's triangles, a patch per group, named as boundary groups (an
/// unnamed group is `wall`). Not checked: call [`Surface::check`].
pub fn surface_of_file(mut read: GroupedSurface) -> Surface {
    split_unnamed_bodies(&mut read);
    let mut taken: Vec<String> = vec![
        Role::Farfield.name().into(),
        "fluid".into(),
        OUTER_GROUP.into(),
    ];
    let patches = read
        .groups
        .into_iter()
        .map(|g| {
            // a group named `farfield` keeps its role (and its name): afsf3d refuses it
            let name = match (g.role, g.name.as_str()) {
                (Role::Farfield, _) => g.name,
                (Role::Wall, "") => wall_group_name(Role::Wall.name(), &mut taken),
                (Role::Wall, name) => wall_group_name(name, &mut taken),
            };
            Patch { name, role: g.role }
        })
        .collect();
    Surface {
        nodes: read.nodes,
        facets: read
            .triangles
            .iter()
            .map(|t| Facet::tri(t[0], t[1], t[2]))
            .collect(),
        facet_patch: read.triangle_group,
        patches,
    }
}

/// Each unnamed group (`""`) of `read` that holds several bodies (components joined by no
/// node) becomes one group per body, in the order of their first triangles: several closed
/// components of one STL are several bodies, each its own boundary group (`wall`, `wall_2`,
/// …). Named groups stay whole: solids given one name share their group.
fn split_unnamed_bodies(read: &mut GroupedSurface) {
    let n = read.nodes.len();
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn root(parent: &mut [u32], mut v: u32) -> u32 {
        while parent[v as usize] != v {
            let up = parent[parent[v as usize] as usize];
            parent[v as usize] = up;
            v = up;
        }
        v
    }
    for t in &read.triangles {
        for i in 1..3 {
            let (a, b) = (root(&mut parent, t[0]), root(&mut parent, t[i]));
            parent[a.max(b) as usize] = a.min(b);
        }
    }
    // (group, body root) → new group, the first body of a group keeping it
    let mut seen: std::collections::HashMap<(u32, u32), u32> = std::collections::HashMap::new();
    let mut first_body: std::collections::HashMap<u32, u32> = std::collections::HashMap::new();
    for (t, g) in read.triangles.iter().zip(read.triangle_group.iter_mut()) {
        let group = &read.groups[*g as usize];
        if !(group.name.is_empty() && group.role == Role::Wall) {
            continue;
        }
        let body = root(&mut parent, t[0]);
        let first = *first_body.entry(*g).or_insert(body);
        if body == first {
            continue;
        }
        let new = *seen.entry((*g, body)).or_insert_with(|| {
            read.groups.push(Patch {
                name: String::new(),
                role: Role::Wall,
            });
            (read.groups.len() - 1) as u32
        });
        *g = new;
    }
}

/// The boundary group of a near-body mesh's outer boundary, the layers' final front
/// ([`mesh_model::OUTER_GROUP`]); a fill to a far field renames it `farfield` (`fill3d`).
pub use mesh_model::OUTER_GROUP;

/// Puts every wall facet of `mesh` (cut from the layers grown from `surface`, whose nodes
/// are the mesh's first) in the patch of the surface facet it lies on, and the outer
/// facets (the final front) in a last patch [`OUTER_GROUP`] of role far field: the mesh's
/// patches become the surface's, then that one.
pub fn wall_groups(surface: &Surface, mesh: &mut Mesh) -> Result<()> {
    let facets_at = facets_at_nodes(surface);
    let far = surface.patches.len() as u32;
    for (i, (f, p)) in mesh
        .boundary
        .iter()
        .zip(mesh.boundary_patch.iter_mut())
        .enumerate()
    {
        if mesh.patches.get(*p as usize).map(|q| q.role) != Some(Role::Wall) {
            *p = far;
            continue;
        }
        // a wall facet is a surface facet or part of one (a quad cut in two triangles)
        let k = f.corners();
        let under = facets_at
            .get(k[0] as usize)
            .into_iter()
            .flatten()
            .find(|&&s| {
                let nodes = surface.facets[s as usize].nodes();
                k.iter().all(|v| nodes.contains(v))
            });
        let Some(&s) = under else {
            return Err(input_error!(
                "the mesh's wall facet {i} lies on no facet of the wall surface"
            ));
        };
        *p = surface.facet_patch[s as usize];
    }
    mesh.patches = surface.patches.clone();
    mesh.patches.push(Patch {
        name: OUTER_GROUP.into(),
        role: Role::Farfield,
    });
    Ok(())
}

/// The facets around each node of `surface`.
fn facets_at_nodes(surface: &Surface) -> Vec<Vec<u32>> {
    let mut at = vec![Vec::new(); surface.nodes.len()];
    for (i, f) in surface.facets.iter().enumerate() {
        for &v in f.nodes() {
            at[v as usize].push(i as u32);
        }
    }
    at
}

#[cfg(test)]
mod tests {
    use super::*;

    fn patch(name: &str, role: Role) -> Patch {
        Patch {
            name: name.into(),
            role,
        }
    }

    fn names(s: &Surface) -> Vec<&str> {
        s.patches.iter().map(|p| p.name.as_str()).collect()
    }

    /// The unit tetrahedron's surface, its facets in `groups`.
    fn tet(groups: Vec<Patch>, triangle_group: Vec<u32>) -> GroupedSurface {
        GroupedSurface {
            nodes: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
            ],
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
            triangle_group,
            groups,
        }
    }

    /// Two tetrahedra apart in one unnamed group are two bodies, `wall` and `wall_2`; named
    /// alike they stay one group.
    #[test]
    fn an_unnamed_group_of_two_bodies_is_two_groups() {
        let mut read = tet(vec![patch("", Role::Wall)], vec![0; 4]);
        let far: Vec<[f64; 3]> = read
            .nodes
            .iter()
            .map(|p| [p[0] + 5.0, p[1], p[2]])
            .collect();
        read.nodes.extend(far);
        let more: Vec<[u32; 3]> = read.triangles.iter().map(|t| t.map(|v| v + 4)).collect();
        read.triangles.extend(more);
        read.triangle_group.extend([0; 4]);
        let mut named = read.clone();
        let s = surface_of_file(read);
        assert_eq!(names(&s), ["wall", "wall_2"]);
        assert_eq!(s.facet_patch, [0, 0, 0, 0, 1, 1, 1, 1]);
        assert_eq!(s.check(), Ok(()));
        named.groups[0].name = "pods".into();
        assert_eq!(names(&surface_of_file(named)), ["pods"]);
    }

    #[test]
    fn file_groups_become_identifier_patches_and_unnamed_ones_walls() {
        let read = tet(
            vec![
                patch("upper part", Role::Wall),
                patch("", Role::Wall),
                patch("fluid", Role::Wall),
                patch("", Role::Wall),
            ],
            vec![0, 1, 2, 3],
        );
        let s = surface_of_file(read);
        assert_eq!(names(&s), ["upper_part", "wall", "fluid_2", "wall_2"]);
        assert_eq!(s.facet_patch, [0, 1, 2, 3]);
        assert_eq!(s.check(), Ok(()));
    }

    #[test]
    fn wall_facets_take_their_surface_facets_patch() {
        use mesh_model::{CellType, Dim, Shape};
        // a cube of quads in two patches; the mesh's wall: one quad kept, one cut in two
        let mut s = Surface::cube(1.0, 1, false);
        s.patches.push(patch("top", Role::Wall));
        s.facet_patch[5] = 1;
        let mut mesh = Mesh::new(Dim::Three, 1);
        mesh.nodes = s.nodes.clone();
        mesh.nodes.push([9.0; 3]);
        let (a, b) = (s.facets[0].0, s.facets[5].0);
        mesh.boundary.push(CellType::new(Shape::Quad, 1), &a);
        mesh.boundary
            .push(CellType::new(Shape::Tri, 1), &[b[0], b[1], b[2]]);
        mesh.boundary
            .push(CellType::new(Shape::Tri, 1), &[b[0], b[2], b[3]]);
        mesh.boundary
            .push(CellType::new(Shape::Tri, 1), &[8, b[0], b[1]]);
        mesh.boundary_patch = vec![0, 0, 0, 1];
        mesh.patches = vec![patch("wall", Role::Wall), patch("farfield", Role::Farfield)];
        wall_groups(&s, &mut mesh).unwrap();
        assert_eq!(mesh.boundary_patch, [0, 1, 1, 2]);
        let got: Vec<(&str, Role)> = mesh
            .patches
            .iter()
            .map(|p| (p.name.as_str(), p.role))
            .collect();
        assert_eq!(
            got,
            [
                ("wall", Role::Wall),
                ("top", Role::Wall),
                ("outer", Role::Farfield)
            ]
        );
        // a wall facet on no surface facet is an error, not a guess
        mesh.boundary_patch[3] = 0;
        assert!(wall_groups(&s, &mut mesh).is_err());
    }
}
