//! Projection onto the true wall surface for the 3D curving: the [`SurfaceProjector`] trait
//! the caller implements for its geometry, and the exact sphere ([`SphereProjector`]).

/// Puts points onto the true wall surface.
pub trait SurfaceProjector {
    /// The point of the true surface for `p`, a point near wall facet `facet` (the pipe of
    /// the layer-0 cells through it: the index of the facet in the surface the layers grew
    /// from).
    fn project(&self, p: [f64; 3], facet: usize) -> [f64; 3];

    /// The point at fraction `s` of the length of the surface's curve over the wall edge from
    /// `a` to `b` (two corners of wall facet `facet`): the P3 wall edges' nodes, spaced along
    /// the curve as the 2D curving spaces them. By default the curve is the image of the chord
    /// under [`SurfaceProjector::project`], its length taken along 24 pieces of it, and a
    /// flat wall's (the image is the chord) is the chord itself.
    fn edge_point(&self, a: [f64; 3], b: [f64; 3], s: f64, facet: usize) -> [f64; 3] {
        const PIECES: usize = 24;
        let chord = |t: f64| [0, 1, 2].map(|d| a[d] + t * (b[d] - a[d]));
        let image: Vec<[f64; 3]> = (0..=PIECES)
            .map(|k| self.project(chord(k as f64 / PIECES as f64), facet))
            .collect();
        if image
            .iter()
            .enumerate()
            .all(|(k, p)| *p == chord(k as f64 / PIECES as f64))
        {
            return chord(s);
        }
        let mut length = vec![0.0];
        for w in image.windows(2) {
            let d = (0..3).map(|d| (w[1][d] - w[0][d]).powi(2)).sum::<f64>();
            length.push(length[length.len() - 1] + d.sqrt());
        }
        let at = s * length[PIECES];
        let k = length.partition_point(|&l| l <= at).clamp(1, PIECES) - 1;
        let piece = length[k + 1] - length[k];
        let within = if piece > 0.0 {
            (at - length[k]) / piece
        } else {
            0.0
        };
        self.project(chord((k as f64 + within) / PIECES as f64), facet)
    }
}

/// The exact sphere: projection along the ray from the centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereProjector {
    /// The centre.
    pub centre: [f64; 3],
    /// The radius (> 0).
    pub radius: f64,
}

impl SurfaceProjector for SphereProjector {
    fn project(&self, p: [f64; 3], _facet: usize) -> [f64; 3] {
        let d = [0, 1, 2].map(|k| p[k] - self.centre[k]);
        let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if r == 0.0 {
            return p;
        }
        [0, 1, 2].map(|k| self.centre[k] + self.radius * d[k] / r)
    }

    /// On the great circle through `a` and `b` (taken onto the sphere) at fraction `s` of the
    /// angle between them.
    fn edge_point(&self, a: [f64; 3], b: [f64; 3], s: f64, facet: usize) -> [f64; 3] {
        let unit = |p: [f64; 3]| {
            let q = self.project(p, facet);
            [0, 1, 2].map(|k| (q[k] - self.centre[k]) / self.radius)
        };
        let (u, v) = (unit(a), unit(b));
        let dot = (0..3).map(|k| u[k] * v[k]).sum::<f64>().clamp(-1.0, 1.0);
        let angle = dot.acos();
        if angle < 1e-12 {
            return self.project(a, facet);
        }
        let (wu, wv) = (
            ((1.0 - s) * angle).sin() / angle.sin(),
            (s * angle).sin() / angle.sin(),
        );
        [0, 1, 2].map(|k| self.centre[k] + self.radius * (wu * u[k] + wv * v[k]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The default `edge_point` of a projector that is the sphere's projection alone.
    struct Radial(SphereProjector);

    impl SurfaceProjector for Radial {
        fn project(&self, p: [f64; 3], facet: usize) -> [f64; 3] {
            self.0.project(p, facet)
        }
    }

    /// A flat wall: the identity.
    struct Flat;

    impl SurfaceProjector for Flat {
        fn project(&self, p: [f64; 3], _facet: usize) -> [f64; 3] {
            p
        }
    }

    #[test]
    fn edge_points_are_at_equal_arc_length() {
        let sphere = SphereProjector {
            centre: [1.0, 2.0, 3.0],
            radius: 2.0,
        };
        let a = [3.0, 2.0, 3.0];
        let b = [1.0 + 2.0 * 0.3f64.cos(), 2.0 + 2.0 * 0.3f64.sin(), 3.0];
        for s in [1.0f64 / 3.0, 2.0 / 3.0] {
            // exactly at s · 0.3 rad on the great circle, and the default within a millionth
            // (along the curve: its 24 straight pieces)
            let want = [
                1.0 + 2.0 * (s * 0.3).cos(),
                2.0 + 2.0 * (s * 0.3).sin(),
                3.0,
            ];
            let exact = sphere.edge_point(a, b, s, 0);
            let sampled = Radial(sphere).edge_point(a, b, s, 0);
            for d in 0..3 {
                assert!((exact[d] - want[d]).abs() < 1e-14, "{exact:?}");
                assert!((sampled[d] - want[d]).abs() < 1e-6, "{sampled:?}");
            }
        }
        // a flat wall's points are the chord's, to the last bit
        assert_eq!(Flat.edge_point(a, b, 1.0 / 3.0, 0), {
            let t = 1.0 / 3.0;
            [0, 1, 2].map(|d| a[d] + t * (b[d] - a[d]))
        });
    }
}
