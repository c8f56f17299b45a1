//! Fuzz target: the motion-file reader on arbitrary TOML text, then every motion it accepts
//! checked against the built-in NACA 0012 and the two-element airfoil (loop names, values,
//! loops crossing, the moved curves fitted). Any panic, hang or abort is a bug.
#![no_main]

use std::sync::OnceLock;

use curvemesh::Case;
use curvemesh::movement::motion;
use libfuzzer_sys::fuzz_target;

fn cases() -> &'static [Case] {
    static CASES: OnceLock<Vec<Case>> = OnceLock::new();
    CASES.get_or_init(|| {
        ["naca0012", "two-element"]
            .iter()
            .map(|n| curvemesh::load::load_2d(n).expect("a built-in case"))
            .collect()
    })
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(motions) = motion::parse_str(text, "motion.toml") {
        for case in cases() {
            let _ = motion::moved_geometry(case, &motions);
        }
    }
});
