//! Criterion bench of the curving, filled in with the crate's tests.
fn main() {}
