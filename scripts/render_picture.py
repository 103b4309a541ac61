#!/usr/bin/python3
"""Render the README's picture: a shape, its polycube and its optimized hex mesh, side by side.

Usage: xvfb-run -a /usr/bin/python3 scripts/render_picture.py RUN_DIR INPUT_SURFACE OUT.png
(`make picture` does it all: it runs `polycube run` on the flange sample first.)

RUN_DIR is the folder of a `polycube run`; the polycube is the boundary of its simplified
map's polycube tet mesh, the hex mesh its hex_quality.vtk coloured by the scaled Jacobian.
Uses Debian's python3-vtk9 (and python3-meshio for the Medit .mesh files); it needs an X
display, which xvfb-run provides on a headless machine.
"""
import sys
from collections import Counter

import meshio
import numpy as np
import vtk


def boundary_polydata(path):
    """The boundary triangles of a tet mesh (faces used by one tet) as vtkPolyData."""
    m = meshio.read(path)
    tets = next(c.data for c in m.cells if c.type == "tetra")
    faces = Counter()
    first = {}
    for t in tets:
        for f in ((t[0], t[2], t[1]), (t[0], t[1], t[3]), (t[0], t[3], t[2]), (t[1], t[2], t[3])):
            key = tuple(sorted(f))
            faces[key] += 1
            first.setdefault(key, f)
    points = vtk.vtkPoints()
    for p in m.points:
        points.InsertNextPoint(*p)
    cells = vtk.vtkCellArray()
    for key, n in faces.items():
        if n == 1:
            cells.InsertNextCell(3, first[key])
    poly = vtk.vtkPolyData()
    poly.SetPoints(points)
    poly.SetPolys(cells)
    return poly


def map_rotation(run_dir):
    """The rotation closest to the map's linear part (model -> polycube; same tets, same
    points), so that the polycube is seen from the direction the model is seen from: the
    construction may have turned the shape to align it with the axes."""
    model = meshio.read(run_dir + "/simplify/model.mesh").points
    cube = meshio.read(run_dir + "/simplify/polycube.mesh").points
    a = np.linalg.lstsq(model - model.mean(0), cube - cube.mean(0), rcond=None)[0].T
    u, _, vt = np.linalg.svd(a)
    r = u @ vt
    if np.linalg.det(r) < 0:
        u[:, -1] *= -1
        r = u @ vt
    return r


def polycube_actor(poly):
    """The polycube's faces coloured by their axis, as in the thesis's figures."""
    normals = vtk.vtkPolyDataNormals()
    normals.SetInputData(poly)
    normals.ComputeCellNormalsOn()
    normals.ComputePointNormalsOff()
    normals.SplittingOff()
    normals.Update()
    out = normals.GetOutput()
    n = out.GetCellData().GetNormals()
    palette = [(230, 120, 110), (120, 190, 120), (110, 150, 225)]  # X, Y, Z
    colours = vtk.vtkUnsignedCharArray()
    colours.SetNumberOfComponents(3)
    colours.SetName("axis")
    for c in range(out.GetNumberOfCells()):
        colours.InsertNextTuple3(*palette[int(np.argmax(np.abs(n.GetTuple3(c))))])
    out.GetCellData().SetScalars(colours)
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(out)
    mapper.SetScalarModeToUseCellData()
    mapper.SetColorModeToDirectScalars()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    # its edges, which flat colours alone leave ambiguous
    edges = vtk.vtkFeatureEdges()
    edges.SetInputData(poly)
    edges.BoundaryEdgesOff()
    edges.ManifoldEdgesOff()
    edges.NonManifoldEdgesOff()
    edges.FeatureEdgesOn()
    edges.SetFeatureAngle(30)
    edge_mapper = vtk.vtkPolyDataMapper()
    edge_mapper.SetInputConnection(edges.GetOutputPort())
    edge_mapper.ScalarVisibilityOff()
    edge_actor = vtk.vtkActor()
    edge_actor.SetMapper(edge_mapper)
    edge_actor.GetProperty().SetColor(0.1, 0.1, 0.1)
    edge_actor.GetProperty().SetLineWidth(2)
    return [actor, edge_actor]


