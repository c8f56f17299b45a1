//! The built-in cases of the pipeline (`fixtures/cases/*.toml`), with their boundary nodes made
//! the way `cargo xtask mesh` makes them: one copy, in the dev-only `test-cases` crate, shared
//! with the other crates' tests and benches.
#![allow(unused_imports)]

pub use test_cases::{mesher_input, real_case, real_cases, with_layers};
