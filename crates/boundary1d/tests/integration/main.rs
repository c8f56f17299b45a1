//! The integration tests of `boundary1d`, linked into one binary (one link of the crate and its
//! dependencies instead of one per file); each module below was a test file of its own.
//! `cargo test -p boundary1d --test integration -- MODULE::` runs one of them.

mod common;

mod caps;
mod gaps;
mod properties;
mod real_airfoils;
mod robustness;