def surface_actor(source_port, colour):
    normals = vtk.vtkPolyDataNormals()
    normals.SetInputConnection(source_port)
    normals.SetFeatureAngle(30)
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(normals.GetOutputPort())
    mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(*colour)
    return actor


def hex_actor(path):
    reader = vtk.vtkUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    surface = vtk.vtkDataSetSurfaceFilter()
    surface.SetInputData(grid)
    mapper = vtk.vtkDataSetMapper()
    mapper.SetInputConnection(surface.GetOutputPort())
    names = [grid.GetCellData().GetArrayName(i) for i in range(grid.GetCellData().GetNumberOfArrays())]
    field = next((n for n in names if "jacobian" in n.lower() or n.lower() == "sj"), None)
    if field:
        mapper.SetScalarModeToUseCellFieldData()
        mapper.SelectColorArray(field)
        mapper.SetScalarRange(0.0, 1.0)
        lut = vtk.vtkLookupTable()
        lut.SetHueRange(0.0, 0.33)  # red (poor) to green (cube-like)
        lut.Build()
        mapper.SetLookupTable(lut)
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().EdgeVisibilityOn()
    actor.GetProperty().SetEdgeColor(0.1, 0.1, 0.1)
    return actor, field


def label(text):
    t = vtk.vtkTextActor()
    t.SetInput(text)
    t.GetTextProperty().SetFontSize(16)
    t.GetTextProperty().SetColor(0.1, 0.1, 0.1)
    t.SetPosition(12, 12)
    return t


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    run_dir, surface_path, out_png = sys.argv[1:]

    obj = vtk.vtkOBJReader()
    obj.SetFileName(surface_path)
    hexes, field = hex_actor(run_dir + "/hex_quality.vtk")
    rotation = map_rotation(run_dir)

    panels = [
        (surface_actor(obj.GetOutputPort(), (0.8, 0.8, 0.82)), "input surface"),
        (polycube_actor(boundary_polydata(run_dir + "/simplify/polycube.mesh")), "polycube (faces by axis)"),
        (hexes, "hex mesh" + (": scaled Jacobian, red 0 to green 1" if field else "")),
    ]
    window = vtk.vtkRenderWindow()
    window.SetSize(1200, 400)
    window.SetOffScreenRendering(1)
    camera = None
    for i, (actor, text) in enumerate(panels):
        r = vtk.vtkRenderer()
        r.SetViewport(i / 3, 0, (i + 1) / 3, 1)
        r.SetBackground(1, 1, 1)
        for a in actor if isinstance(actor, list) else [actor]:
            r.AddActor(a)
        r.AddActor2D(label(text))
        if camera is None:
            r.ResetCamera()
            camera = r.GetActiveCamera()
            camera.ParallelProjectionOn()
            camera.Elevation(-55)
            camera.Azimuth(25)
            camera.OrthogonalizeViewUp()
            r.ResetCamera()
            camera.Zoom(1.2)
        else:
            # the polycube has its own size: same direction, its own framing
            c = r.GetActiveCamera()
            c.ParallelProjectionOn()
            turn = rotation if actor is panels[1][0] else np.eye(3)
            direction = np.subtract(camera.GetPosition(), camera.GetFocalPoint())
            c.SetFocalPoint(0, 0, 0)
            c.SetPosition(*(turn @ direction))
            c.SetViewUp(*(turn @ np.array(camera.GetViewUp())))
            r.ResetCamera()
            c.Zoom(1.1)
        window.AddRenderer(r)
    window.Render()
    shot = vtk.vtkWindowToImageFilter()
    shot.SetInput(window)
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(out_png)
    writer.SetInputConnection(shot.GetOutputPort())
    writer.Write()


if __name__ == "__main__":
    main()
