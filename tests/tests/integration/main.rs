//! The integration tests of `end-to-end`, linked into one binary (one link of the crate and its
//! dependencies instead of one per file); each module below was a test file of its own.
//! `cargo test -p end-to-end --test integration -- MODULE::` runs one of them.

mod checked_run;

mod airfoil_files;
mod bad_input;
mod boundary_groups;
mod builtin_cases;
mod case_inputs;
mod exit_status;
mod mesh_identity;
mod movement;
mod narrow_gaps;
mod notes;
mod outputs;
mod pictures;
mod quality_3d;
mod quality_certified;
mod random_geometry;
mod report_honesty;
mod snapshot;
mod su2_3d;
mod surface_inputs;
mod surfaces_3d;
mod threads_and_binary;
mod tidy;
mod wing3d;
