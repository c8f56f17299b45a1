//! The integration tests of `jacobian-check`, linked into one binary (one link of the crate and its
//! dependencies instead of one per file); each module below was a test file of its own.
//! `cargo test -p jacobian-check --test integration -- MODULE::` runs one of them.

mod area;
mod certify;
mod certify3d;
mod certify3d_p3;
mod lagrange;
mod measure;
mod pyramid14;
