//! Fuzz target: the STL reader (ASCII and binary) on arbitrary bytes. Any panic, hang or
//! abort is a bug.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = mesh_io::stl::parse(data, std::path::Path::new("fuzz.stl"));
});
