//! Mesh file formats: Gmsh MSH 4.1 (write and read), VTK XML .vtu with Lagrange cells, SU2, and binary snapshots of intermediate stages; every write is atomic.
