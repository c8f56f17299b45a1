//! Fuzz target: the STL reader (ASCII and binary, with the solids' groups) on arbitrary
//! bytes. Any panic, hang or abort is a bug.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = mesh_io::stl::parse_grouped(data, std::path::Path::new("fuzz.stl"));
});
