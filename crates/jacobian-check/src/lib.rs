//! Validity of high-order cells (skeleton; see Cargo.toml description).
