#include "meshnbv/synth/project.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"
#include "meshnbv/raycaster.h"

namespace fs = std::filesystem;

namespace meshnbv::synth {

void SynthOptions::check() const {
  if (scene == "object") {
    if (mesh_file.empty()) throw Error("scene 'object' needs a mesh file (--mesh)");
  } else if (scene != "building" && scene != "fortress" && scene != "city") {
    throw Error("unknown scene '" + scene + "' (expected building, fortress, city or object)");
  }
  check_option(cameras.count >= 2 && cameras.count <= 1000, "views", "in [2, 1000]", cameras.count);
  check_option(cameras.width >= 16 && cameras.width <= 8192, "image width", "in [16, 8192] pixels",
               cameras.width);
  check_option(cameras.height >= 16 && cameras.height <= 8192, "image height",
               "in [16, 8192] pixels", cameras.height);
  check_option(cameras.horizontal_fov_degrees > 1 && cameras.horizontal_fov_degrees < 170,
               "horizontal field of view", "in (1, 170) degrees", cameras.horizontal_fov_degrees);
  check_option(cameras.fill > 0 && cameras.fill <= 1, "camera fill", "in (0, 1]", cameras.fill);
  check_option(cameras.elevation_degrees >= -89 && cameras.elevation_degrees <= 89,
               "camera elevation", "in [-89, 89] degrees", cameras.elevation_degrees);
  check_option(render.samples_per_pixel >= 1 && render.samples_per_pixel <= 64, "samples per pixel",
               "in [1, 64]", render.samples_per_pixel);
  check_option(render.ambient >= 0 && render.ambient <= 1, "render ambient", "in [0, 1]",
               render.ambient);
  check_option(render.diffuse >= 0 && render.diffuse <= 1, "render diffuse", "in [0, 1]",
               render.diffuse);
  if (!render.light_direction.allFinite() || !(render.light_direction.norm() > 0))
    throw Error("render light direction must be a finite, non-zero vector");
  if (!render.background.allFinite()) throw Error("render background must be a finite colour");
  // Finer triangles than a quarter of the default would multiply the face
  // count (and memory, render and distance times) by more than 16.
  const double d = default_edge_length(scene);
  if (d > 0) {
    const std::string range = "0 (the scene's default, " + format_option_value(d) + ") or in [" +
                              format_option_value(d / 4) + ", 100] metres for '" + scene + "'";
    check_option(generator.edge_length == 0 ||
                     (generator.edge_length >= d / 4 && generator.edge_length <= 100),
                 "edge length", range, generator.edge_length);
  } else {
    check_option(generator.edge_length >= 0 && generator.edge_length <= 100,
                 "edge length (unused by '" + scene + "')", "0 or in (0, 100] metres",
                 generator.edge_length);
  }
  check_option(degradations.size() <= 64, "the number of degradations", "at most 64",
               double(degradations.size()));
}

namespace {

TriangleMesh load_object(const std::string& path) {
  TriangleMesh m = io::read_mesh(path);
  if (m.empty()) throw Error("the object mesh has no faces", path);
  // Only geometry: the texture comes from our materials.
  m.face_attributes.clear();
  m.face_colors.clear();
  m.face_attributes[kMaterialAttribute] = std::vector<float>(m.num_faces(), 0.0f);
  return m;
}

// The finest texture period, in pixels at the median camera distance. Below
// about 4 px, the view-dependent pixel footprint (foreshortening, distance)
// filters the texture differently in each view and the truth itself stops
// being photo-consistent; measured in tests/core/test_pri_quality.cpp.
constexpr double kBandLimitPixels = 8.0;

// Texture periods in metres suit buildings; an object of any size gets its
// patterns scaled to its own size. The texture is band-limited (see above).
SolidTexture make_texture(const SynthOptions& o, const TriangleMesh& truth,
                          const std::vector<View>& views) {
  std::vector<Material> materials = default_materials();
  if (o.scene == "object") {
    const double diag = truth.bounding_box().diagonal();
    for (auto& m : materials) m.scale *= diag / 20.0;
  }
  std::vector<double> footprint;
  const Vec3 centre = truth.bounding_box().center();
  for (const auto& v : views) footprint.push_back((v.camera.center() - centre).norm() / v.camera.fx);
  std::nth_element(footprint.begin(), footprint.begin() + footprint.size() / 2, footprint.end());
  return SolidTexture(o.seed, materials, kBandLimitPixels * footprint[footprint.size() / 2]);
}

}  // namespace

void render_synthetic_views(const SynthOptions& o, SynthProject* p) {
  const RayCaster caster(p->truth);
  const SolidTexture texture = make_texture(o, p->truth, p->scene.views);
  RenderInputs in{&p->truth, &caster, &texture, p->truth.face_attribute(kMaterialAttribute)};
  for (View& v : p->scene.views) {
    v.image_path.clear();
    v.pixels = std::make_shared<const Image>(render(in, v.camera, o.render));
  }
}

namespace {

std::string describe(const SynthOptions& o) {
  std::ostringstream ss;
  ss << "scene " << o.scene << (o.mesh_file.empty() ? "" : " (" + o.mesh_file + ")") << ", seed "
     << o.seed << ", " << o.cameras.count << " views, layout "
     << camera_layout_name(o.cameras.layout)
     << ", " << o.cameras.width << "x" << o.cameras.height << ", " << o.render.samples_per_pixel
     << " samples per pixel";
  return ss.str();
}

void write_readme(const std::string& path, const SynthOptions& o, const SynthProject& p) {
  std::ostringstream ss;
  const BoundingBox box = p.truth.bounding_box();
  ss << "# Synthetic MeshNBV project\n\n"
     << "Made by `meshnbv synth`: " << describe(o) << ".\n\n"
     << "| file | what |\n|---|---|\n"
     << "| truth.ply | ground-truth mesh (" << p.truth.num_faces()
     << " faces; face property `material`) |\n"
     << "| degraded.ply | the degraded reconstruction (" << p.scene.mesh.num_faces()
     << " faces; face property `gt_error` = mean distance of face samples to the truth, metres) |\n"
     << "| gt_error.csv | the same per-face error as `face,gt_error` |\n"
     << "| images/ | the rendered views (procedural solid texture, Lambert + ambient shading) |\n"
     << "| project.mlp | MeshLab project: degraded mesh + rasters |\n"
     << "| scene.json | the same as a MeshNBV JSON scene |\n\n"
     << "Bounding box: (" << box.min.transpose() << ") .. (" << box.max.transpose()
     << "), diagonal " << box.diagonal() << " m.\n\n"
     << "Degradations, in order:\n\n";
  const auto& degradations = o.degradations;
  std::size_t regional = 0;
  for (const auto& d : degradations) {
    ss << "- " << degradation_name(d.kind) << ", strength " << d.strength;
    if (d.kind != DegradationKind::Decimate && regional < p.region_centers.size()) {
      ss << ", radius " << d.radius << " of the diagonal, centred at ("
         << p.region_centers[regional].transpose() << ")";
      ++regional;
    }
    ss << "\n";
  }
  ss << "\nSuggested completeness threshold: " << p.completeness_threshold
     << " m (1% of the diagonal).\n";
  io::write_atomically(path, [&](std::ostream& out) { out << ss.str(); });
}

}  // namespace

SynthProject make_synthetic_project(const SynthOptions& options) {
  SynthOptions o = options;
  o.check();
  if (o.degradations.empty()) {
    o.degradations.push_back(parse_degradation("noise"));
    o.degradations.push_back(parse_degradation("dent"));
  }
  SynthProject p;
  GeneratorOptions g = o.generator;
  g.seed = o.seed;
  p.truth = o.scene == "object" ? load_object(o.mesh_file) : make_scene_mesh(o.scene, g);
  DegradeResult degraded = degrade(p.truth, o.degradations, o.seed);
  if (degraded.mesh.empty())
    throw Error("the degradations removed every face of the scene (a hole or decimation too large)");
  p.region_centers = degraded.region_centers;
  p.scene.mesh = std::move(degraded.mesh);
  p.scene.mesh.face_attributes.erase(kMaterialAttribute);
  p.gt_error = face_distance_to_surface(p.scene.mesh, p.truth);
  p.scene.mesh.set_face_attribute("gt_error", p.gt_error);
  p.completeness_threshold = 0.01 * p.truth.bounding_box().diagonal();
  CameraSetOptions c = o.cameras;
  c.seed = o.seed;
  const auto cams = make_cameras(p.truth, c);
  for (std::size_t i = 0; i < cams.size(); ++i) {
    View v;
    char label[32];
    std::snprintf(label, sizeof(label), "view_%03zu", i);
    v.label = label;
    v.camera = cams[i];
    p.scene.views.push_back(v);
  }
  p.scene.format = "synthetic";
  return p;
}

SynthProject write_synthetic_project(const SynthOptions& options, const std::string& folder,
                                     const ProgressCallback& progress) {
  options.check();
  io::check_can_write_folder(folder);
  std::error_code ec;
  if (fs::exists(folder, ec) && !fs::is_empty(folder, ec) && !options.overwrite)
    throw Error("output folder is not empty; pass --overwrite to write into it", folder);
  SynthOptions o = options;
  if (o.degradations.empty()) {
    o.degradations.push_back(parse_degradation("noise"));
    o.degradations.push_back(parse_degradation("dent"));
  }
  report_progress(progress, 0.0, "scene");
  SynthProject p = make_synthetic_project(o);
  fs::create_directories(fs::path(folder) / "images");

  const RayCaster caster(p.truth);
  const SolidTexture texture = make_texture(o, p.truth, p.scene.views);
  RenderInputs in{&p.truth, &caster, &texture, p.truth.face_attribute(kMaterialAttribute)};
  for (std::size_t i = 0; i < p.scene.views.size(); ++i) {
    View& v = p.scene.views[i];
    std::vector<float> depth;
    const Image image = render(in, v.camera, o.render, o.write_depth ? &depth : nullptr);
    v.image_path = (fs::path(folder) / "images" / (v.label + ".png")).string();
    image.save(v.image_path);
    if (o.write_depth) {
      cv::Mat d(v.camera.height, v.camera.width, CV_32FC1, depth.data());
      const std::string depth_path = (fs::path(folder) / "images" / (v.label + "_depth.tiff")).string();
      if (!cv::imwrite(depth_path, d)) throw Error("cannot write depth map", depth_path);
    }
    report_progress(progress, double(i + 1) / p.scene.views.size(), "render");
  }

  io::PlyWriteOptions ply;
  ply.overwrite = true;
  io::write_ply(p.truth, (fs::path(folder) / "truth.ply").string(), ply);
  const std::string degraded_path = (fs::path(folder) / "degraded.ply").string();
  io::write_ply(p.scene.mesh, degraded_path, ply);
  p.scene.mesh_path = degraded_path;
  io::write_atomically((fs::path(folder) / "gt_error.csv").string(), [&](std::ostream& out) {
    out << "face,gt_error\n";
    out.precision(9);
    for (std::size_t f = 0; f < p.gt_error.size(); ++f) out << f << "," << p.gt_error[f] << "\n";
  });
  io::write_mlp(p.scene, (fs::path(folder) / "project.mlp").string(), degraded_path, true);
  io::write_json_scene(p.scene, (fs::path(folder) / "scene.json").string(), degraded_path, true);
  write_readme((fs::path(folder) / "README.md").string(), o, p);
  p.scene.source = (fs::path(folder) / "project.mlp").string();
  return p;
}

}  // namespace meshnbv::synth
