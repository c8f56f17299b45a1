//! The workspace's geometry fixtures (`fixtures/geometry`): Selig `.dat` airfoils and the bat.

use geom_curve::{ClosedCurve, CurveParams, Point2, selig};

/// Every airfoil fixture, by its path under `fixtures/geometry`.
pub const AIRFOILS: [&str; 6] = [
    "naca0012.dat",
    "naca0012-sharp-te-generated.dat",
    "rae2822.dat",
    "30p30n/slat.dat",
    "30p30n/main.dat",
    "30p30n/flap.dat",
];

/// The three elements of the 30P30N, slat first.
pub const THIRTY_P_THIRTY_N: [&str; 3] = ["30p30n/slat.dat", "30p30n/main.dat", "30p30n/flap.dat"];

/// The workspace's `fixtures/geometry` folder.
pub fn geometry_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/geometry")
}

/// The points of a Selig file of `fixtures/geometry`, as `geom_curve::selig` reads them.
///
/// # Panics
/// When the file cannot be read or parsed.
pub fn selig(name: &str) -> Vec<Point2<f64>> {
    let path = geometry_dir().join(name);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read fixture {}: {e}", path.display()));
    selig::parse(&text).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// [`selig()`] as `[x, y]` pairs.
pub fn selig_xy(name: &str) -> Vec<[f64; 2]> {
    selig(name).iter().map(|p| [p.x, p.y]).collect()
}

/// The C2 curve through a Selig fixture (default curve parameters).
///
/// # Panics
/// As [`selig()`], or when the curve cannot be fitted.
pub fn selig_curve(name: &str) -> ClosedCurve {
    ClosedCurve::new(&selig(name), &CurveParams::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}
