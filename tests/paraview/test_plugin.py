"""The MeshNBV ParaView plugin from pvpython (Debian's ParaView 5.11).

- the plugin loads (LoadPlugin, as the Plugin Manager does) and its four
  proxies exist: MeshNBV Scene Reader, Compute PRI, Suggest Next View, the
  suggestion writer;
- File > Open's choice: OpenDataFile picks the MeshNBV reader for a .mlp
  and for a *_par.txt, and the reader's mesh has the faces `meshnbv info`
  counts;
- the panels carry the core's option tables (`meshnbv options --json`):
  every option of `pri` on Compute PRI and of `suggest` on Suggest Next
  View, by its VTK name, at its default, with the table's range (domain
  ends, special values included) and its choices;
- Compute PRI's PRI array equals the CLI's PLY quality (`meshnbv pri`) to
  1e-6, NaN where the CLI has NaN, and PRIViews equals pri_views;
- Suggest Next View's table gives the CLI's suggestions (`meshnbv suggest`
  on the CLI's PLY): same labels, centres to 1e-6; the writer writes the
  same JSON suggestions;
- shown in a render view, the mesh is coloured by PRI (cell data) through
  the green-yellow-red map with grey for NaN, and the picture holds green
  and red pixels.

Usage: pvpython test_plugin.py PLUGIN MESHNBV SCENE WORK
"""
import json
import math
import os
import shutil
import subprocess
import sys

from paraview import servermanager as sm
from paraview import simple

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "support"))
from ply_faces import read_face_properties  # noqa: E402


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def run(*args):
    r = subprocess.run(list(args), capture_output=True, text=True)
    check(r.returncode == 0, f"{' '.join(args)}: {r.stderr.strip()}")
    return r.stdout


def domain_range(prop):
    """(min, max) of a property's range domain, None where it has no bound."""
    domain = prop.SMProperty.GetDomain("range")
    if domain is None:
        return None, None
    lo = domain.GetMinimum(0) if domain.GetMinimumExists(0) else None
    hi = domain.GetMaximum(0) if domain.GetMaximumExists(0) else None
    return lo, hi


def check_options(proxy, table, what):
    for o in table:
        name = o["vtk"]
        check(name in proxy.ListProperties(), f"{what}: no property {name}")
        prop = proxy.GetProperty(name)
        value = prop.GetData()
        if o["type"] == "bool":
            check(value == int(o["default"]), f"{what}.{name}: default {value}, table {o['default']}")
        elif o["type"] == "choice":
            # The enumeration's words and default, in the table's order.
            enum = prop.SMProperty.GetDomain("enum")
            words = [enum.GetEntryText(i) for i in range(enum.GetNumberOfEntries())]
            values = [enum.GetEntryValue(i) for i in range(enum.GetNumberOfEntries())]
            check(words == o["choices"], f"{what}.{name}: words {words}, table {o['choices']}")
            check(values == list(range(len(words))), f"{what}.{name}: values {values}")
            # pvpython shows an enumeration's value as its word.
            check(value == o["default"], f"{what}.{name}: default {value}, table {o['default']}")
        else:
            check(math.isclose(float(value), float(o["default"]), rel_tol=1e-12, abs_tol=0),
                  f"{what}.{name}: default {value}, table {o['default']}")
            lo, hi = domain_range(prop)
            specials = [s["value"] for s in o["specials"]]
            want_lo = None if o["min"] is None else min([o["min"]] + specials)
            want_hi = None if o["max"] is None else max([o["max"]] + specials)
            check((lo is None) == (want_lo is None) and (lo is None or math.isclose(lo, want_lo)),
                  f"{what}.{name}: minimum {lo}, table {want_lo} ({o['range']})")
            check((hi is None) == (want_hi is None) and (hi is None or math.isclose(hi, want_hi)),
                  f"{what}.{name}: maximum {hi}, table {want_hi} ({o['range']})")
            doc = prop.SMProperty.GetDocumentation().GetDescription()
            check(o["range"] in doc, f"{what}.{name}: documentation without its range: {doc}")
    print(f"{what}: {len(table)} options as in the table")


