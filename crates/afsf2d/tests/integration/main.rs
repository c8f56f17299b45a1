//! The integration tests of `afsf2d`, linked into one binary (one link of the crate and its
//! dependencies instead of one per file); each module below was a test file of its own.
//! `cargo test -p afsf2d --test integration -- MODULE::` runs one of them.

mod common;

mod beside;
mod cases;
mod narrow_gaps;
mod props;
mod real_cases;
mod threads;
