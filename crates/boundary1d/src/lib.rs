//! Curvature-driven 1D boundary meshes on geometry curves: the spacing law, break points, optional medial-axis refinement and graded node placement.
