//! The properties every mesh of the pipeline must have, as assertions that name what failed:
//! structurally valid, covering the domain's area, boundary nodes on the geometry, every
//! curved cell certified valid.

use jacobian_check::{CertifyParams, MeshValidity};
use mesh_model::{Mesh, validate};

/// Asserts that `mesh` passes `mesh_model::validate` (conforming, every cell positive),
/// naming the count of problems and the first.
pub fn assert_valid(what: &str, mesh: &Mesh) {
    let problems = validate(mesh);
    assert!(
        problems.is_empty(),
        "{what}: {} problems, first: {}",
        problems.len(),
        problems[0]
    );
}

/// Asserts that `area` (of the cells, linear or integrated) is the domain's `domain` to a
/// relative `rel`; returns the relative error.
pub fn assert_area(what: &str, area: f64, domain: f64, rel: f64) -> f64 {
    let error = (area - domain).abs() / domain.abs();
    assert!(
        error <= rel,
        "{what}: area {area} vs domain {domain}: relative error {error:e} > {rel:e}"
    );
    error
}

/// Asserts that every node of every boundary facet (ends and high-order nodes) lies within
/// `tol` of the geometry of its patch, `distance(patch, point)`; returns the largest distance.
pub fn assert_boundary_on(
    what: &str,
    mesh: &Mesh,
    distance: impl Fn(usize, [f64; 2]) -> f64,
    tol: f64,
) -> f64 {
    let mut worst = 0.0f64;
    for (f, facet) in mesh.boundary.iter().enumerate() {
        let patch = mesh.boundary_patch[f] as usize;
        for &n in facet.nodes {
            let d = distance(patch, mesh.xy(n));
            assert!(
                d <= tol,
                "{what}: node {n} of boundary facet {f} is {d:e} off its geometry (> {tol:e})"
            );
            worst = worst.max(d);
        }
    }
    worst
}

/// Asserts that every cell of `mesh` is certified valid (`jacobian_check::check_mesh`: no
/// invalid cell, none undecided); returns the figures.
pub fn assert_certified(what: &str, mesh: &Mesh) -> MeshValidity {
    let v = jacobian_check::check_mesh(mesh, &CertifyParams::default())
        .unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(
        v.invalid_cells.is_empty() && v.undecided.is_empty(),
        "{what}: invalid cells {:?}, undecided {:?}",
        &v.invalid_cells[..v.invalid_cells.len().min(5)],
        &v.undecided[..v.undecided.len().min(5)]
    );
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_model::{CellType, Dim, Shape};

    fn square() -> Mesh {
        let mut m = Mesh::new(Dim::Two, 1);
        m.nodes = vec![[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]];
        m.cells.push(CellType::new(Shape::Quad, 1), &[0, 1, 2, 3]);
        let line = CellType::new(Shape::Line, 1);
        for k in 0..4 {
            m.boundary.push(line, &[k, (k + 1) % 4]);
            m.boundary_patch.push(0);
        }
        m.patches.push(mesh_model::Patch {
            name: "farfield".into(),
            role: mesh_model::Role::Farfield,
        });
        m
    }

    #[test]
    fn a_unit_square_passes_every_check() {
        let m = square();
        assert_valid("square", &m);
        assert_area("square", m.linear_area(), 1.0, 1e-15);
        // on the square's outline: the distance to the nearest side
        let outline = |_: usize, p: [f64; 2]| p[0].min(1.0 - p[0]).min(p[1]).min(1.0 - p[1]).abs();
        assert_eq!(assert_boundary_on("square", &m, outline, 1e-15), 0.0);
        assert!(assert_certified("square", &m).min_scaled_jacobian > 0.99);
    }

    #[test]
    #[should_panic(expected = "relative error")]
    fn a_wrong_area_is_named() {
        assert_area("square", 1.1, 1.0, 1e-9);
    }
}
