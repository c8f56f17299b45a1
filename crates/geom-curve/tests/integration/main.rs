//! The integration tests of `geom-curve`, linked into one binary (one link of the crate and its
//! dependencies instead of one per file); each module below was a test file of its own.
//! `cargo test -p geom-curve --test integration -- MODULE::` runs one of them.

mod common;

mod curve_properties;
mod real_geometry;
mod robustness;
