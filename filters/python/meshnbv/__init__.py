"""MeshNBV: next-best-view planning for mesh refinement.

After Morreale, Romanoni, Matteucci, "Predicting the Next Best View for 3D
Mesh Refinement" (2018). The VTK pipeline algorithms are in ``meshnbv.vtk``
(see docs/vtk.md)::

    from meshnbv.vtk import vtkMeshNBVSceneReader, vtkMeshNBVPRIFilter
"""
