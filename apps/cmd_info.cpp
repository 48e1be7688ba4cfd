// meshnbv info: what a scene holds, and what is wrong with it.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.h"
#include "meshnbv/error.h"
#include "meshnbv/io/exif.h"
#include "meshnbv/io/file_util.h"

namespace meshnbv::cli {
namespace {

struct Range {
  double lo = INFINITY, hi = -INFINITY;
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  nlohmann::json to_json() const { return lo <= hi ? nlohmann::json{lo, hi} : nlohmann::json(nullptr); }
};

// Lens models with their view counts, the image files not found, and the
// reprojection error of the sparse points: the user's first check of an import.
void add_import_checks(const Scene& scene, nlohmann::json* out) {
  using nlohmann::json;
  std::map<std::string, int> lenses;
  json missing = json::array();
  std::size_t num_missing = 0;
  for (const auto& view : scene.views) {
    ++lenses[view.camera.lens_description()];
    std::error_code ec;
    if (!view.image_path.empty() && !std::filesystem::exists(view.image_path, ec) && num_missing++ < 5)
      missing.push_back(view.image_path);
  }
  (*out)["views"]["lenses"] = lenses;
  (*out)["views"]["missing_images"] = num_missing;
  (*out)["views"]["missing_images_first"] = missing;
  if (scene.sparse_points.empty()) {
    (*out)["sparse_points"] = nullptr;
    return;
  }
  const ReprojectionStats r = reprojection_error(scene);
  (*out)["sparse_points"] = {
      {"points", scene.sparse_points.size()},
      {"observations", r.observations},
      {"behind_camera", r.behind},
      {"reprojection_error_px", {{"median", r.median}, {"mean", r.mean}, {"max", r.max}}}};
}

// The photos' headers (no pixels decoded): stored sizes, bit depths, EXIF
// orientation tags, the photos Scene::image will read turned by their tag
// (stored on their side of the camera's size) and those that fit their
// camera neither way.
nlohmann::json photo_summary(const Scene& scene) {
  using nlohmann::json;
  std::map<std::string, int> sizes, bits, orientations;
  std::size_t read = 0, turned = 0, mismatched = 0, unreadable = 0;
  json mismatch_first = json::array(), unreadable_first = json::array();
  for (const auto& view : scene.views) {
    std::error_code ec;
    if (view.image_path.empty() || !std::filesystem::exists(view.image_path, ec)) continue;
    std::optional<io::PhotoHeader> h;
    try {
      h = io::read_photo_header(view.image_path);
    } catch (const Error& e) {
      if (unreadable++ < 5) unreadable_first.push_back(e.what());
      continue;
    }
    if (!h || h->width <= 0) continue;  // a type without a header exiv2 reads (PGM, BMP)
    ++read;
    ++sizes[std::to_string(h->width) + "x" + std::to_string(h->height)];
    ++bits[h->bits > 0 ? std::to_string(h->bits) : std::string("unknown")];
    if (h->orientation > 0) ++orientations[std::to_string(h->orientation)];
    const bool swaps = h->orientation >= 5;  // tags 5..8 turn by 90 degrees
    const bool exif = view.orientation == ImageOrientation::exif;
    const int w = exif && swaps ? h->height : h->width, ht = exif && swaps ? h->width : h->height;
    const PinholeCamera& c = view.camera;
    if (w == c.width && ht == c.height) continue;
    if (!exif && swaps && h->height == c.width && h->width == c.height) {
      ++turned;
      continue;
    }
    if (mismatched++ < 5)
      mismatch_first.push_back(view.label + ": " + std::to_string(w) + "x" + std::to_string(ht) +
                               ", camera " + std::to_string(c.width) + "x" + std::to_string(c.height));
  }
  return {{"headers_read", read},
          {"sizes", sizes},
          {"bits", bits},
          {"exif_orientation", orientations},
          {"read_turned", turned},
          {"size_mismatch", mismatched},
          {"size_mismatch_first", mismatch_first},
          {"unreadable", unreadable},
          {"unreadable_first", unreadable_first}};
}

nlohmann::json summarize(const Scene& scene) {
  using nlohmann::json;
  const TriangleMesh& mesh = scene.mesh;
  const MeshCheck check = check_mesh(mesh);
  const BoundingBox box = mesh.bounding_box();
  json out;
  out["scene"] = scene.source;
  out["format"] = scene.format;
  out["producer"] = scene.producer;
  json m;
  m["file"] = scene.mesh_path.empty() ? json(nullptr) : json(scene.mesh_path);
  m["vertices"] = mesh.num_vertices();
  m["faces"] = mesh.num_faces();
  m["area"] = mesh.total_area();
  m["bounding_box"] = box.empty() ? json(nullptr)
                                  : json{{"min", {box.min.x(), box.min.y(), box.min.z()}},
                                         {"max", {box.max.x(), box.max.y(), box.max.z()}},
                                         {"diagonal", box.diagonal()}};
  m["degenerate_faces"] = check.degenerate_faces;
  m["boundary_edges"] = check.boundary_edges;
  m["nonmanifold_edges"] = check.nonmanifold_edges;
  m["unreferenced_vertices"] = check.unreferenced_vertices;
  m["closed"] = mesh.empty() ? false : check.closed();
  m["face_attributes"] = json::array();
  for (const auto& [name, values] : mesh.face_attributes) m["face_attributes"].push_back(name);
  out["mesh"] = m;

  json v;
  Range fx, fy, cx, cy, dist;
  std::size_t with_image = 0, image_present = 0, unused = 0;
  std::map<std::string, int> resolutions;
  const Vec3 centre = box.empty() ? Vec3::Zero() : box.center();
  for (const auto& view : scene.views) {
    const PinholeCamera& c = view.camera;
    fx.add(c.fx);
    fy.add(c.fy);
    cx.add(c.cx);
    cy.add(c.cy);
    dist.add((c.center() - centre).norm());
    ++resolutions[std::to_string(c.width) + "x" + std::to_string(c.height)];
    if (view.has_image()) {
      ++with_image;
      std::error_code ec;
      if (std::filesystem::exists(view.image_path, ec)) ++image_present;
    }
    if (!view.used) ++unused;
  }
  v["count"] = scene.views.size();
  v["with_image"] = with_image;
  v["image_files_present"] = image_present;
  v["without_image"] = scene.views.size() - with_image;
  v["marked_unused"] = unused;
  v["resolutions"] = resolutions;
  v["fx"] = fx.to_json();
  v["fy"] = fy.to_json();
  v["cx"] = cx.to_json();
  v["cy"] = cy.to_json();
  v["center_distance_to_mesh_box_center"] = dist.to_json();
  out["views"] = v;
  out["photos"] = photo_summary(scene);
  add_import_checks(scene, &out);
  out["warnings"] = scene.warnings;
  return out;
}

void print_text(const nlohmann::json& s) {
  auto num = [](const nlohmann::json& j) {
    std::ostringstream ss;
    ss << std::setprecision(6) << j.get<double>();
    return ss.str();
  };
  auto range = [&](const nlohmann::json& j) {
    return j.is_null() ? std::string("-") : num(j[0]) + " .. " + num(j[1]);
  };
  const auto& m = s["mesh"];
  std::cout << "scene      " << s["scene"].get<std::string>() << " (" << s["format"].get<std::string>()
            << ")\n";
  if (!s["producer"].get<std::string>().empty())
    std::cout << "from       " << s["producer"].get<std::string>() << "\n";
  std::cout << "mesh       " << (m["file"].is_null() ? std::string("(none)") : m["file"].get<std::string>())
            << "\n";
  std::cout << "  vertices " << m["vertices"] << ", faces " << m["faces"] << ", area " << num(m["area"])
            << "\n";
  if (!m["bounding_box"].is_null()) {
    const auto& b = m["bounding_box"];
    std::cout << "  bbox     (" << num(b["min"][0]) << ", " << num(b["min"][1]) << ", " << num(b["min"][2])
              << ") .. (" << num(b["max"][0]) << ", " << num(b["max"][1]) << ", " << num(b["max"][2])
              << "), diagonal " << num(b["diagonal"]) << "\n";
  }
  std::cout << "  checks   degenerate faces " << m["degenerate_faces"] << ", boundary edges "
            << m["boundary_edges"] << ", non-manifold edges " << m["nonmanifold_edges"]
            << ", unreferenced vertices " << m["unreferenced_vertices"]
            << (m["closed"].get<bool>() ? ", closed" : "") << "\n";
  const auto& v = s["views"];
  std::cout << "views      " << v["count"] << " (" << v["with_image"] << " with image, "
            << v["image_files_present"] << " image files present, " << v["without_image"]
            << " candidates without image)\n";
  std::cout << "  size     ";
  bool first = true;
  for (const auto& [res, n] : v["resolutions"].items()) {
    std::cout << (first ? "" : ", ") << res << " x" << n;
    first = false;
  }
  std::cout << "\n  fx       " << range(v["fx"]) << "\n  fy       " << range(v["fy"]) << "\n  cx       "
            << range(v["cx"]) << "\n  cy       " << range(v["cy"])
            << "\n  camera distance to mesh box centre " << range(v["center_distance_to_mesh_box_center"])
            << "\n";
  for (const auto& [lens, n] : v["lenses"].items()) std::cout << "  lens     " << lens << " x" << n << "\n";
  if (v["missing_images"].get<std::size_t>() > 0) {
    std::cout << "  missing  " << v["missing_images"] << " image files not found, e.g.";
    for (const auto& f : v["missing_images_first"]) std::cout << " " << f.get<std::string>();
    std::cout << "\n";
  }
  const auto& p = s["photos"];
  if (p["headers_read"].get<std::size_t>() > 0) {
    std::cout << "photos     ";
    first = true;
    for (const auto& [size, n] : p["sizes"].items()) {
      std::cout << (first ? "" : ", ") << size << " x" << n;
      first = false;
    }
    std::cout << "; bits";
    for (const auto& [b, n] : p["bits"].items()) std::cout << " " << b << " x" << n;
    if (!p["exif_orientation"].empty()) {
      std::cout << "; EXIF orientation";
      for (const auto& [o, n] : p["exif_orientation"].items()) std::cout << " " << o << " x" << n;
    }
    std::cout << "\n";
    if (p["read_turned"].get<std::size_t>() > 0)
      std::cout << "  turned   " << p["read_turned"]
                << " photos stored on their side of their camera's size: read turned by their EXIF tag\n";
    if (p["size_mismatch"].get<std::size_t>() > 0) {
      std::cout << "  mismatch " << p["size_mismatch"] << " photos of another size than their camera's, e.g.";
      for (const auto& f : p["size_mismatch_first"]) std::cout << " " << f.get<std::string>() << ";";
      std::cout << "\n";
    }
  }
  if (p["unreadable"].get<std::size_t>() > 0) {
    std::cout << "  unread   " << p["unreadable"] << " photo headers not read, e.g.";
    for (const auto& f : p["unreadable_first"]) std::cout << " " << f.get<std::string>() << ";";
    std::cout << "\n";
  }
  if (!s["sparse_points"].is_null()) {
    const auto& sp = s["sparse_points"];
    const auto& e = sp["reprojection_error_px"];
    std::cout << "sparse     " << sp["points"] << " points, " << sp["observations"]
              << " observations; reprojection error through these cameras: median " << num(e["median"])
              << " px, mean " << num(e["mean"]) << " px, max " << num(e["max"]) << " px";
    if (sp["behind_camera"].get<std::size_t>() > 0)
      std::cout << "; " << sp["behind_camera"] << " observations behind their camera";
    std::cout << "\n";
  }
  for (const auto& w : s["warnings"]) std::cout << "warning: " << w.get<std::string>() << "\n";
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto input = std::make_shared<SceneInput>();
  input->print_warnings = false;  // the summary lists them
  auto json_out = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("info", "Mesh statistics and checks, and a summary of the views");
  input->add_to(cmd);
  cmd->add_option("--json", *json_out, "Also write the summary as JSON to this file ('-' = stdout)");
  cmd->callback([input, json_out]() {
    if (!json_out->empty() && *json_out != "-") io::check_can_write(*json_out, true);
    const Scene scene = input->read();
    const nlohmann::json summary = summarize(scene);
    if (*json_out == "-") {
      std::cout << summary.dump(2) << "\n";
      return;
    }
    print_text(summary);
    if (!json_out->empty()) {
      io::write_atomically(*json_out, [&](std::ostream& out) { out << summary.dump(2) << "\n"; });
      std::cout << "summary written to " << *json_out << "\n";
    }
  });
}

}  // namespace meshnbv::cli
