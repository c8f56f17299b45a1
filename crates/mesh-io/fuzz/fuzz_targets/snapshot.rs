//! Fuzz target: the snapshot decoder (header and bincode payload) on arbitrary bytes, as a
//! mesh and as a layered mesh. Any panic, hang, abort or unbounded allocation is a bug.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let path = std::path::Path::new("fuzz.snap");
    let _ = mesh_io::snapshot::parse::<mesh_model::Mesh>(data, path);
    let _ = mesh_io::snapshot::parse::<mesh_model::LayeredMesh>(data, path);
});
