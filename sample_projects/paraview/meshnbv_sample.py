"""MeshNBV in ParaView: the bundled sample project (sample_projects/building)
read, its PRI computed, three next views suggested and shown.

The mesh is coloured by PRI (green best, red worst, grey where fewer than
two views see a face) and the suggested views are drawn as frustums, red
for the best to yellow. A Python state: run it in the GUI (View > Python
Shell > Run Script, or `paraview --script=meshnbv_sample.py`) or in
pvpython, which also saves a picture:

    pvpython sample_projects/paraview/meshnbv_sample.py [--screenshot OUT.png] [--state OUT.pvsm]

--state saves the pipeline as a ParaView state, which the GUI opens with
`paraview --state=OUT.pvsm` (plugins/paraview/tools/gui_screenshot.sh).

The plugin is loaded from $MESHNBV_PARAVIEW_PLUGIN, else from the build
folder scripts/run-sample.sh and scripts/test.sh use (build/release,
build/ci); once loaded from the Plugin Manager (Auto Load), nothing is
needed.
"""
import glob
import os
import sys

from paraview import simple

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))
SCENE = os.path.join(REPO, "sample_projects", "building", "project.mlp")


def plugin_path():
    path = os.environ.get("MESHNBV_PARAVIEW_PLUGIN")
    if path:
        return path
    for build in ("build/release", "build/ci"):
        found = glob.glob(os.path.join(REPO, build, "plugins/paraview/lib/**/MeshNBV.so"), recursive=True)
        if found:
            return found[0]
    sys.exit("meshnbv_sample.py: no MeshNBV plugin: build with -DMESHNBV_BUILD_PARAVIEW=ON "
             "or set MESHNBV_PARAVIEW_PLUGIN to MeshNBV.so")


def load_plugin():
    if not hasattr(simple, "MeshNBVSceneReader"):
        simple.LoadPlugin(plugin_path(), remote=False, ns=vars(simple))


def build(view):
    """The pipeline of the sample, shown in `view`; returns its proxies."""
    reader = simple.MeshNBVSceneReader(registrationName="building", FileName=SCENE)
    pri = simple.ComputePRI(registrationName="Compute PRI", Input=simple.OutputPort(reader, 0),
                                   Views=simple.OutputPort(reader, 1))
    nbv = simple.SuggestNextView(registrationName="Suggest Next View", Input=pri,
                                        Views=simple.OutputPort(reader, 1))
    nbv.Top = 3

    mesh = simple.Show(pri, view)
    simple.ColorBy(mesh, ("CELLS", "PRI"))
    # The report's colour range: the 5th to 95th percentile of the observed
    # faces (ParaView's default, min to max, lets a few faces set the scale).
    pri.UpdatePipeline()
    from paraview import servermanager
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import numpy as np
    values = vtk_to_numpy(servermanager.Fetch(pri).GetCellData().GetArray("PRI"))
    values = values[~np.isnan(values)]
    lut = simple.GetColorTransferFunction("PRI")
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(float(np.percentile(values, 5)), float(np.percentile(values, 95)))
    mesh.SetScalarBarVisibility(view, True)
    bar = simple.GetScalarBar(lut, view)
    bar.Title = f"PRI ({pri.Measure.GetData()}): green best, red worst"
    bar.ComponentTitle = ""
    bar.Orientation = "Horizontal"
    bar.WindowLocation = "Lower Center"
    bar.ScalarBarLength = 0.4
    bar.TitleFontSize = 14
    bar.LabelFontSize = 12
    frustums = simple.Show(simple.OutputPort(nbv, 0), view)
    frustums.Representation = "Wireframe"
    frustums.LineWidth = 3.0
    simple.ColorBy(frustums, ("CELLS", "RGB"))
    frustums.MapScalars = 0  # the frustums' own colours, red (best) to yellow
    simple.Hide(reader, view)
    return reader, pri, nbv


def frame(view, mesh_source):
    """Looks at the mesh from above one corner; the frustums in the picture too."""
    bounds = mesh_source.GetDataInformation().GetBounds()
    centre = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[0] + 1.0, centre[1] - 1.2, centre[2] + 0.9]
    view.CameraViewUp = [0, 0, 1]
    simple.ResetCamera(view)


def main():
    load_plugin()
    view = simple.GetActiveViewOrCreate("RenderView")
    view.OrientationAxesVisibility = 1
    _, pri, _ = build(view)
    frame(view, pri)
    simple.Render(view)
    if "--screenshot" in sys.argv:
        out = sys.argv[sys.argv.index("--screenshot") + 1]
        simple.SaveScreenshot(out, view, ImageResolution=[1024, 768], FontScaling="Do not scale fonts")
        print("screenshot:", out)
    if "--state" in sys.argv:
        out = sys.argv[sys.argv.index("--state") + 1]
        simple.SaveState(out)
        print("state:", out)


main()
