//! Fuzz target: the Selig/Lednicer `.dat` reader, then the loop checks and the curve fit on
//! whatever it accepts. Any panic, hang or abort is a bug.
#![no_main]

use geom_curve::{ClosedCurve, CurveParams, loops, selig};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(mut points) = selig::parse(text) {
        if loops::validate_loop(&points, &CurveParams::default().loop_checks).is_ok() {
            loops::make_counter_clockwise(&mut points);
            if let Ok(curve) = ClosedCurve::new(&points, &CurveParams::default()) {
                let _ = curve.t_at_arc_length(0.5 * curve.total_length());
            }
        }
    }
});
