#!/usr/bin/python3
"""MeshNBV as a VTK pipeline: read a project, compute PRI, suggest views.

    xvfb-run -a /usr/bin/python3 sample_projects/vtk/pipeline.py [project] [--out DIR]

Reads a scene (default: ../building/project.mlp next to this script),
computes the per-face Photo-consistency Reconstruction Index, suggests the
next views (Morreale, Romanoni, Matteucci, "Predicting the Next Best View
for 3D Mesh Refinement", 2018) and writes into --out (default out/vtk at the
top of the repository):

    mesh_pri.vtp       the mesh with cell arrays PRI and PRIViews
    frustums.vtp       one pyramid per suggestion (cell arrays rank, energy, RGB)
    suggestions.json   the suggestions document (docs/formats.md)
    suggestions.mlp    the project plus one raster per suggestion (MeshLab)
    pipeline.png       the mesh coloured by PRI (green best, red worst, grey
                       unobserved) with the suggested frustums, rendered off screen

Needs Debian's VTK Python (/usr/bin/python3) and PYTHONPATH pointing at the
build's lib/python3/dist-packages (or an installed prefix's). Rendering needs
an X display: run it under xvfb-run, or pass --no-render. Every algorithm is
kept in a variable: Debian's VTK 9.1 crashes on temporary upstream algorithms.
"""
import argparse
import math
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

from meshnbv.vtk import (
    vtkMeshNBVNextBestViewFilter,
    vtkMeshNBVPRIFilter,
    vtkMeshNBVSceneReader,
    vtkMeshNBVSuggestionWriter,
)

HERE = os.path.dirname(os.path.abspath(__file__))


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("project", nargs="?", default=os.path.join(HERE, "..", "building", "project.mlp"),
                        help="scene: .mlp, .json, Middlebury or COLMAP folder, bundle.out")
    parser.add_argument("--out", default=os.path.join(HERE, "..", "..", "out", "vtk"),
                        help="output folder (created; files in it are replaced)")
    parser.add_argument("--measure", choices=("ssd", "ncc"), default="ssd")
    parser.add_argument("--candidates", choices=("given", "sampled", "refined"), default="sampled")
    parser.add_argument("--top", type=int, default=3, help="number of suggestions")
    parser.add_argument("--size", default="1000x750", help="PNG size WxH")
    parser.add_argument("--no-render", action="store_true", help="skip the PNG")
    return parser.parse_args()


