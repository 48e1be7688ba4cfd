// Results as meshes and JSON text, shared by every front end: the mesh with
// its PRI, the frustums of the suggestions, and the JSON summaries (schemas
// in docs/formats.md). No file is written here (meshnbv::io does that).
#pragma once

#include <cstddef>
#include <string>

#include "meshnbv/planner.h"
#include "meshnbv/pri.h"

namespace meshnbv {

// Copy of `mesh` with face attributes "quality" (= PRI, NaN where
// undefined) and "pri_views", and face colours from pri_colors() over the
// 5th..95th percentile of the observed PRI.
TriangleMesh mesh_with_pri(const TriangleMesh& mesh, const PriResult& result);

// The PRI summary as JSON text: counts, percentiles, histogram, the worst
// faces, the options used and the time taken.
std::string pri_summary_json(const PriResult& result, const PriOptions& options,
                             std::size_t worst_k = 10);

struct SuggestionContext {
  std::string scene;     // the input scene's path
  std::string pri_from;  // "computed (ssd)" or the PLY it was read from
};

// The suggestions as JSON text (format "meshnbv-suggestions").
std::string suggestions_json(const SuggestResult& result, const SuggestOptions& options,
                             const SuggestionContext& context);

// One pyramid per suggestion (apex at the camera centre, base = the image
// corners at `depth`; depth 0 = 20% of the distance to the look-at point),
// faces coloured by rank from red (1) to yellow (last).
TriangleMesh frustum_mesh(const SuggestResult& result, double depth = 0.0);

}  // namespace meshnbv
