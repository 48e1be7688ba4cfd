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

// The summary as JSON text: counts, percentiles, histogram, the worst
// faces, the options used and the time taken.
std::string pri_summary_json(const PriResult& result, const PriOptions& options,
                             std::size_t worst_k = 10);

}  // namespace meshnbv::io
