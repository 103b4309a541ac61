#!/usr/bin/env python3
"""Per-cell scaled Jacobian of legacy VTK unstructured grids, computed by VTK's vtkMeshQuality
(Verdict), one value per line in cell order. Used by test_quality to check our implementation.
Several pairs can be given, so that VTK is imported once.

usage: vtk_scaled_jacobian.py IN.vtk OUT.txt [IN2.vtk OUT2.txt ...]
"""
import sys

# The two modules needed, not the whole `vtk` package (a few times faster to import).
from vtkmodules.vtkFiltersVerdict import vtkMeshQuality
from vtkmodules.vtkIOLegacy import vtkUnstructuredGridReader


def scaled_jacobian(path_in, path_out):
    reader = vtkUnstructuredGridReader()
    reader.SetFileName(path_in)
    reader.Update()
    grid = reader.GetOutput()
    if grid is None or grid.GetNumberOfCells() == 0:
        sys.stderr.write("no cells read from %s\n" % path_in)
        return False
    quality = vtkMeshQuality()
    quality.SetInputData(grid)
    quality.SetHexQualityMeasureToScaledJacobian()
    quality.SetTetQualityMeasureToScaledJacobian()
    quality.SetQuadQualityMeasureToScaledJacobian()
    quality.Update()
    values = quality.GetOutput().GetCellData().GetArray("Quality")
    with open(path_out, "w") as out:
        for i in range(values.GetNumberOfTuples()):
            out.write(repr(values.GetValue(i)) + "\n")
    return True


def main():
    args = sys.argv[1:]
    if not args or len(args) % 2 != 0:
        sys.stderr.write(__doc__)
        return 1
    for i in range(0, len(args), 2):
        if not scaled_jacobian(args[i], args[i + 1]):
            return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
