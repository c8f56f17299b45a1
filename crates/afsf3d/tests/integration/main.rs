//! The integration tests of `afsf3d`, linked into one binary (one link of the crate and its
//! dependencies instead of one per file); each module below was a test file of its own.
//! `cargo test -p afsf3d --test integration -- MODULE::` runs one of them.

mod fan;
mod grow;
mod identity;
mod stop;
