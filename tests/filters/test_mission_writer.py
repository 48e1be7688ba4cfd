"""vtkMeshNBVMissionWriter from Python (Debian's /usr/bin/python3).

The fixture's project through reader -> PRI -> next best view -> mission
writer, against `meshnbv mission` on the same suggestions (written by
vtkMeshNBVSuggestionWriter) with the same georeference, take-off point,
keep-out box and options:
- the same files; waypoints.csv equal row by row (positions to 1e-6 scene
  units, WGS84 to 1e-9 degrees), the same flights and notes in mission.json;
- the results the writer reports (photos, flights, minutes, georeference);
- errors: no georeference, an option out of range (named with its range),
  existing files without Overwrite, an ENU origin out of range: each a
  vtkErrorMacro, Write() fails, nothing written.

Usage: test_mission_writer.py <project folder> <scratch folder> <meshnbv>
"""
import csv
import json
import os
import shutil
import subprocess
import sys

from meshnbv.vtk import (
    vtkMeshNBVMissionWriter,
    vtkMeshNBVNextBestViewFilter,
    vtkMeshNBVPRIFilter,
    vtkMeshNBVSceneReader,
    vtkMeshNBVSuggestionWriter,
)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_pipeline import watch_errors  # noqa: E402


def rows(path):
    return list(csv.DictReader(open(path)))


def main():
    project, scratch, cli = sys.argv[1], sys.argv[2], sys.argv[3]
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    georef = os.path.join(scratch, "georef.json")
    with open(georef, "w") as f:
        json.dump({"crs": "EPSG:32632", "transform": [0, -1, 0, 500000, 1, 0, 0, 5000000, 0, 0, 1, 300,
                                                      0, 0, 0, 1]}, f)

    reader = vtkMeshNBVSceneReader()
    reader.SetFileName(os.path.join(project, "project.mlp"))
    pri = vtkMeshNBVPRIFilter()
    pri.SetInputConnection(reader.GetOutputPort(0))
    pri.SetViewsConnection(reader.GetViewsOutputPort())
    nbv = vtkMeshNBVNextBestViewFilter()
    nbv.SetInputConnection(pri.GetOutputPort())
    nbv.SetViewsConnection(reader.GetViewsOutputPort())
    nbv.SetTop(4)
    nbv.SetDirections(16)
    suggestions = vtkMeshNBVSuggestionWriter()
    suggestions.SetInputConnection(nbv.GetOutputPort(1))
    suggestions.SetFileName(os.path.join(scratch, "suggestions.json"))
    assert suggestions.Write() == 1

    writer = vtkMeshNBVMissionWriter()
    messages = watch_errors(writer)
    writer.SetInputConnection(nbv.GetOutputPort(1))
    writer.SetViewsConnection(reader.GetViewsOutputPort())
    writer.SetMeshConnection(reader.GetOutputPort(0))
    vtk_out = os.path.join(scratch, "vtk")
    writer.SetOutputDirectory(vtk_out)
    writer.SetGeoreference(georef)
    writer.SetMaxAltitude(12)
    writer.SetBatteryMinutes(0.4)
    writer.AddKeepOutBox(-1, -1, 0, 1, 1, 40)
    assert writer.GetNumberOfKeepOutBoxes() == 1
    assert writer.GetInfeasible() == vtkMeshNBVMissionWriter.MOVE
    assert writer.Write() == 1 and not messages, messages
    print(f"VTK: {writer.GetNumberOfPhotos()} photos in {writer.GetNumberOfFlights()} flight(s), "
          f"{writer.GetTotalMinutes():.2f} min; {writer.GetGeoreferenceSource()}")
    # Moved below max_altitude (and re-scored), split by the battery.
    assert writer.GetNumberOfPhotos() >= 1 and writer.GetNumberOfFlights() >= 2
    assert "above max_altitude 12 m" in writer.GetNotes(), writer.GetNotes()
    assert "georeference file" in writer.GetGeoreferenceSource()

    cli_out = os.path.join(scratch, "cli")
    r = subprocess.run([cli, "mission", os.path.join(project, "project.mlp"), "--suggestions",
                        os.path.join(scratch, "suggestions.json"), "--georef", georef, "--out", cli_out,
                        "--max-altitude", "12", "--battery-minutes", "0.4", "--keep-out-box", "-1,-1,0,1,1,40"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert sorted(os.listdir(vtk_out)) == sorted(os.listdir(cli_out)), (os.listdir(vtk_out), os.listdir(cli_out))
    a, b = rows(os.path.join(vtk_out, "waypoints.csv")), rows(os.path.join(cli_out, "waypoints.csv"))
    assert len(a) == len(b) == writer.GetNumberOfPhotos()
    for x, y in zip(a, b):
        assert x["label"] == y["label"] and x["flight"] == y["flight"] and x["order"] == y["order"], (x, y)
        for k in ("x", "y", "z"):
            assert abs(float(x[k]) - float(y[k])) < 1e-6, (k, x, y)
        for k in ("latitude", "longitude"):
            assert abs(float(x[k]) - float(y[k])) < 1e-9, (k, x, y)
    ma, mb = (json.load(open(os.path.join(d, "mission.json"))) for d in (vtk_out, cli_out))
    assert ma["notes"] == mb["notes"] and len(ma["flights"]) == len(mb["flights"])
    for fa, fb in zip(ma["flights"], mb["flights"]):
        assert fa["photos"] == fb["photos"] and abs(fa["minutes"] - fb["minutes"]) < 1e-9
    assert abs(writer.GetTotalMinutes() - sum(f["minutes"] for f in mb["flights"])) < 1e-6
    assert writer.GetNotes().count("\n") == len(mb["notes"])
    print(f"equal to `meshnbv mission`: {len(a)} waypoints, {len(ma['notes'])} notes")

    def refused(fragment, out):
        del messages[:]
        writer.SetOutputDirectory(out)
        ok = writer.Write()
        assert ok == 0 and any(fragment in m for m in messages), (fragment, messages)
        assert not os.path.exists(out) or out == vtk_out, f"{out} written despite the error"
        assert writer.GetNumberOfPhotos() == 0

    writer.SetGeoreference("")  # the fixture's photos carry no GPS, its source no CRS
    refused("no georeference", os.path.join(scratch, "none"))
    writer.SetGeoreference("enu:91,9,0")
    refused("the ENU origin must be", os.path.join(scratch, "enu"))
    writer.SetGeoreference(georef)
    writer.SetMaxAltitude(10001)
    refused("max_altitude must be in (0, 10000] metres", os.path.join(scratch, "range"))
    writer.SetMaxAltitude(12)
    before = open(os.path.join(vtk_out, "mission.json")).read()
    refused("exists", vtk_out)
    assert open(os.path.join(vtk_out, "mission.json")).read() == before
    writer.OverwriteOn()
    del messages[:]
    assert writer.Write() == 1 and not messages, messages
    print("errors: one message each, nothing written")


if __name__ == "__main__":
    main()
