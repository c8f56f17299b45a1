//! The integration tests of `mesh-model`, linked into one binary (one link of the crate and its
//! dependencies instead of one per file); each module below was a test file of its own.
//! `cargo test -p mesh-model --test integration -- MODULE::` runs one of them.

mod solid_props;
mod validate_props;
