"""The whole VTK pipeline from Python (Debian's /usr/bin/python3).

Reads the synthetic project of the vtk/setup_project fixture, computes PRI,
suggests views, writes .vtp and JSON, and asserts numbers:
- the PRI cell array equals the CLI's (`meshnbv pri`, face `quality` of its
  PLY) to 1e-6, NaN where the CLI has NaN, also after a .vtp round trip,
  and PRIViews, PRIPairs, PRISamples, PRITexture equal its pri_views,
  pri_pairs, pri_samples, pri_texture exactly, for ssd and for offset;
- the suggestions table equals the JSON document the writer wrote;
- each frustum's apex is its camera centre (C = -R^T t) and its four other
  points lie on the viewing rays of the image's outer corners (pixel
  centres at integers: the corners are (-0.5, -0.5) ... (W-0.5, H-0.5));
- a PRI filter without views reports an error and produces no output;
- (under a display) an off-screen render of the mesh coloured by PRI with
  the frustums is neither empty nor flat: the one, loose, image check.

Usage: test_pipeline.py <project folder> <scratch folder>
"""
import json
import os
import shutil
import sys

import numpy as np
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_STRING
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter

from meshnbv.vtk import (
    vtkMeshNBVNextBestViewFilter,
    vtkMeshNBVPRIFilter,
    vtkMeshNBVSceneReader,
    vtkMeshNBVSuggestionWriter,
)

PLY_TYPES = {"char": "i1", "uchar": "u1", "short": "<i2", "ushort": "<u2", "int": "<i4",
             "uint": "<u4", "float": "<f4", "double": "<f8"}


def read_ply_faces(path):
    """Per-face properties of a binary little-endian triangle PLY (as the CLI writes)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    elements, current = [], None
    for line in data[:end].decode().splitlines():
        words = line.split()
        if words[0] == "format":
            assert words[1] == "binary_little_endian", words
        elif words[0] == "element":
            current = (words[1], int(words[2]), [])
            elements.append(current)
        elif words[0] == "property" and words[1] == "list":
            current[2].append(("count", PLY_TYPES[words[2]]))
            current[2].append((words[4], PLY_TYPES[words[3]], (3,)))  # triangles only
        elif words[0] == "property":
            current[2].append((words[2], PLY_TYPES[words[1]]))
    offset = end
    for name, count, fields in elements:
        array = np.frombuffer(data, dtype=np.dtype(fields), count=count, offset=offset)
        offset += array.nbytes
        if name == "face":
            assert np.all(array["count"] == 3)
            return array
    raise AssertionError("no face element in " + path)


def same(a, b, tolerance):
    """Both NaN, or within tolerance, everywhere."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and np.array_equal(np.isnan(a), np.isnan(b)) and \
        np.all(np.abs(a[~np.isnan(a)] - b[~np.isnan(b)]) <= tolerance)


def watch_errors(algorithm):
    """The ErrorEvent messages of an algorithm (also kept off the console)."""
    messages = []

    @calldata_type(VTK_STRING)
    def on_error(caller, event, message):
        messages.append(message)

    algorithm.AddObserver("ErrorEvent", on_error)
    algorithm.GetExecutive().AddObserver("ErrorEvent", lambda *args: None)
    return messages


def check_evidence(mesh, cli, what):
    """PRIViews, PRIPairs, PRISamples, PRITexture equal the CLI PLY's properties."""
    cells = mesh.GetCellData()
    for array, prop in (("PRIViews", "pri_views"), ("PRIPairs", "pri_pairs"),
                        ("PRISamples", "pri_samples"), ("PRITexture", "pri_texture")):
        values = cells.GetArray(array)
        assert values is not None, f"{what}: no {array}"
        assert same(vtk_to_numpy(values), cli[prop], 0.0), f"{what}: {array} differs from the CLI's {prop}"
    observed = ~np.isnan(cli["quality"])
    assert np.all(vtk_to_numpy(cells.GetArray("PRIPairs"))[observed] >= 1), what
    assert np.all(vtk_to_numpy(cells.GetArray("PRISamples"))[observed] >= 3), what


