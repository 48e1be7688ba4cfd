// Reading a PRI back: the per-face quality of a PLY written by `meshnbv pri`
// (mesh_with_pri in meshnbv/results.h + write_ply), for a scene's own mesh.
#pragma once

#include <string>
#include <vector>

#include "meshnbv/mesh.h"
#include "meshnbv/pri.h"

namespace meshnbv::io {

// The per-face PRI (face property "quality") of a PLY written by
// mesh_with_pri + write_ply (`meshnbv pri`), for `mesh`, which is not
// replaced: the file's mesh must be `mesh` -- the same vertex and face
// counts, the same faces, and vertices equal to the precision the file
// stores them at (float or double). Throws Error otherwise ("different
// meshes"), or when the file has no quality.
std::vector<float> read_pri_for_mesh(const std::string& path, const TriangleMesh& mesh);

// A PLY written by `meshnbv pri` as the previous state of incremental PRI
// (compute_pri with PriPrevious): its mesh and every per-face value
// mesh_with_pri stores, the evidence keys included; the statuses follow
// from quality and pri_views. Throws Error when an attribute is missing
// (a PLY from an older MeshNBV, or not from meshnbv pri) or a value is not
// what mesh_with_pri writes.
PriPrevious read_pri_previous(const std::string& path);

}  // namespace meshnbv::io
