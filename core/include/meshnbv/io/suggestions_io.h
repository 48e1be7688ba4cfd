// Writing next-view suggestions: JSON (schema in docs/formats.md), the
// scene as .mlp with one raster per suggestion, a frustum mesh, and a
// COLMAP text model of the suggestions.
#pragma once

#include <string>

#include "meshnbv/planner.h"

namespace meshnbv::io {

struct SuggestionContext {
  std::string scene;     // the input scene's path
  std::string pri_from;  // "computed (ssd)" or the PLY it was read from
};

std::string suggestions_json(const SuggestResult& result, const SuggestOptions& options,
                             const SuggestionContext& context);

// The scene's views plus one raster without image per suggestion (labels
// nbv_1, ...), written as .mlp (the mesh is referenced where it already is
// on disk, else written beside the project).
void write_suggestions_mlp(const Scene& scene, const SuggestResult& result, const std::string& path,
                           bool overwrite);

// One pyramid per suggestion (apex at the camera centre, base = the image
// corners at `depth`; depth 0 = 20% of the distance to the look-at point),
// faces coloured by rank from red (1) to yellow (last).
TriangleMesh frustum_mesh(const SuggestResult& result, double depth = 0.0);

// cameras.txt, images.txt and points3D.txt of the suggestions.
void write_suggestions_colmap(const SuggestResult& result, const std::string& folder, bool overwrite);

}  // namespace meshnbv::io
