"""Print what meshio reads from a mesh file, as JSON: point count, cells per type, field names.

Used by tests/io/test_outside_readers.cpp to check that meshio reads every format we write.
"""
import json
import sys

import meshio

mesh = meshio.read(sys.argv[1])
cells = {}
for block in mesh.cells:
    cells[block.type] = cells.get(block.type, 0) + len(block.data)
print(json.dumps({"points": len(mesh.points), "cells": cells,
                  "point_data": sorted(mesh.point_data), "cell_data": sorted(mesh.cell_data)}))
