"""MeshNBV's VTK 9.1 pipeline algorithms (docs/vtk.md).

- vtkMeshNBVSceneReader: a scene (.mlp, JSON, Middlebury, COLMAP, Bundler)
  -> mesh (port 0) and views (port 1, one vtkImageData per view).
- vtkMeshNBVPRIFilter: mesh + views -> mesh with cell arrays PRI, PRIViews.
- vtkMeshNBVNextBestViewFilter: mesh with PRI + views (+ candidates) ->
  frustums (port 0) and a suggestions table (port 1).
- vtkMeshNBVSuggestionWriter: suggestions -> .json or .mlp.
- vtkMeshNBVMissionWriter: suggestions + views + mesh -> drone mission files
  (KML, DJI WPML KMZ, Litchi CSV, GeoJSON, CSV; docs/missions.md).

Keep every algorithm of a pipeline in a Python variable: Debian's VTK 9.1
crashes when an upstream algorithm is a temporary.
"""
# The base classes' modules first, so that the wrapped classes find them.
import vtkmodules.vtkCommonCore  # noqa: F401
import vtkmodules.vtkCommonDataModel  # noqa: F401
import vtkmodules.vtkCommonExecutionModel  # noqa: F401
import vtkmodules.vtkIOCore  # noqa: F401

from .vtkMeshNBVFilters import (  # noqa: F401
    vtkMeshNBVNextBestViewFilter,
    vtkMeshNBVPRIFilter,
)
from .vtkMeshNBVIO import (  # noqa: F401
    vtkMeshNBVMissionWriter,
    vtkMeshNBVSceneReader,
    vtkMeshNBVSuggestionWriter,
)

__all__ = [
    "vtkMeshNBVMissionWriter",
    "vtkMeshNBVNextBestViewFilter",
    "vtkMeshNBVPRIFilter",
    "vtkMeshNBVSceneReader",
    "vtkMeshNBVSuggestionWriter",
]
