#!/usr/bin/python3
"""Synthetic organic shapes for trying the chain on models it has not seen (issue 27).

Each shape is a smooth union of anisotropic Gaussian blobs (a body with thin parts: ears,
flippers, a fluke, legs, arms), contoured at half height, smoothed, decimated and written as
a closed genus-0 OBJ surface. Deterministic: the same files on every run.

Usage: bench/organic_shapes.py OUT_DIR [NAME ...]   (names: bear whale cactus dog starfish mug;
default: all)
Needs VTK's Python module (Debian: python3-vtk9, installed for CI by scripts/packages-ci.txt).
Try them with: polycube run OUT_DIR/whale.obj --hexes 20000 -o out/whale
"""
import os
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import numpy_to_vtk


def rot_z(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def rot_y(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


# (centre, radii, rotation or None) per blob.
SHAPES = {
    # a head with two thin ears and a snout
    "bear": [((0, 0, 0), (1, 1, 1), None),
             ((0.75, 0, 0.75), (0.35, 0.12, 0.35), rot_y(0.8)),
             ((-0.75, 0, 0.75), (0.35, 0.12, 0.35), rot_y(-0.8)),
             ((0, -0.9, -0.1), (0.35, 0.3, 0.3), None)],
    # a body with two flat flippers and a flat fluke
    "whale": [((0, 0, 0), (2.0, 0.8, 0.7), None),
              ((1.9, 0, 0.1), (0.5, 0.25, 0.3), None),
              ((2.4, 0, 0.2), (0.15, 0.7, 0.08), None),
              ((-0.5, 0.9, -0.3), (0.45, 0.35, 0.08), rot_z(0.4)),
              ((-0.5, -0.9, -0.3), (0.45, 0.35, 0.08), rot_z(-0.4))],
    # a stem with two arms
    "cactus": [((0, 0, 0), (0.45, 0.45, 2.2), None),
               ((0.7, 0, 0.2), (0.5, 0.3, 0.25), None),
               ((1.0, 0, 0.9), (0.25, 0.25, 0.7), None),
               ((-0.6, 0, -0.3), (0.45, 0.3, 0.25), None),
               ((-0.9, 0, 0.4), (0.25, 0.25, 0.6), None)],
    # a body, a head with a snout, four legs and a tail
    "dog": [((0, 0, 0), (1.6, 0.6, 0.6), None),
            ((1.6, 0, 0.7), (0.5, 0.45, 0.45), None),
            ((2.1, 0, 0.6), (0.35, 0.2, 0.2), None)]
           + [((sx * 1.0, sy * 0.35, -0.9), (0.18, 0.18, 0.7), None) for sx in (-1, 1) for sy in (-1, 1)]
           + [((-1.7, 0, 0.5), (0.4, 0.1, 0.1), rot_y(-0.6))],
    # five flat arms around a flat centre
    "starfish": [((0, 0, 0), (0.6, 0.6, 0.25), None)]
                + [((1.0 * np.cos(a), 1.0 * np.sin(a), 0), (0.7, 0.22, 0.15), rot_z(-a))
                   for a in np.linspace(0, 2 * np.pi, 5, endpoint=False)],
    # a cup with a handle (genus 1): the handle a ring of small blobs
    "mug": [((0, 0, 0), (0.8, 0.8, 1.0), None)]
           + [((0.75 + 0.6 * np.cos(a), 0, 0.6 * np.sin(a)), (0.14, 0.14, 0.14), None)
              for a in np.linspace(-np.pi / 2, np.pi / 2, 15)],
}

SAMPLES = 120        # field samples per axis
TRIANGLES = 12000    # decimation target
DIAGONAL = 100.0     # the field box's diagonal in the output's units


def field(blobs, lo, hi):
    axes = [np.linspace(lo[i], hi[i], SAMPLES) for i in range(3)]
    x, y, z = np.meshgrid(*axes, indexing="ij")
    f = np.zeros_like(x)
    for centre, radii, rotation in blobs:
        p = np.stack([x - centre[0], y - centre[1], z - centre[2]], -1)
        if rotation is not None:
            p = p @ rotation
        f += np.exp(-sum((p[..., k] / radii[k]) ** 2 for k in range(3)))
    return f


def surface(blobs):
    centres = np.array([b[0] for b in blobs], dtype=float)
    reach = 2.5 * np.array([max(b[1]) for b in blobs])[:, None]
    lo, hi = (centres - reach).min(0), (centres + reach).max(0)
    image = vtk.vtkImageData()
    image.SetDimensions(SAMPLES, SAMPLES, SAMPLES)
    image.SetOrigin(lo)
    image.SetSpacing([(hi[i] - lo[i]) / (SAMPLES - 1) for i in range(3)])
    image.GetPointData().SetScalars(numpy_to_vtk(field(blobs, lo, hi).ravel(order="F"), deep=True))
    contour = vtk.vtkFlyingEdges3D()
    contour.SetInputData(image)
    contour.SetValue(0, 0.5)
    largest = vtk.vtkPolyDataConnectivityFilter()
    largest.SetInputConnection(contour.GetOutputPort())
    largest.SetExtractionModeToLargestRegion()
    smooth = vtk.vtkWindowedSincPolyDataFilter()
    smooth.SetInputConnection(largest.GetOutputPort())
    smooth.SetNumberOfIterations(20)
    smooth.SetPassBand(0.05)
    smooth.NormalizeCoordinatesOn()
    triangles = vtk.vtkTriangleFilter()
    triangles.SetInputConnection(smooth.GetOutputPort())
    triangles.Update()
    decimate = vtk.vtkQuadricDecimation()
    decimate.SetInputConnection(triangles.GetOutputPort())
    decimate.SetTargetReduction(max(0.0, 1 - TRIANGLES / triangles.GetOutput().GetNumberOfCells()))
    clean = vtk.vtkCleanPolyData()
    clean.SetInputConnection(decimate.GetOutputPort())
    scale = vtk.vtkTransform()
    s = DIAGONAL / np.linalg.norm(hi - lo)
    scale.Scale(s, s, s)
    scaled = vtk.vtkTransformPolyDataFilter()
    scaled.SetInputConnection(clean.GetOutputPort())
    scaled.SetTransform(scale)
    scaled.Update()
    return scaled.GetOutput()


def main():
    if len(sys.argv) < 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(sys.argv) >= 2 else 2
    out = sys.argv[1]
    names = sys.argv[2:] or list(SHAPES)
    os.makedirs(out, exist_ok=True)
    for name in names:
        if name not in SHAPES:
            print(f"organic_shapes.py: no shape named {name} (names: {' '.join(SHAPES)})", file=sys.stderr)
            return 2
        mesh = surface(SHAPES[name])
        writer = vtk.vtkOBJWriter()
        writer.SetFileName(os.path.join(out, name + ".obj"))
        writer.SetInputData(mesh)
        writer.Write()
        print(f"{name}: {mesh.GetNumberOfPoints()} vertices, {mesh.GetNumberOfCells()} triangles")
    return 0


if __name__ == "__main__":
    sys.exit(main())
