//! The integration tests of `curvemesh`, linked into one binary (one link of the crate and its
//! dependencies instead of one per file); each module below was a test file of its own.
//! `cargo test -p curvemesh --test integration -- MODULE::` runs one of them.

mod curved_walls;
mod far_field;
mod library;
