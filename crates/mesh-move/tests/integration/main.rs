//! The integration tests of `mesh-move`, linked into one binary (one link of the crate and its
//! dependencies instead of one per file); each module below was a test file of its own.
//! `cargo test -p mesh-move --test integration -- MODULE::` runs one of them.

mod common;

mod motion;
mod naca;
mod smooth;
mod springs;
