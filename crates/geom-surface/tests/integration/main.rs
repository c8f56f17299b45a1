//! The integration tests of `geom-surface`, linked into one binary (one link of the crate and its
//! dependencies instead of one per file); each module below was a test file of its own.
//! `cargo test -p geom-surface --test integration -- MODULE::` runs one of them.

mod smooth;
mod surface;
mod wing;
