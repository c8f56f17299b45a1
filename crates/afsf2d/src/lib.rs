//! AFSF in 2D: the advancing-front spring-field linear viscous mesh of mixed quads and triangles, grown layer by layer from every boundary loop until the fronts close.
