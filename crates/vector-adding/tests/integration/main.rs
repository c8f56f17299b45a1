//! The integration tests of `vector-adding`, linked into one binary (one link of the crate and its
//! dependencies instead of one per file); each module below was a test file of its own.
//! `cargo test -p vector-adding --test integration -- MODULE::` runs one of them.

mod common;

mod convergence;
mod curve3d;
mod keeping;
mod props;
mod real_cases;
mod threads;
