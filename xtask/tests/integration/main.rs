//! The integration tests of `xtask`, linked into one binary (one link of the crate and its
//! dependencies instead of one per file); each module below was a test file of its own.
//! `cargo test -p xtask --test integration -- MODULE::` runs one of them.

mod bench;
mod binary;
mod docs_examples;
mod help;
mod mesh3d;