def check_frustums(frustums, table):
    points = vtk_to_numpy(frustums.GetPoints().GetData()).reshape(-1, 5, 3)
    column = lambda name: vtk_to_numpy(table.GetColumnByName(name))
    assert points.shape[0] == table.GetNumberOfRows() and frustums.GetNumberOfCells() == 6 * points.shape[0]
    scale = 10 * np.linalg.norm(np.ptp(points.reshape(-1, 3), axis=0))
    for row in range(points.shape[0]):
        R = column("R")[row].reshape(3, 3)
        t = column("t")[row]
        w, h = column("width")[row], column("height")[row]
        fx, fy, cx, cy = (column(name)[row] for name in ("fx", "fy", "cx", "cy"))
        centre = -R.T @ t
        assert np.allclose(centre, column("centre")[row], atol=1e-9 * scale)
        pts = points[row]
        apex = [i for i in range(5) if np.linalg.norm(pts[i] - centre) <= 1e-9 * scale]
        assert len(apex) == 1, (row, pts, centre)
        hit = []
        for u, v in ((-0.5, -0.5), (w - 0.5, -0.5), (w - 0.5, h - 0.5), (-0.5, h - 0.5)):
            ray = R.T @ np.array([(u - cx) / fx, (v - cy) / fy, 1.0])
            ray /= np.linalg.norm(ray)
            for i in range(5):
                d = pts[i] - centre
                if i != apex[0] and d @ ray > 0 and np.linalg.norm(d - (d @ ray) * ray) <= 1e-9 * scale:
                    hit.append(i)
        assert sorted(hit) == sorted(set(range(5)) - set(apex)), (row, hit)


def render(mesh, frustums, png):
    """Off-screen PNG of the mesh coloured by PRI with the frustums; the pixels as an array."""
    import vtkmodules.vtkInteractionStyle  # noqa: F401  (factories)
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                             vtkRenderWindow, vtkWindowToImageFilter)
    mesh_mapper = vtkPolyDataMapper()
    mesh_mapper.SetInputData(mesh)
    mesh_mapper.SetScalarModeToUseCellFieldData()
    mesh_mapper.SelectColorArray("PRI")
    pri = vtk_to_numpy(mesh.GetCellData().GetArray("PRI"))
    mesh_mapper.SetScalarRange(0.0, float(np.nanpercentile(pri, 95)))
    mesh_mapper.ScalarVisibilityOn()
    frustum_mapper = vtkPolyDataMapper()
    frustum_mapper.SetInputData(frustums)
    frustum_mapper.SetScalarModeToUseCellFieldData()
    frustum_mapper.SelectColorArray("RGB")
    frustum_mapper.SetColorModeToDirectScalars()
    renderer = vtkRenderer()
    renderer.SetBackground(1.0, 1.0, 1.0)
    for mapper in (mesh_mapper, frustum_mapper):
        actor = vtkActor()
        actor.SetMapper(mapper)
        renderer.AddActor(actor)
    renderer.ResetCamera()
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(400, 300)
    window.AddRenderer(renderer)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(png)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    image = grab.GetOutput()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars())[:, :3]
    return pixels


