//! The built-in cases and the data files they name, embedded in the binary from `fixtures/` so
//! that `cargo xtask mesh NAME` works from any folder.

/// The case used when none is named: the 30P30N three-element airfoil.
pub const DEFAULT: &str = "30p30n";

/// (name, one-line description, case file text).
const CASES: &[(&str, &str, &str)] = &[
    (
        "30p30n",
        "HLPW-4 30P30N three-element high-lift airfoil, first height 5e-6 (default)",
        include_str!("../../../fixtures/cases/30p30n.toml"),
    ),
    (
        "naca0012",
        "NACA 0012, public coordinates with a blunt trailing edge, first height 5e-5",
        include_str!("../../../fixtures/cases/naca0012.toml"),
    ),
    (
        "two-element",
        "synthetic two-element airfoil: NACA 2412 main and a 30 % NACA 4412 flap at 25 deg",
        include_str!("../../../fixtures/cases/two-element.toml"),
    ),
    (
        "bat",
        "concave bat-like loop meshed inside (wingspan 60), like the dissertation's",
        include_str!("../../../fixtures/cases/bat.toml"),
    ),
    (
        "lshape",
        "L-shaped body with sharp convex and concave corners",
        include_str!("../../../fixtures/cases/lshape.toml"),
    ),
];

/// The built-in 3D cases (`dimension = 3`), listed after the 2D ones.
const CASES_3D: &[(&str, &str, &str)] = &[
    (
        "sphere",
        "3D: unit sphere (1280 triangles), 30 layers from 1e-3, mixed cells",
        include_str!("../../../fixtures/cases/sphere.toml"),
    ),
    (
        "cube",
        "3D: unit cube (8x8 quads a face, sharp edges and corners), 30 layers, mixed cells",
        include_str!("../../../fixtures/cases/cube.toml"),
    ),
    (
        "step",
        "3D: 1x1x0.5 block with a 0.4x0.4x0.5 tower (90 deg concave edges), 15 layers from 2e-3",
        include_str!("../../../fixtures/cases/step.toml"),
    ),
    (
        "wing",
        "3D: NACA 0012 wing of span 2 from the naca0012 case, 45 layers from 1e-3, tets (tables 5-7, case 1)",
        include_str!("../../../fixtures/cases/wing.toml"),
    ),
];

/// Data files named by the built-in cases, by the path written in the case file.
const FILES: &[(&str, &str)] = &[
    (
        "../geometry/30p30n/slat.dat",
        include_str!("../../../fixtures/geometry/30p30n/slat.dat"),
    ),
    (
        "../geometry/30p30n/main.dat",
        include_str!("../../../fixtures/geometry/30p30n/main.dat"),
    ),
    (
        "../geometry/30p30n/flap.dat",
        include_str!("../../../fixtures/geometry/30p30n/flap.dat"),
    ),
    (
        "../geometry/naca0012.dat",
        include_str!("../../../fixtures/geometry/naca0012.dat"),
    ),
    (
        "../geometry/bat.dat",
        include_str!("../../../fixtures/geometry/bat.dat"),
    ),
];

/// The text of built-in case `name`, if there is one.
pub fn case_text(name: &str) -> Option<&'static str> {
    CASES
        .iter()
        .chain(CASES_3D)
        .find(|c| c.0 == name)
        .map(|c| c.2)
}

/// The names of the built-in 2D cases (what `bench`, `move` and the 2D tests run).
pub fn names() -> Vec<&'static str> {
    CASES.iter().map(|c| c.0).collect()
}

/// The names of the built-in 3D cases.
pub fn names_3d() -> Vec<&'static str> {
    CASES_3D.iter().map(|c| c.0).collect()
}

/// The names of every built-in case, 2D then 3D.
pub fn all_names() -> Vec<&'static str> {
    CASES.iter().chain(CASES_3D).map(|c| c.0).collect()
}

/// (name, description) of every built-in case, 2D then 3D.
pub fn list() -> impl Iterator<Item = (&'static str, &'static str)> {
    CASES.iter().chain(CASES_3D).map(|c| (c.0, c.1))
}

/// An embedded data file, by the path a built-in case gives.
pub fn data_file(path: &str) -> Option<&'static str> {
    FILES.iter().find(|f| f.0 == path).map(|f| f.1)
}
