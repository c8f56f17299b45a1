#!/usr/bin/env python3
"""Independent check of a .vtu file with VTK's own reader.

Usage: python3 tests/python/check_vtu.py MESH.vtu      (needs: pip install vtk)

Prints one JSON line: point and cell counts, cell counts per VTK type, the cell-data arrays,
and the area (2D) or volume (3D) that VTK integrates over the cells (vtkIntegrateAttributes,
which follows the curved Lagrange cells through their nodes: a wrong node order shows as a
wrong area). Exits 1 if VTK cannot read the file.
"""
import collections
import json
import sys

import vtk


def main(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    errors = []
    observer = lambda obj, ev: errors.append(ev)
    reader.AddObserver("ErrorEvent", observer)
    reader.Update()
    grid = reader.GetOutput()
    if errors or grid is None or grid.GetNumberOfCells() == 0:
        print(json.dumps({"file": path, "error": "VTK could not read the file"}))
        return 1
    types = collections.Counter(grid.GetCellType(i) for i in range(grid.GetNumberOfCells()))
    integrate = vtk.vtkIntegrateAttributes()
    integrate.SetInputData(grid)
    integrate.Update()
    out = integrate.GetOutput()
    measure = {}
    for name in ("Area", "Volume"):
        arr = out.GetCellData().GetArray(name)
        if arr is not None:
            measure[name.lower()] = arr.GetValue(0)
    cd = grid.GetCellData()
    print(json.dumps({"file": path, "points": grid.GetNumberOfPoints(),
                      "cells": grid.GetNumberOfCells(),
                      "types": {str(k): v for k, v in sorted(types.items())},
                      "cell_data": [cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())],
                      **measure}))
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
