// Results as meshes and JSON text, shared by every front end: the mesh with
// its PRI, the frustums of the suggestions, and the JSON summaries (schemas
// in docs/formats.md). No file is written here (meshnbv::io does that).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "meshnbv/planner.h"
#include "meshnbv/pri.h"

namespace meshnbv {

// The unit of a measure's PRI values: "squared intensity" (ssd),
// "1 - rho over 2" (ncc), "scene units" (offset).
std::string measure_unit(Measure measure);

// Below this texture strength (pri_texture: standard deviation of a face's
// samples, intensity in [0, 1]; 0.01 = 2.55 grey levels of 255) a face's
// PRI rests on low texture.
constexpr double kLowTexture = 0.01;

// What the observed faces' PRI rests on (PriResult's evidence), as every
// front end reports it.
struct PriEvidence {
  std::size_t observed = 0;     // faces with a PRI value
  std::size_t two_views = 0;    // ... compared on only 2 views
  std::size_t low_texture = 0;  // ... with pri_texture below low_texture_below
  double low_texture_below = kLowTexture;
  // (percent, value) at 0, 5, 25, 50, 75, 95, 100 over the observed faces;
  // empty when none is observed.
  std::vector<std::pair<double, double>> texture_percentiles, pairs_percentiles,
      samples_percentiles;
};
PriEvidence pri_evidence(const PriResult& result, double low_texture_below = kLowTexture);

// Copy of `mesh` with face attributes "quality" (= PRI, NaN where
// undefined), "pri_views", and the evidence "pri_pairs", "pri_samples",
// "pri_texture" (PriResult; counts 0 and texture NaN where undefined), and
// face colours from pri_colors() over the 5th..95th percentile of the
// observed PRI. For incremental PRI (`meshnbv pri --previous`): the
// evidence key in "pri_key_0/1/2" (bits 0-21, 22-42, 43-63 as exact
// integers), and with the offset measure "pri_offset_signed",
// "pri_offset_precision", "pri_offset_pixel", "pri_offset_steady" (PriResult).
TriangleMesh mesh_with_pri(const TriangleMesh& mesh, const PriResult& result);
inline constexpr const char* kPriKeyAttributes[3] = {"pri_key_0", "pri_key_1", "pri_key_2"};
// The PLY comment lines that carry PriResult::options_key and view_keys
// beside mesh_with_pri's mesh ("meshnbv_pri_options_key <hex>", then
// "meshnbv_pri_view_keys" and up to 64 keys in hex per line), and reading
// them back into `result` (left alone when absent; Error when malformed).
std::vector<std::string> pri_key_comments(const PriResult& result);
void read_pri_key_comments(const std::vector<std::string>& comments, PriResult* result);

// The PRI summary as JSON text: counts, the measure and its unit,
// percentiles, histogram, the evidence (pri_evidence), the worst faces
// with theirs, the options used and the time taken.
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
