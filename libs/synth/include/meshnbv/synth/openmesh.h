// OpenMesh for MeshNBV's decimations (synth::decimate, the report's display
// mesh): the mesh type and the conversion from a TriangleMesh. Include it
// only where OpenMesh is linked (OpenMeshCore, OpenMeshTools).
#pragma once

#include <cstddef>
#include <vector>

#include "meshnbv/mesh.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wdeprecated-copy"
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#pragma GCC diagnostic pop

namespace meshnbv::synth {

struct OmTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<OmTraits>;

// Loads `mesh` into the empty `om`, with vertex, edge and face status and
// face normals, ready for a decimater. OpenMesh holds only manifold,
// consistently oriented surfaces: a face it rejects (an edge with a third
// face, a flipped neighbour, a repeated index, a complex vertex) is not
// added, its index goes to `rejected` and its vertices are locked so that a
// decimation never moves or removes them. Returns, per face of `mesh`, its
// OpenMesh face index (-1 where rejected).
std::vector<int> to_openmesh(const TriangleMesh& mesh, OmMesh& om, std::vector<std::size_t>& rejected);

}  // namespace meshnbv::synth
