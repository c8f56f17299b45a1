//! Projection onto the true wall surface for the 3D curving: the [`SurfaceProjector`] trait
//! the caller implements for its geometry, and the exact sphere ([`SphereProjector`]).

/// Puts points onto the true wall surface.
pub trait SurfaceProjector {
    /// The point of the true surface for `p`, a point near wall facet `facet` (the pipe of
    /// the layer-0 cells through it: the index of the facet in the surface the layers grew
    /// from).
    fn project(&self, p: [f64; 3], facet: usize) -> [f64; 3];
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
}
