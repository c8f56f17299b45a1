//! Boundary groups: the named sets of boundary facets that a solver sees (Gmsh physical groups
//! of dimension `d − 1`, SU2 markers). Every wall patch is its own group, named after the
//! patch (`slat`, `main`, `flap`); patches of one name share a group, so wall patches all
//! named `wall` make one `wall` group. Far-field patches make one group named `farfield`.
//! A wall patch with no name is in a group `wall`.

use mesh_model::{Mesh, Role};

/// One boundary group.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Group {
    /// The group's name.
    pub name: String,
    /// The role of its patches.
    pub role: Role,
}

/// The boundary groups of `mesh`, in the order of their first patch, and the group of each
/// patch. Errors with a message when a wall patch is named like the far-field group or the
/// domain's group `fluid`.
pub fn boundary_groups(mesh: &Mesh) -> Result<(Vec<Group>, Vec<usize>), String> {
    let mut groups: Vec<Group> = Vec::new();
    let mut of_patch = Vec::with_capacity(mesh.patches.len());
    for (i, p) in mesh.patches.iter().enumerate() {
        // every far-field patch is `farfield` but a 3D near-body mesh's outer boundary
        // (`outer`); a wall its own name, else `wall`
        let name = match p.role {
            Role::Farfield if p.name == mesh_model::OUTER_GROUP => mesh_model::OUTER_GROUP,
            Role::Farfield => Role::Farfield.name(),
            Role::Wall if p.name.is_empty() => Role::Wall.name(),
            Role::Wall => p.name.as_str(),
        };
        if p.role == Role::Wall
            && (name.eq_ignore_ascii_case(Role::Farfield.name())
                || name.eq_ignore_ascii_case(crate::msh::FLUID_GROUP))
        {
            return Err(format!(
                "wall patch {i} is named {name:?}, the name of another group: rename it"
            ));
        }
        let k = match groups.iter().position(|g| g.name == name) {
            Some(k) if groups[k].role != p.role => {
                return Err(format!(
                    "patch {i} is named {name:?}, the name of a group of another role: rename it"
                ));
            }
            Some(k) => k,
            None => {
                groups.push(Group {
                    name: name.to_string(),
                    role: p.role,
                });
                groups.len() - 1
            }
        };
        of_patch.push(k);
    }
    Ok((groups, of_patch))
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_model::{Dim, Patch};

    fn mesh(patches: &[(&str, Role)]) -> Mesh {
        let mut m = Mesh::new(Dim::Two, 1);
        m.patches = patches
            .iter()
            .map(|&(name, role)| Patch {
                name: name.into(),
                role,
            })
            .collect();
        m
    }

    #[test]
    fn each_wall_is_a_group_and_the_far_field_is_one() {
        let m = mesh(&[
            ("slat", Role::Wall),
            ("main", Role::Wall),
            ("flap", Role::Wall),
            ("circle", Role::Farfield),
            ("", Role::Farfield),
        ]);
        let (g, of) = boundary_groups(&m).unwrap();
        let names: Vec<&str> = g.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, ["slat", "main", "flap", "farfield"]);
        assert_eq!(of, [0, 1, 2, 3, 3]);
        // but a 3D near-body mesh's outer boundary keeps its name
        let (g, _) =
            boundary_groups(&mesh(&[("wall", Role::Wall), ("outer", Role::Farfield)])).unwrap();
        assert_eq!(g[1].name, "outer");
        assert_eq!(g[1].role, Role::Farfield);
        // one name for two roles is refused
        assert!(
            boundary_groups(&mesh(&[("outer", Role::Wall), ("outer", Role::Farfield)])).is_err()
        );
    }

    #[test]
    fn walls_of_one_name_share_a_group() {
        let m = mesh(&[
            ("wall", Role::Wall),
            ("farfield", Role::Farfield),
            ("wall", Role::Wall),
        ]);
        let (g, of) = boundary_groups(&m).unwrap();
        assert_eq!(g.len(), 2);
        assert_eq!(of, [0, 1, 0]);
        assert!(boundary_groups(&mesh(&[("farfield", Role::Wall)])).is_err());
        assert!(boundary_groups(&mesh(&[("fluid", Role::Wall)])).is_err());
    }
}