def main():
    plugin, cli, scene, work = sys.argv[1:5]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)

    # The CLI's results on the same scene.
    tables = json.loads(run(cli, "options", "--json"))
    run(cli, "pri", scene, "--out", os.path.join(work, "cli.ply"), "--quiet")
    run(cli, "suggest", scene, "--pri", os.path.join(work, "cli.ply"), "--top", "2",
        "--out", os.path.join(work, "cli_suggestions.json"), "--quiet")
    _, cli_faces = read_face_properties(os.path.join(work, "cli.ply"))

    simple.LoadPlugin(plugin, remote=False, ns=vars(simple))
    for name in ("MeshNBVSceneReader", "ComputePRI", "SuggestNextView"):
        check(hasattr(simple, name), f"the plugin gave no {name}")

    # File > Open: the reader is ParaView's choice for a MeshNBV scene.
    reader = simple.OpenDataFile(scene)
    check(reader is not None and reader.GetXMLName() == "MeshNBVSceneReader",
          f"OpenDataFile({scene}) made {reader and reader.GetXMLName()}")
    reader.UpdatePipeline()
    faces = reader.GetDataInformation(0).GetNumberOfCells()
    check(faces == len(cli_faces), f"reader: {faces} faces, the CLI's PLY {len(cli_faces)}")
    par = os.path.join(work, "ring_par.txt")
    with open(par, "w") as f:
        f.write("0\n")
    factory = sm.vtkSMProxyManager.GetProxyManager().GetReaderFactory()
    # File > Open lists every reader that matches (group, name, description).
    possible = factory.GetPossibleReaders(par, sm.ActiveConnection.Session)
    readers = [possible.GetString(i) for i in range(1, possible.GetNumberOfStrings(), 3)]
    check("MeshNBVSceneReader" in readers, f"*_par.txt opens with {readers}")
    print(f"reader: {faces} faces; File > Open offers it for .mlp and *_par.txt")

    # Compute PRI: the panel and the values.
    pri = simple.ComputePRI(Input=simple.OutputPort(reader, 0), Views=simple.OutputPort(reader, 1))
    check_options(pri, tables["pri"], "Compute PRI")
    pri.UpdatePipeline()
    data = sm.Fetch(pri)
    values = data.GetCellData().GetArray("PRI")
    views = data.GetCellData().GetArray("PRIViews")
    check(values is not None and values.GetNumberOfTuples() == len(cli_faces), "no PRI array")
    worst, observed = 0.0, 0
    for i, face in enumerate(cli_faces):
        a, b = values.GetValue(i), face["quality"]
        if math.isnan(b):
            check(math.isnan(a), f"face {i}: PRI {a}, the CLI has NaN")
            continue
        observed += 1
        check(abs(a - b) <= 1e-6, f"face {i}: PRI {a}, the CLI {b}")
        check(views.GetValue(i) == face["pri_views"], f"face {i}: views {views.GetValue(i)}")
        worst = max(worst, abs(a - b))
    check(observed > 0, "no face observed")
    print(f"Compute PRI: {observed} of {len(cli_faces)} faces observed, max |PRI - CLI| = {worst:.3g}")

    # Suggest Next View: the CLI's suggestions, and the writer.
    nbv = simple.SuggestNextView(Input=pri, Views=simple.OutputPort(reader, 1))
    check_options(nbv, tables["suggest"], "Suggest Next View")
    nbv.Top = 2
    nbv.UpdatePipeline()
    out_json = os.path.join(work, "suggestions.json")
    writer = simple.CreateWriter(out_json, simple.OutputPort(nbv, 1))
    check(writer.GetXMLName() == "MeshNBVSuggestionWriter", f"writer for .json: {writer.GetXMLName()}")
    writer.UpdatePipeline()
    ours = json.load(open(out_json))["suggestions"]
    theirs = json.load(open(os.path.join(work, "cli_suggestions.json")))["suggestions"]
    check(len(ours) == len(theirs) == 2, f"{len(ours)} suggestions, the CLI {len(theirs)}")
    for a, b in zip(ours, theirs):
        check(a["label"] == b["label"], f"labels {a['label']} / {b['label']}")
        ca, cb = a["centre"], b["centre"]
        check(all(abs(x - y) <= 1e-6 * max(1.0, abs(y)) for x, y in zip(ca, cb)),
              f"{a['label']}: centre {ca}, the CLI {cb}")
    print(f"Suggest Next View: {len(ours)} suggestions, the CLI's; written by the writer")

    # Shown: coloured by PRI through the plugin's map.
    view = simple.CreateRenderView()
    view.ViewSize = [480, 360]
    display = simple.Show(pri, view)
    check(list(display.ColorArrayName) == ["CELLS", "PRI"],
          f"the mesh is coloured by {list(display.ColorArrayName)}, not PRI")
    lut = simple.GetColorTransferFunction("PRI")
    points = list(lut.RGBPoints)
    colours = [tuple(points[i + 1:i + 4]) for i in range(0, len(points), 4)]
    check(colours[0] == (0.0, 1.0, 0.0) and colours[-1] == (1.0, 0.0, 0.0),
          f"PRI colour map {colours}: not green to red")
    check(all(abs(c - 160 / 255) < 1e-6 for c in lut.NanColor), f"NaN colour {list(lut.NanColor)}")
    simple.ResetCamera(view)
    png = os.path.join(work, "pri.png")
    simple.SaveScreenshot(png, view, ImageResolution=[480, 360])
    from vtkmodules.vtkIOImage import vtkPNGReader
    image = vtkPNGReader()
    image.SetFileName(png)
    image.Update()
    pixels = image.GetOutput().GetPointData().GetScalars()
    green = red = 0
    for i in range(pixels.GetNumberOfTuples()):
        r, g, b = pixels.GetTuple(i)[:3]
        green += g > 150 and r < 120 and b < 80
        red += r > 150 and g < 120 and b < 80
    check(green > 100 and red > 20, f"picture: {green} green and {red} red pixels")
    print(f"shown: coloured by PRI, {green} green and {red} red pixels in {png}")
    print("paraview plugin: OK")


if __name__ == "__main__":
    main()
