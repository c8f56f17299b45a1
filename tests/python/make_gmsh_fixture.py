#!/usr/bin/env python3
"""Make the Gmsh-written fixture crates/mesh-io/tests/data/gmsh_ring_p3.msh: a coarse mixed
(triangles and recombined quadrangles) P3 mesh of the ring between circles of radius 1 (wall)
and 3 (farfield), meshed and saved by Gmsh itself as MSH 4.1 ASCII, for mesh-io's reader tests.

Usage: python3 tests/python/make_gmsh_fixture.py OUT.msh      (needs: pip install gmsh)
"""
import sys

import gmsh

gmsh.initialize(["-noenv"], readConfigFiles=False)
gmsh.option.setNumber("General.Terminal", 0)
gmsh.model.add("ring")
outer = gmsh.model.occ.addDisk(0, 0, 0, 3, 3)
inner = gmsh.model.occ.addDisk(0, 0, 0, 1, 1)
gmsh.model.occ.cut([(2, outer)], [(2, inner)])
gmsh.model.occ.synchronize()
curves = gmsh.model.getEntities(1)
by_radius = sorted(curves, key=lambda c: gmsh.model.getBoundingBox(*c)[3])
gmsh.model.addPhysicalGroup(1, [by_radius[0][1]], name="wall")
gmsh.model.addPhysicalGroup(1, [by_radius[1][1]], name="farfield")
gmsh.model.addPhysicalGroup(2, [s[1] for s in gmsh.model.getEntities(2)], name="fluid")
gmsh.option.setNumber("Mesh.MeshSizeMax", 0.9)
gmsh.model.mesh.generate(2)
# Recombine part of the triangles into quadrangles: a mixed mesh.
gmsh.option.setNumber("Mesh.RecombineAll", 0)
gmsh.model.mesh.recombine()
gmsh.model.mesh.setOrder(3)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.option.setNumber("Mesh.Binary", 0)
gmsh.write(sys.argv[1])
gmsh.finalize()
