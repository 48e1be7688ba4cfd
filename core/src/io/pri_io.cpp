#include "meshnbv/io/pri_io.h"

#include <cmath>

#include <nlohmann/json.hpp>

namespace meshnbv::io {

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
  j["options"] = {{"measure", measure_name(options.measure)},
                  {"samples_per_side", options.samples_per_side},
                  {"max_views_per_face", options.max_views_per_face},
                  {"max_incidence_angle", options.max_incidence_angle},
                  {"edge_margin", options.edge_margin},
                  {"check_interior_occlusion", options.check_interior_occlusion},
                  {"color", options.color},
                  {"threads", options.threads},
                  {"textureless_variance", options.textureless_variance}};
  j["views_used"] = result.views_used;
  j["seconds"] = result.seconds;
  return j.dump(2) + "\n";
}

}  // namespace meshnbv::io
