//! The integration tests of `tet-fill`, linked into one binary; `cargo test -p tet-fill --test
//! integration -- MODULE::` runs one module.

mod common;

mod delaunay;
mod fill;
mod sliver;
