// Results as meshes and JSON: the mesh with its PRI, the suggestions'
// frustums, and the JSON summaries every front end writes (schemas in
// docs/formats.md).
#include "meshnbv/results.h"

#include "percentiles.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "meshnbv/error.h"
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
  if (e.whole_mesh)
    return {{"total", e.total}, {"refinement", e.refinement}, {"exploration", e.exploration}};
  return {{"total", e.total}, {"occlusion", e.occlusion}, {"focus", e.focus},
          {"parallax", e.parallax}, {"incidence", e.incidence}};
}


// Every per-face vector of a result holds one value per face.
void check_sizes(const PriResult& r) {
  const std::size_t n = r.pri.size();
  if (r.pri_views.size() != n || r.pri_pairs.size() != n || r.pri_samples.size() != n ||
      r.pri_texture.size() != n)
    throw Error("PRI result: " + std::to_string(n) + " faces but " +
                std::to_string(r.pri_views.size()) + " views, " + std::to_string(r.pri_pairs.size()) +
                " pairs, " + std::to_string(r.pri_samples.size()) + " samples and " +
                std::to_string(r.pri_texture.size()) + " texture values");
}

// (percent, value) at 0, 5, 25, 50, 75, 95, 100, linear between closest
// ranks (as summarize_pri); empty for no values.
std::vector<std::pair<double, double>> percentiles(std::vector<double> v) {
  return detail::interpolated_percentiles(v, {0.0, 5.0, 25.0, 50.0, 75.0, 95.0, 100.0});
}

json percentiles_json(const std::vector<std::pair<double, double>>& pct) {
  json j = json::object();
  for (const auto& [p, v] : pct) j["p" + std::to_string(int(p))] = v;
  return j;
}

json evidence_json(const PriEvidence& e) {
  return {{"observed", e.observed},
          {"two_views", e.two_views},
          {"low_texture", e.low_texture},
          {"low_texture_below", e.low_texture_below},
          {"texture_percentiles", percentiles_json(e.texture_percentiles)},
          {"pairs_percentiles", percentiles_json(e.pairs_percentiles)},
          {"samples_percentiles", percentiles_json(e.samples_percentiles)}};
}

}  // namespace

std::string measure_unit(Measure measure) {
  switch (measure) {
    case Measure::SSD: return "squared intensity";
    case Measure::NCC: return "1 - rho over 2";
    case Measure::Offset: return "scene units";
  }
  throw Error("unknown PRI measure " + std::to_string(int(measure)));
}

PriEvidence pri_evidence(const PriResult& result, double low_texture_below) {
  check_sizes(result);
  PriEvidence e;
  e.low_texture_below = low_texture_below;
  std::vector<double> texture, pairs, samples;
  for (std::size_t f = 0; f < result.pri.size(); ++f) {
    if (std::isnan(result.pri[f])) continue;
    ++e.observed;
    if (result.pri_views[f] == 2) ++e.two_views;
    // NaN texture (no samples read) counts as low: there is no texture to rely on.
    if (!(result.pri_texture[f] >= low_texture_below)) ++e.low_texture;
    if (!std::isnan(result.pri_texture[f])) texture.push_back(result.pri_texture[f]);
    pairs.push_back(result.pri_pairs[f]);
    samples.push_back(result.pri_samples[f]);
  }
  e.texture_percentiles = percentiles(std::move(texture));
  e.pairs_percentiles = percentiles(std::move(pairs));
  e.samples_percentiles = percentiles(std::move(samples));
  return e;
}

TriangleMesh mesh_with_pri(const TriangleMesh& mesh, const PriResult& result) {
  check_sizes(result);
  TriangleMesh out = mesh;
  out.set_face_attribute("quality", result.pri);
  out.set_face_attribute("pri_views", std::vector<float>(result.pri_views.begin(), result.pri_views.end()));
  out.set_face_attribute("pri_pairs", std::vector<float>(result.pri_pairs.begin(), result.pri_pairs.end()));
  out.set_face_attribute("pri_samples", std::vector<float>(result.pri_samples.begin(), result.pri_samples.end()));
  out.set_face_attribute("pri_texture", result.pri_texture);
  if (result.evidence_key.size() == result.pri.size()) {
    // The 64-bit evidence key in three floats of 22, 21 and 21 bits (exact
    // integers: a float holds them up to 2^24).
    const int shift[3] = {0, 22, 43}, bits[3] = {22, 21, 21};
    for (int k = 0; k < 3; ++k) {
      std::vector<float> part(result.pri.size());
      for (std::size_t f = 0; f < part.size(); ++f)
        part[f] = float((result.evidence_key[f] >> shift[k]) & ((std::uint64_t(1) << bits[k]) - 1));
      out.set_face_attribute(kPriKeyAttributes[k], std::move(part));
    }
  }
  if (result.offset_signed.size() == result.pri.size()) {
    out.set_face_attribute("pri_offset_signed", result.offset_signed);
    out.set_face_attribute("pri_offset_precision", result.offset_precision);
    out.set_face_attribute("pri_offset_pixel", result.offset_pixel);
    out.set_face_attribute("pri_offset_steady", result.offset_steady);
  }
  const PriSummary s = summarize_pri(result, 0);
  double lo = 0, hi = 1;
  for (const auto& [p, v] : s.percentiles) {
    if (p == 5.0) lo = v;
    if (p == 95.0) hi = v;
  }
  out.face_colors = pri_colors(result.pri, lo, hi);
  return out;
}

