//! Without merges the layers are those of the code before neighbour merging, to the last
//! bit: a digest of every node's coordinates and every face on the sphere and the cube,
//! against the digests of that code (commit c02b0c3).

use afsf3d::{LayerParams, grow_layers};
use geom_surface::Surface;

/// FNV-1a over the bits of every node coordinate, then every face's nodes.
fn digest(surface: &Surface, layers: usize) -> u64 {
    let params = LayerParams {
        layers,
        ..LayerParams::default()
    };
    let grown = grow_layers(surface, &params).expect("grows");
    assert_eq!(grown.stats.merges, 0);
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |x: u64| {
        for b in x.to_le_bytes() {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    };
    for p in &grown.mesh.nodes {
        p.iter().for_each(|x| eat(x.to_bits()));
    }
    for f in 0..grown.mesh.face_count() {
        grown.mesh.face(f).iter().for_each(|&v| eat(u64::from(v)));
    }
    h
}

#[test]
fn sphere_and_cube_layers_are_unchanged_to_the_bit() {
    let cases = [
        (
            "sphere",
            digest(&Surface::sphere(1.0, 3), 30),
            0xd54a_54b5_7049_9ccc,
        ),
        (
            "cube quads",
            digest(&Surface::cube(1.0, 8, false), 30),
            0xde98_0dee_e305_6828,
        ),
        (
            "cube triangles",
            digest(&Surface::cube(1.0, 8, true), 30),
            0x2675_efd4_c63e_4b01,
        ),
    ];
    for (name, got, want) in cases {
        assert_eq!(got, want, "{name}: {got:#018x}, not {want:#018x}");
    }
}