def main():
    project, scratch = sys.argv[1], sys.argv[2]
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)

    reader = vtkMeshNBVSceneReader()
    reader.SetFileName(os.path.join(project, "project.mlp"))
    pri = vtkMeshNBVPRIFilter()
    pri.SetInputConnection(reader.GetOutputPort(0))
    pri.SetViewsConnection(reader.GetViewsOutputPort())
    nbv = vtkMeshNBVNextBestViewFilter()
    nbv.SetInputConnection(pri.GetOutputPort())
    nbv.SetViewsConnection(reader.GetViewsOutputPort())
    nbv.SetTop(2)
    nbv.Update()
    assert pri.GetMeasureAsString() == "ssd" and pri.GetMaxIncidenceAngle() == 80.0
    assert nbv.GetCandidatesAsString() == "sampled" and (nbv.GetWeightOcclusion(), nbv.GetWeightFocus(), nbv.GetWeightParallax(), nbv.GetWeightIncidence()) == (0.6, 1.6, 2.1, 0.6)

    # PRI equals the CLI's.
    mesh = pri.GetOutput()
    values = vtk_to_numpy(mesh.GetCellData().GetArray("PRI"))
    cli = read_ply_faces(os.path.join(project, "pri_ssd.ply"))
    assert same(values, cli["quality"], 1e-6), "PRI differs from the CLI"
    assert np.array_equal(vtk_to_numpy(mesh.GetCellData().GetArray("PRIViews")), cli["pri_views"])
    check_evidence(mesh, cli, "ssd")
    n = cli["pri_views"][~np.isnan(cli["quality"])]
    assert np.array_equal(cli["pri_pairs"][~np.isnan(cli["quality"])], n * (n - 1) / 2)
    observed = int(np.count_nonzero(~np.isnan(values)))
    print(f"PRI: {observed} of {values.size} faces observed, max |PRI - CLI| = "
          f"{np.nanmax(np.abs(values - cli['quality'])):.3g}")

    # offset, with the fixture's non-default sweep: the same values as the CLI.
    offset = vtkMeshNBVPRIFilter()
    offset.SetInputConnection(reader.GetOutputPort(0))
    offset.SetViewsConnection(reader.GetViewsOutputPort())
    offset.SetMeasureToOffset()
    offset.SetSupportRadius(3)
    offset.SetOffsetRange(3)
    offset.SetOffsetSteps(3)
    offset.Update()
    assert offset.GetMeasureAsString() == "offset" and offset.GetMeasure() == vtkMeshNBVPRIFilter.OFFSET
    cli_offset = read_ply_faces(os.path.join(project, "pri_offset.ply"))
    offset_pri = vtk_to_numpy(offset.GetOutput().GetCellData().GetArray("PRI"))
    assert same(offset_pri, cli_offset["quality"], 1e-6), "offset PRI differs from the CLI"
    check_evidence(offset.GetOutput(), cli_offset, "offset")
    print(f"offset: {int(np.count_nonzero(~np.isnan(offset_pri)))} faces observed, median "
          f"{np.nanmedian(offset_pri):.3g} scene units, equal to the CLI with its evidence")

    # .vtp files; the PRI survives the round trip.
    mesh_writer = vtkXMLPolyDataWriter()
    mesh_writer.SetInputConnection(pri.GetOutputPort())
    mesh_writer.SetFileName(os.path.join(scratch, "mesh_pri.vtp"))
    assert mesh_writer.Write() == 1
    frustum_writer = vtkXMLPolyDataWriter()
    frustum_writer.SetInputConnection(nbv.GetOutputPort(0))
    frustum_writer.SetFileName(os.path.join(scratch, "frustums.vtp"))
    assert frustum_writer.Write() == 1
    vtp = vtkXMLPolyDataReader()
    vtp.SetFileName(os.path.join(scratch, "mesh_pri.vtp"))
    vtp.Update()
    assert same(vtk_to_numpy(vtp.GetOutput().GetCellData().GetArray("PRI")), cli["quality"], 1e-6)

    # The table equals the JSON the writer wrote.
    table = nbv.GetSuggestionsOutput()
    writer = vtkMeshNBVSuggestionWriter()
    writer.SetInputConnection(nbv.GetSuggestionsOutputPort())
    writer.SetFileName(os.path.join(scratch, "suggestions.json"))
    assert writer.Write() == 1
    with open(os.path.join(scratch, "suggestions.json")) as f:
        doc = json.load(f)
    assert len(doc["suggestions"]) == table.GetNumberOfRows() == 2
    for row, s in enumerate(doc["suggestions"]):
        assert table.GetColumnByName("label").GetValue(row) == s["label"] == f"nbv_{row + 1}"
        for term in ("occlusion", "focus", "parallax", "incidence"):
            assert abs(table.GetColumnByName(term).GetValue(row) - s["energy"][term]) <= 1e-9
        assert abs(table.GetColumnByName("energy").GetValue(row) - s["energy"]["total"]) <= 1e-9
        assert np.allclose(vtk_to_numpy(table.GetColumnByName("centre"))[row], s["centre"], atol=1e-9)
    energies = vtk_to_numpy(table.GetColumnByName("energy"))
    print(f"suggestions: energies {energies.round(3).tolist()}, equal to the JSON document")

    check_frustums(nbv.GetOutput(0), table)
    print("frustums: apex at the camera centre, corners on the image corners' rays (1e-9)")

    # Error path: no views input.
    lonely = vtkMeshNBVPRIFilter()
    errors = watch_errors(lonely)
    lonely.SetInputConnection(reader.GetOutputPort(0))
    lonely.Update()
    assert len(errors) == 1 and "no views input" in errors[0], errors
    assert lonely.GetOutput().GetNumberOfCells() == 0
    print("no views input:", errors[0])

    if os.environ.get("MESHNBV_NO_RENDER"):
        print("rendering skipped (MESHNBV_NO_RENDER)")
        return
    pixels = render(mesh, nbv.GetOutput(0), os.path.join(scratch, "pipeline.png"))
    background = np.all(pixels == 255, axis=1)
    colours = len(np.unique(pixels[~background] // 32, axis=0))
    share = 1.0 - background.mean()
    print(f"render: {share:.1%} of the pixels drawn, {colours} colour bins")
    assert 0.01 <= share <= 0.95 and colours >= 8, "the render is empty or flat"


if __name__ == "__main__":
    main()
