//! curvemesh: curved (high-order) viscous meshes by Spring-Field and Vector-Adding, the whole
//! pipeline as one library. A case — 2D loops (TOML, airfoil `.dat` files, the built-ins) or
//! a 3D closed surface (built-in, STL, `.msh`) — becomes a layered boundary-layer mesh,
//! curved to P2/P3 with every cell certified valid by a Bernstein bound of its Jacobian, and
//! described in a [`Report`]; a meshed 2D case can be moved by rigid motions and bumps
//! ([`movement`]), with the mesh's derivatives with respect to the motion.
//!
//! ```
//! let case = curvemesh::load("naca0012")?;
//! let options = curvemesh::Options { order: Some(3), ..Default::default() };
//! let meshed = curvemesh::mesh(&case, &options, &mut curvemesh::Silent)?;
//! assert!(meshed.report.is_valid(), "{:?}", meshed.report.problems);
//! assert_eq!(meshed.mesh.order, 3);
//! # Ok::<(), curvemesh::Error>(())
//! ```
//!
//! The stages are crates of their own, usable one by one (`geom-curve`, `boundary1d`,
//! `afsf2d`, `vector-adding`, `jacobian-check`, `mesh-io`, …); this crate composes them with
//! the tool's policies (the boundary spacing from the first layer height, the loops' checks,
//! the cell estimate), so a caller gets the very mesh `curvemesh mesh` writes.
//!
//! Module order, each using only those above it: [`error`], [`observer`], [`builtin`],
//! [`placement`], [`policy`], [`source`] → [`case`] → [`case3d`] → [`mod@load`], [`airfoil`];
//! [`estimate`], [`pipeline`] → [`wing`], `groups3d`, [`columns3d`] → [`pipeline3d`];
//! [`stages`],
//! [`movement::report`] → [`report`] → [`outputs`], [`quality`]; `meshed` (`Options`,
//! `Meshed`); then the runs (`mesh2d`, `mesh3d`, [`movement`]) and this root (`mesh`,
//! `mesh_into`, the re-exports).

pub mod airfoil;
pub mod builtin;
pub mod case;
pub mod case3d;
pub mod columns3d;
pub mod error;
pub mod estimate;
pub mod fill3d;
mod groups3d;
pub mod load;
mod mesh2d;
mod mesh3d;
mod meshed;
pub mod movement;
pub mod observer;
pub mod outputs;
pub mod pipeline;
pub mod pipeline3d;
pub mod placement;
pub mod policy;
pub mod quality;
pub mod report;
pub mod source;
pub mod stages;
pub mod wing;

pub use case::Case;
pub use case3d::Case3d;
pub use error::{Error, ErrorKind, Result};
pub use load::{AnyCase, load};
pub use mesh_model::Mesh;
pub use meshed::{Meshed, Options};
pub use observer::{Observer, Silent};
pub use outputs::Plan;
pub use report::Report;
pub use stages::Snapshot;

/// Meshes `case` (2D or 3D) with `options`, telling `observer` of each stage, and certifies
/// every cell. A mesh that fails validation is returned with its problems in the report;
/// bad input is an [`Error`].
pub fn mesh(case: &AnyCase, options: &Options, observer: &mut dyn Observer) -> Result<Meshed> {
    mesh_into(case, options, observer, None)
}

/// [`mesh`], writing the mesh files (and the snapshot) into `plan`'s reserved outputs as soon
/// as the mesh is made (in 2D beside its certification); the caller commits the plan.
pub fn mesh_into(
    case: &AnyCase,
    options: &Options,
    observer: &mut dyn Observer,
    plan: Option<&mut Plan>,
) -> Result<Meshed> {
    match case {
        AnyCase::Two(case) => mesh2d::mesh(case, options, observer, plan),
        AnyCase::Three(case) => mesh3d::mesh(case, options, observer, plan),
    }
}
