#include "viewer_data.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "base64.h"
#include "meshnbv/display_mesh.h"
#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/results.h"
#include "viewer_bundle.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace meshnbv::report_detail {
namespace {

static_assert(sizeof(float) == 4, "float32 arrays");

// A typed array for the viewer: its element type (a JavaScript typed array
// name) and its bytes in base64, little-endian as on every platform we build
// on (x86-64, arm64).
template <class T>
json typed_array(const char* type, const std::vector<T>& values) {
  return {{"type", type}, {"count", values.size()}, {"base64", base64(values.data(), values.size() * sizeof(T))}};
}

json vec3(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

json camera(const PinholeCamera& c, double frustum_depth) {
  json R = json::array();
  for (int r = 0; r < 3; ++r) R.push_back({c.R(r, 0), c.R(r, 1), c.R(r, 2)});
  return {{"centre", vec3(c.center())}, {"R", R},   {"fx", c.fx},         {"fy", c.fy},
          {"cx", c.cx},                 {"cy", c.cy}, {"width", c.width}, {"height", c.height},
          {"depth", frustum_depth}};
}

template <class T>
std::vector<T> clamped(const std::vector<int>& v) {
  std::vector<T> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    out[i] = T(std::clamp<long long>(v[i], 0, (long long)std::numeric_limits<T>::max()));
  return out;
}

// The world's up direction for orbiting: the mean "up" of the existing
// cameras (photos are mostly taken upright), +Z when they do not agree.
Vec3 world_up(const Scene& scene) {
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (const View& v : scene.views)
    if (v.has_image() && v.used) sum -= v.camera.down(), ++n;
  if (n > 0 && sum.norm() > 0.5 * n) return sum.normalized();
  return Vec3::UnitZ();
}

}  // namespace

ViewerFiles write_viewer(const ReportInputs& in, const std::string& report_folder,
                         std::pair<double, double> range) {
  const Scene& scene = *in.scene;
  const SuggestResult& sug = *in.suggestions;
  const PriResult& pri = *in.pri;
  const TriangleMesh& mesh = scene.mesh;
  ViewerFiles out;
  const fs::path folder = fs::path(report_folder) / out.folder;
  fs::create_directories(folder);

  const DisplayMesh display = display_mesh(mesh, in.display_faces);
  const DisplayPri shown = display_pri(display, mesh, pri, kLowTexture);
  out.original_faces = mesh.num_faces();
  out.display_faces = display.mesh.num_faces();
  out.decimated = display.decimated;

  // Coordinates relative to the bounding box's centre: float32 keeps a
  // mesh far from the origin (georeferenced) precise.
  const BoundingBox box = mesh.bounding_box();
  const Vec3 origin = box.center();
  std::vector<float> positions;
  positions.reserve(display.mesh.vertices.size() * 3);
  for (const Vec3& p : display.mesh.vertices)
    for (int k = 0; k < 3; ++k) positions.push_back(float(p[k] - origin[k]));
  std::vector<std::uint32_t> indices;
  indices.reserve(display.mesh.faces.size() * 3);
  for (const Face& f : display.mesh.faces)
    for (int k = 0; k < 3; ++k) indices.push_back(std::uint32_t(f[std::size_t(k)]));
  // Colours exactly as the pictures': pri_colors over the same range.
  std::vector<std::uint8_t> colours;
  colours.reserve(display.mesh.faces.size() * 3);
  for (const Rgb8& c : pri_colors(shown.pri, range.first, range.second))
    colours.insert(colours.end(), c.begin(), c.end());

  json arrays = {{"positions", typed_array("Float32Array", positions)},
                 {"indices", typed_array("Uint32Array", indices)},
                 {"colours", typed_array("Uint8Array", colours)},
                 {"display_pri", typed_array("Float32Array", shown.pri)},
                 {"display_flags", typed_array("Uint8Array", shown.flags)},
                 {"face_pri", typed_array("Float32Array", pri.pri)},
                 {"face_views", typed_array("Uint16Array", clamped<std::uint16_t>(pri.pri_views))},
                 {"face_pairs", typed_array("Uint32Array", clamped<std::uint32_t>(pri.pri_pairs))},
                 {"face_samples", typed_array("Uint32Array", clamped<std::uint32_t>(pri.pri_samples))},
                 {"face_texture", typed_array("Float32Array", pri.pri_texture)}};
  json decimation = nullptr;
  if (display.decimated) {
    // Picking: the original faces a display face stands for, and their
    // centroids quantised to 16 bits over their bounding box (the viewer
    // reports the one nearest the picked point).
    BoundingBox cbox;
    std::vector<Vec3> centroids(mesh.num_faces());
    for (std::size_t f = 0; f < centroids.size(); ++f) cbox.extend(centroids[f] = mesh.face_centroid(f));
    const Vec3 extent = cbox.extent().cwiseMax(Vec3::Constant(1e-300));
    std::vector<std::uint16_t> quantised;
    quantised.reserve(centroids.size() * 3);
    for (const Vec3& c : centroids)
      for (int k = 0; k < 3; ++k)
        quantised.push_back(std::uint16_t(std::lround(std::clamp((c[k] - cbox.min[k]) / extent[k], 0.0, 1.0) * 65535)));
    arrays["member_begin"] = typed_array("Uint32Array", display.member_begin);
    arrays["members"] = typed_array("Uint32Array", display.members);
    arrays["centroids"] = typed_array("Uint16Array", quantised);
    decimation = {{"method", "OpenMesh quadric edge collapses; a removed face is taken over by its neighbour "
                             "across the stretched edge; a display face shows the area-weighted mean PRI of "
                             "its observed original faces"},
                  {"centroid_min", vec3(cbox.min - origin)},
                  {"centroid_extent", vec3(extent)}};
  }

  // The interaction level of detail: a coarser copy drawn while the camera
  // moves, sharing the display mesh's positions (its vertices are display
  // vertices), its faces coloured from the area-weighted PRI of the original
  // faces each stands for. None when the display mesh is small enough.
  json interaction = nullptr;
  if (in.interaction_faces == 0) throw Error("report: the interaction face budget must be at least 1");
  if (display.mesh.num_faces() > in.interaction_faces) {
    const CoarseDisplayMesh coarse = coarse_display_mesh(display, in.interaction_faces);
    const TriangleMesh& cm = coarse.mesh.mesh;
    const DisplayPri coarse_shown = display_pri(coarse.mesh, mesh, pri, kLowTexture);
    std::vector<std::uint8_t> coarse_colours;
    coarse_colours.reserve(cm.faces.size() * 3);
    for (const Rgb8& c : pri_colors(coarse_shown.pri, range.first, range.second))
      coarse_colours.insert(coarse_colours.end(), c.begin(), c.end());
    std::vector<std::uint32_t> vertices(coarse.mesh.source_vertex.begin(), coarse.mesh.source_vertex.end());
    // Indices and the display-to-coarse map in 16 bits when they fit.
    auto narrow = [](const std::vector<std::uint32_t>& v, std::size_t bound) {
      if (bound <= 65536) {
        std::vector<std::uint16_t> n16(v.begin(), v.end());
        return typed_array("Uint16Array", n16);
      }
      return typed_array("Uint32Array", v);
    };
    std::vector<std::uint32_t> coarse_indices;
    coarse_indices.reserve(cm.faces.size() * 3);
    for (const Face& f : cm.faces)
      for (int k = 0; k < 3; ++k) coarse_indices.push_back(std::uint32_t(f[std::size_t(k)]));
    const std::vector<std::uint32_t> of_display(coarse.coarse_face.begin(), coarse.coarse_face.end());
    arrays["interaction_vertices"] = typed_array("Uint32Array", vertices);
    arrays["interaction_indices"] = narrow(coarse_indices, cm.vertices.size());
    arrays["interaction_colours"] = typed_array("Uint8Array", coarse_colours);
    arrays["interaction_flags"] = typed_array("Uint8Array", coarse_shown.flags);
    arrays["interaction_face_of_display"] = narrow(of_display, cm.faces.size());
    out.interaction_faces = cm.num_faces();
    interaction = {{"faces", out.interaction_faces},
                   {"budget", in.interaction_faces},
                   {"method", "the display mesh decimated again (OpenMesh quadric edge collapses), drawn while the "
                              "camera moves; a face shows the area-weighted mean PRI of the original faces it "
                              "stands for"}};
  }

  json cameras = json::array();
  const double diag = box.diagonal();
  for (const View& v : scene.views) {
    if (!v.has_image() || !v.used) continue;
    json c = camera(v.camera, 0.06 * diag * v.camera.fx / v.camera.width);  // as the overviews draw them
    c["label"] = v.label;
    cameras.push_back(c);
  }
  json suggestions = json::array();
  for (const Suggestion& s : sug.suggestions) {
    json c = camera(s.camera, 0.2 * std::max(1e-9, s.camera.depth(s.look_at)));
    c["label"] = s.label;
    c["rank"] = s.rank;
    c["source"] = s.source;
    c["region"] = s.region;
    c["look_at"] = vec3(s.look_at);
    c["energy"] = s.energy.whole_mesh
                      ? json{{"total", s.energy.total}, {"refinement", s.energy.refinement},
                             {"exploration", s.energy.exploration}}
                      : json{{"total", s.energy.total}, {"occlusion", s.energy.occlusion},
                             {"focus", s.energy.focus}, {"parallax", s.energy.parallax},
                             {"incidence", s.energy.incidence}};
    c["seen_faces"] = s.seen_faces;
    suggestions.push_back(c);
  }
  json regions = json::array();
  for (const WorstRegion& r : sug.regions) {
    double radius = 0;
    for (int f : r.faces)
      for (int v : mesh.faces[std::size_t(f)]) radius = std::max(radius, (mesh.vertices[std::size_t(v)] - r.centroid).norm());
    float worst = std::numeric_limits<float>::quiet_NaN();
    if (!r.faces.empty()) worst = pri.pri[std::size_t(r.faces.front())];
    regions.push_back({{"faces", r.faces}, {"centroid", vec3(r.centroid)}, {"normal", vec3(r.mean_normal)},
                       {"radius", radius}, {"worst_pri", worst}});
  }

  json data = {{"format", "meshnbv-report-view"},
               {"version", 1},
               {"measure", measure_name(in.pri_options.measure)},
               {"unit", measure_unit(in.pri_options.measure)},
               {"range", {range.first, range.second}},
               {"low_texture_below", kLowTexture},
               {"origin", vec3(origin)},
               {"up", vec3(world_up(scene))},
               {"box", {{"min", vec3(box.min - origin)}, {"max", vec3(box.max - origin)}}},
               {"faces", out.original_faces},
               {"display_faces", out.display_faces},
               {"display_budget", in.display_faces},
               {"decimated", out.decimated},
               {"decimation", decimation},
               {"interaction", interaction},
               {"cameras", cameras},
               {"suggestions", suggestions},
               {"regions", regions},
               {"arrays", arrays}};
  // NaN and infinities become null (JSON has neither); the viewer reads null as NaN.
  const std::string text = data.dump(-1, ' ', false, json::error_handler_t::replace);
  io::write_atomically((folder / "report_data.js").string(), [&](std::ostream& o) {
    o << "// MeshNBV report data (meshnbv run): read by meshnbv_viewer.js\nwindow.MESHNBV_REPORT = " << text
      << ";\n";
  });
  io::write_atomically(
      (folder / "meshnbv_viewer.js").string(),
      [&](std::ostream& o) { o.write(reinterpret_cast<const char*>(kViewerBundle), std::streamsize(kViewerBundleSize)); },
      true, true);
  return out;
}

}  // namespace meshnbv::report_detail
