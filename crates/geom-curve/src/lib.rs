//! Geometry curves: Selig and NACA inputs, approximate curvature, the C2 piecewise quintic Hermite curve with corner breaks, evaluation, arc length and closest point.
