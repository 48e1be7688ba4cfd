// Writing PRI results: the mesh with per-face quality and colour, and the
// JSON summary (schema in docs/formats.md).
#pragma once

#include <string>

#include "meshnbv/pri.h"

namespace meshnbv::io {

// Copy of `mesh` with face attributes "quality" (= PRI, NaN where
// undefined) and "pri_views", and face colours from pri_colors() over the
// 5th..95th percentile of the observed PRI.
TriangleMesh mesh_with_pri(const TriangleMesh& mesh, const PriResult& result);

// The per-face PRI (face property "quality") of a PLY written by
// mesh_with_pri + write_ply (`meshnbv pri`), for `mesh`, which is not
// replaced: the file's mesh must be `mesh` -- the same vertex and face
// counts, the same faces, and vertices equal to the precision the file
// stores them at (float or double). Throws Error otherwise ("different
// meshes"), or when the file has no quality.
std::vector<float> read_pri_for_mesh(const std::string& path, const TriangleMesh& mesh);

// The summary as JSON text: counts, percentiles, histogram, the worst
// faces, the options used and the time taken.
std::string pri_summary_json(const PriResult& result, const PriOptions& options,
                             std::size_t worst_k = 10);

}  // namespace meshnbv::io
