//! Pictures of meshes: PNG and SVG drawings with boundary loops, layers and colour maps, whole or zoomed.
