// Writing next-view suggestions as files of other tools: the scene as .mlp
// with one raster per suggestion, and a COLMAP text model of the
// suggestions. (The JSON and the frustum mesh are in meshnbv/results.h.)
#pragma once

#include <string>

#include "meshnbv/planner.h"
#include "meshnbv/results.h"

namespace meshnbv::io {

// The scene's views plus one raster without image per suggestion (labels
// nbv_1, ...), written as .mlp (the mesh is referenced where it already is
// on disk, else written beside the project).
void write_suggestions_mlp(const Scene& scene, const SuggestResult& result, const std::string& path,
                           bool overwrite);

// cameras.txt, images.txt and points3D.txt of the suggestions.
void write_suggestions_colmap(const SuggestResult& result, const std::string& folder, bool overwrite);

}  // namespace meshnbv::io