namespace {

std::string hex_key(std::uint64_t key) {
  char hex[20];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(key));
  return hex;
}

// The 16-digit hex keys after `tag` in line c.
std::vector<std::uint64_t> keys_after(const std::string& c, const std::string& tag) {
  std::vector<std::uint64_t> keys;
  std::size_t at = tag.size();
  while (at < c.size()) {
    while (at < c.size() && c[at] == ' ') ++at;
    if (at >= c.size()) break;
    std::size_t end = at;
    std::uint64_t v = 0;
    while (end < c.size() && std::isxdigit(static_cast<unsigned char>(c[end]))) {
      const char ch = c[end];
      v = v * 16 + std::uint64_t(std::isdigit(static_cast<unsigned char>(ch)) ? ch - '0' : (std::tolower(ch) - 'a' + 10));
      ++end;
    }
    if (end - at != 16 || (end < c.size() && c[end] != ' '))
      throw Error("malformed key in the PLY comment '" + c.substr(0, 80) + "'");
    keys.push_back(v);
    at = end;
  }
  return keys;
}

}  // namespace

std::vector<std::string> pri_key_comments(const PriResult& result) {
  std::vector<std::string> lines = {"meshnbv_pri_options_key " + hex_key(result.options_key)};
  for (std::size_t i = 0; i < result.view_keys.size(); i += 64) {
    std::string line = "meshnbv_pri_view_keys";
    for (std::size_t k = i; k < std::min(result.view_keys.size(), i + 64); ++k) line += " " + hex_key(result.view_keys[k]);
    lines.push_back(line);
  }
  return lines;
}

void read_pri_key_comments(const std::vector<std::string>& comments, PriResult* result) {
  const std::string views = "meshnbv_pri_view_keys", options = "meshnbv_pri_options_key";
  std::vector<std::uint64_t> keys;
  for (const std::string& c : comments) {
    if (c.compare(0, views.size() + 1, views + " ") == 0) {
      for (std::uint64_t k : keys_after(c, views)) keys.push_back(k);
    } else if (c.compare(0, options.size() + 1, options + " ") == 0) {
      const std::vector<std::uint64_t> k = keys_after(c, options);
      if (k.size() != 1) throw Error("malformed options key in the PLY comment '" + c.substr(0, 80) + "'");
      result->options_key = k[0];
    }
  }
  if (!keys.empty()) result->view_keys = keys;
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
  j["measure"] = measure_name(options.measure);
  j["unit"] = measure_unit(options.measure);
  json pct = json::object();
  for (const auto& [p, v] : s.percentiles) pct["p" + std::to_string(int(p))] = v;
  j["pri_percentiles"] = pct;
  j["histogram"] = {{"min", s.histogram_min}, {"max", s.histogram_max}, {"counts", s.histogram}};
  j["evidence"] = evidence_json(pri_evidence(result));
  json worst = json::array();
  for (const auto& w : s.worst) {
    const auto f = std::size_t(w.face);
    worst.push_back({{"face", w.face}, {"pri", w.pri}, {"views", w.views},
                     {"pairs", result.pri_pairs[f]}, {"texture", result.pri_texture[f]}});
  }
  j["worst_faces"] = worst;
  // Every option of the table, under its one name (options.h).
  j["options"] = json::parse(options_json(options, pri_option_table()));
  j["views_used"] = result.views_used;
  j["recomputed_faces"] = result.recomputed;
  j["reselected_faces"] = result.reselected;
  j["images_decoded"] = result.images_decoded;
  j["views_reduced"] = result.views_reduced;
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
  for (const auto& s : r.suggestions) {
    suggestions.push_back({{"rank", s.rank},
                           {"label", s.label},
                           {"source", s.source},
                           {"region", s.region},
                           {"camera", camera_json(s.camera)},
                           {"centre", vec(s.camera.center())},
                           {"look_at", vec(s.look_at)},
                           {"energy", energy_json(s.energy)},
                           {"seen_faces", s.seen_faces}});
    if (s.energy.whole_mesh) suggestions.back()["improved_faces"] = s.improved_faces;
  }
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
                     {"rejected_too_close", r.rejected_too_close},
                     {"rejected_below_ground", r.rejected_below_ground}};
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