def render(mesh, frustums, size, png):
    """Off-screen PNG of the mesh coloured by PRI with the suggested frustums."""
    import vtkmodules.vtkInteractionStyle  # noqa: F401  (registers factories)
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
    from vtkmodules.vtkCommonCore import vtkLookupTable
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
    from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                             vtkRenderWindow, vtkWindowToImageFilter)

    pri = vtk_to_numpy(mesh.GetCellData().GetArray("PRI"))
    lo, hi = np.nanpercentile(pri, [5, 95])  # the CLI's colour range
    lut = vtkLookupTable()
    lut.SetHueRange(1.0 / 3.0, 0.0)  # green (best) to red (worst)
    lut.SetNanColor(0.6, 0.6, 0.6, 1.0)
    lut.Build()
    mesh_mapper = vtkPolyDataMapper()
    mesh_mapper.SetInputData(mesh)
    mesh_mapper.SetScalarModeToUseCellFieldData()
    mesh_mapper.SelectColorArray("PRI")
    mesh_mapper.SetLookupTable(lut)
    mesh_mapper.SetScalarRange(float(lo), float(hi))
    mesh_actor = vtkActor()
    mesh_actor.SetMapper(mesh_mapper)

    frustum_mapper = vtkPolyDataMapper()
    frustum_mapper.SetInputData(frustums)
    frustum_mapper.SetScalarModeToUseCellFieldData()
    frustum_mapper.SelectColorArray("RGB")
    frustum_mapper.SetColorModeToDirectScalars()
    frustum_actor = vtkActor()
    frustum_actor.SetMapper(frustum_mapper)
    frustum_actor.GetProperty().SetOpacity(0.6)
    frustum_actor.GetProperty().EdgeVisibilityOn()

    bar = vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle("PRI")
    bar.SetNumberOfLabels(3)
    bar.SetWidth(0.08)
    bar.SetHeight(0.5)

    renderer = vtkRenderer()
    renderer.SetBackground(1.0, 1.0, 1.0)
    renderer.AddActor(mesh_actor)
    renderer.AddActor(frustum_actor)
    renderer.AddActor2D(bar)
    # Look at the mesh from beside the best suggestion (turned 35 degrees so
    # that its frustum does not hide the region it looks at), from 30 degrees
    # above the horizon, z up.
    bounds = mesh.GetBounds()
    centre = np.array([(bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2])
    apex = vtk_to_numpy(frustums.GetPoints().GetData())[0] if frustums.GetNumberOfPoints() else centre + 1
    azimuth = math.atan2(apex[1] - centre[1], apex[0] - centre[0]) + math.radians(35)
    elevation = math.radians(30)
    direction = np.array([math.cos(azimuth) * math.cos(elevation), math.sin(azimuth) * math.cos(elevation),
                          math.sin(elevation)])
    camera = renderer.GetActiveCamera()
    camera.SetFocalPoint(*centre)
    camera.SetPosition(*(centre + direction))
    camera.SetViewUp(0, 0, 1)
    renderer.ResetCamera()
    camera.Zoom(1.3)

    width, height = (int(v) for v in size.lower().split("x"))
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(width, height)
    window.AddRenderer(renderer)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    writer = vtkPNGWriter()
    writer.SetInputConnection(grab.GetOutputPort())
    writer.SetFileName(png)
    writer.Write()


def main():
    args = parse_arguments()
    os.makedirs(args.out, exist_ok=True)
    out = lambda name: os.path.join(args.out, name)

    reader = vtkMeshNBVSceneReader()
    reader.SetFileName(args.project)

    pri = vtkMeshNBVPRIFilter()
    pri.SetInputConnection(reader.GetOutputPort(0))
    pri.SetViewsConnection(reader.GetViewsOutputPort())
    if args.measure == "ncc":
        pri.SetMeasureToNCC()

    nbv = vtkMeshNBVNextBestViewFilter()
    nbv.SetInputConnection(pri.GetOutputPort())
    nbv.SetViewsConnection(reader.GetViewsOutputPort())
    getattr(nbv, "SetCandidatesTo" + args.candidates.capitalize())()
    nbv.SetTop(args.top)
    nbv.Update()
    mesh = pri.GetOutput()
    if mesh.GetNumberOfCells() == 0 or nbv.GetSuggestionsOutput().GetNumberOfRows() == 0:
        sys.exit("pipeline failed (see the VTK error above)")

    mesh_writer = vtkXMLPolyDataWriter()
    mesh_writer.SetInputConnection(pri.GetOutputPort())
    mesh_writer.SetFileName(out("mesh_pri.vtp"))
    mesh_writer.Write()
    frustum_writer = vtkXMLPolyDataWriter()
    frustum_writer.SetInputConnection(nbv.GetOutputPort(0))
    frustum_writer.SetFileName(out("frustums.vtp"))
    frustum_writer.Write()
    json_writer = vtkMeshNBVSuggestionWriter()
    json_writer.SetInputConnection(nbv.GetSuggestionsOutputPort())
    json_writer.SetFileName(out("suggestions.json"))
    json_writer.OverwriteOn()
    mlp_writer = vtkMeshNBVSuggestionWriter()
    mlp_writer.SetInputConnection(nbv.GetSuggestionsOutputPort())
    mlp_writer.SetViewsConnection(reader.GetViewsOutputPort())
    mlp_writer.SetMeshConnection(pri.GetOutputPort())
    mlp_writer.SetFileName(out("suggestions.mlp"))
    mlp_writer.OverwriteOn()
    if not (json_writer.Write() and mlp_writer.Write()):
        sys.exit("writing the suggestions failed (see the VTK error above)")

    values = vtk_to_numpy(mesh.GetCellData().GetArray("PRI"))
    observed = values[~np.isnan(values)]
    print(f"{args.project}: {values.size} faces, {observed.size} observed, "
          f"{reader.GetViewsOutput().GetNumberOfBlocks()} views; PRI ({pri.GetMeasureAsString()}) "
          f"median {np.median(observed):.3g}, 95% {np.percentile(observed, 95):.3g}")
    table = nbv.GetSuggestionsOutput()
    centres = vtk_to_numpy(table.GetColumnByName("centre"))
    for row in range(table.GetNumberOfRows()):
        terms = ", ".join(f"{term} {table.GetColumnByName(term).GetValue(row):.2f}"
                          for term in ("occlusion", "focus", "parallax", "incidence"))
        print(f"{table.GetColumnByName('label').GetValue(row)}: energy "
              f"{table.GetColumnByName('energy').GetValue(row):.2f} ({terms}), centre "
              f"({', '.join(f'{c:.2f}' for c in centres[row])}), sees "
              f"{table.GetColumnByName('seen_faces').GetValue(row)} worst faces")
    if not args.no_render:
        render(mesh, nbv.GetOutput(0), args.size, out("pipeline.png"))
    written = ["mesh_pri.vtp", "frustums.vtp", "suggestions.json", "suggestions.mlp"]
    written += [] if args.no_render else ["pipeline.png"]
    print("written to " + os.path.normpath(args.out) + ": " + ", ".join(written))


if __name__ == "__main__":
    main()
