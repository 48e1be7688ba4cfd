// Results as meshes and JSON: the mesh with its PRI, the suggestions'
// frustums, and the JSON summaries every front end writes (schemas in
// docs/formats.md).
#include "meshnbv/results.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "meshnbv/options.h"

using nlohmann::json;

namespace meshnbv {
namespace {

json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

json camera_json(const PinholeCamera& c) {
  return {{"width", c.width}, {"height", c.height}, {"fx", c.fx}, {"fy", c.fy},
          {"cx", c.cx},       {"cy", c.cy},
          {"R", {{c.R(0, 0), c.R(0, 1), c.R(0, 2)}, {c.R(1, 0), c.R(1, 1), c.R(1, 2)}, {c.R(2, 0), c.R(2, 1), c.R(2, 2)}}},
          {"t", vec(c.t)}};
}

json energy_json(const EnergyTerms& e) {
  return {{"total", e.total}, {"occlusion", e.occlusion}, {"focus", e.focus},
          {"parallax", e.parallax}, {"incidence", e.incidence}};
}


}  // namespace

TriangleMesh mesh_with_pri(const TriangleMesh& mesh, const PriResult& result) {
  TriangleMesh out = mesh;
  out.set_face_attribute("quality", result.pri);
  out.set_face_attribute("pri_views", std::vector<float>(result.pri_views.begin(), result.pri_views.end()));
  const PriSummary s = summarize_pri(result, 0);
  double lo = 0, hi = 1;
  for (const auto& [p, v] : s.percentiles) {
    if (p == 5.0) lo = v;
    if (p == 95.0) hi = v;
  }
  out.face_colors = pri_colors(result.pri, lo, hi);
  return out;
}

std::string pri_summary_json(const PriResult& result, const PriOptions& options,
                             std::size_t worst_k) {
  using nlohmann::json;
  const PriSummary s = summarize_pri(result, worst_k);
  json j;
  j["faces"] = {{"total", s.faces},
                {"observed", s.observed},
                {"unobserved", s.unobserved},
                {"textureless", s.textureless}};
  json pct = json::object();
  for (const auto& [p, v] : s.percentiles) pct["p" + std::to_string(int(p))] = v;
  j["pri_percentiles"] = pct;
  j["histogram"] = {{"min", s.histogram_min}, {"max", s.histogram_max}, {"counts", s.histogram}};
  json worst = json::array();
  for (const auto& w : s.worst) worst.push_back({{"face", w.face}, {"pri", w.pri}, {"views", w.views}});
  j["worst_faces"] = worst;
  // Every option of the table, under its one name (options.h).
  j["options"] = json::parse(options_json(options, pri_option_table()));
  j["views_used"] = result.views_used;
  j["seconds"] = result.seconds;
  return j.dump(2) + "\n";
}

std::string suggestions_json(const SuggestResult& r, const SuggestOptions& o,
                             const SuggestionContext& ctx) {
  json j;
  j["format"] = "meshnbv-suggestions";
  j["version"] = 1;
  j["scene"] = ctx.scene;
  j["pri"] = ctx.pri_from;
  // Every option of the table, under its one name (options.h), and the
  // sampling distances, which no front end sets.
  j["options"] = json::parse(options_json(o, suggest_option_table()));
  j["options"]["distance_factors"] = o.sampling.distance_factors;
  json regions = json::array();
  for (std::size_t i = 0; i < r.regions.size(); ++i)
    regions.push_back({{"index", i}, {"faces", r.regions[i].faces},
                       {"centroid", vec(r.regions[i].centroid)},
                       {"mean_normal", vec(r.regions[i].mean_normal)}});
  j["regions"] = regions;
  json suggestions = json::array();
  for (const auto& s : r.suggestions)
    suggestions.push_back({{"rank", s.rank},
                           {"label", s.label},
                           {"source", s.source},
                           {"region", s.region},
                           {"camera", camera_json(s.camera)},
                           {"centre", vec(s.camera.center())},
                           {"look_at", vec(s.look_at)},
                           {"energy", energy_json(s.energy)},
                           {"seen_faces", s.seen_faces}});
  j["suggestions"] = suggestions;
  json ranking = json::array();
  for (std::size_t i = 0; i < r.ranking.size(); ++i)
    ranking.push_back({{"rank", i + 1},
                       {"label", r.ranking[i].label},
                       {"centre", vec(r.ranking[i].camera.center())},
                       {"energy", energy_json(r.ranking[i].energy)}});
  j["ranking"] = ranking;
  j["candidates"] = {{"generated", r.candidates_generated},
                     {"evaluated", r.candidates_evaluated},
                     {"rejected_inside", r.rejected_inside},
                     {"rejected_too_close", r.rejected_too_close}};
  j["seconds"] = r.seconds;
  return j.dump(2) + "\n";
}

TriangleMesh frustum_mesh(const SuggestResult& result, double depth) {
  TriangleMesh m;
  const std::size_t n = result.suggestions.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Suggestion& s = result.suggestions[i];
    const Vec3 c = s.camera.center();
    const double d = depth > 0 ? depth : 0.2 * std::max(1e-9, s.camera.depth(s.look_at));
    const auto corners = s.camera.frustum_corners(d);
    const int base = int(m.vertices.size());
    m.vertices.push_back(c);
    for (const Vec3& p : corners) m.vertices.push_back(p);
    // Four sides (outward) and the base (facing away from the camera).
    for (int k = 0; k < 4; ++k) m.faces.push_back({base, base + 1 + (k + 1) % 4, base + 1 + k});
    m.faces.push_back({base + 1, base + 2, base + 3});
    m.faces.push_back({base + 1, base + 3, base + 4});
    const double t = n > 1 ? double(i) / double(n - 1) : 0.0;
    const Rgb8 colour = {255, std::uint8_t(std::lround(220 * t)), 0};
    for (int k = 0; k < 6; ++k) m.face_colors.push_back(colour);
    m.face_attributes["rank"].insert(m.face_attributes["rank"].end(), 6, float(s.rank));
    m.face_attributes["energy"].insert(m.face_attributes["energy"].end(), 6, float(s.energy.total));
  }
  return m;
}

}  // namespace meshnbv
