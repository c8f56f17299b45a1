//! Fuzz target: the case-file loader, 2D and 3D (`dimension = 3`), on arbitrary TOML text
//! (data files resolve to the built-in ones only), then the loop checks of every 2D loop it
//! accepts. Any panic, hang or abort is a bug.
#![no_main]

use curvemesh::AnyCase;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(AnyCase::Two(case)) = curvemesh::load::parse_str(text) {
        for l in &case.loops {
            let points: Vec<geom_curve::Point2<f64>> = l
                .points
                .iter()
                .map(|p| geom_curve::Point2::new(p[0], p[1]))
                .collect();
            let _ = geom_curve::loops::validate_loop(&points, &Default::default());
        }
    }
});
