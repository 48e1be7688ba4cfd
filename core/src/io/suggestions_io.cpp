#include "meshnbv/io/suggestions_io.h"

#include <filesystem>

#include <nlohmann/json.hpp>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace meshnbv::io {
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

std::vector<View> suggestion_views(const SuggestResult& result) {
  std::vector<View> views;
  for (const auto& s : result.suggestions) {
    View v;
    v.label = s.label;
    v.camera = s.camera;
    views.push_back(v);
  }
  return views;
}

}  // namespace

std::string suggestions_json(const SuggestResult& r, const SuggestOptions& o,
                             const SuggestionContext& ctx) {
  json j;
  j["format"] = "meshnbv-suggestions";
  j["version"] = 1;
  j["scene"] = ctx.scene;
  j["pri"] = ctx.pri_from;
  const auto& w = o.energy.weights;
  j["options"] = {{"candidates", candidate_mode_name(o.mode)},
                  {"top", o.top},
                  {"worst", o.worst_k},
                  {"weights", {w[0], w[1], w[2], w[3]}},
                  {"penalty", o.energy.penalty},
                  {"parallax_delta", o.energy.parallax_delta},
                  {"incidence_mu", o.energy.incidence_mu},
                  {"incidence_sigma", o.energy.incidence_sigma},
                  {"directions", o.sampling.directions},
                  {"distance_factors", o.sampling.distance_factors},
                  {"safety_distance", o.safety_distance},
                  {"refine_best", o.refine_best},
                  {"refine_iterations", o.refine.iterations},
                  {"seed", o.sampling.seed}};
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

void write_suggestions_mlp(const Scene& scene, const SuggestResult& result, const std::string& path,
                           bool overwrite) {
  check_can_write(path, overwrite);
  // Before the mesh is written: a project cannot reference an in-memory image.
  for (const View& v : scene.views) v.image_file("a MeshLab project (.mlp)");
  Scene out;
  out.views = scene.views;
  for (auto& v : suggestion_views(result)) out.views.push_back(v);
  std::string mesh_file = scene.mesh_path;
  std::error_code ec;
  if (mesh_file.empty() || !fs::exists(mesh_file, ec)) {
    const fs::path p(path);
    mesh_file = (p.parent_path() / (p.stem().string() + "_mesh.ply")).string();
    PlyWriteOptions ply;
    ply.overwrite = overwrite;
    write_ply(scene.mesh, mesh_file, ply);
  }
  write_mlp(out, path, mesh_file, overwrite);
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

void write_suggestions_colmap(const SuggestResult& result, const std::string& folder, bool overwrite) {
  Scene s;
  s.views = suggestion_views(result);
  write_colmap(s, folder, overwrite);
}

}  // namespace meshnbv::io
