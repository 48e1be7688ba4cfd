// Procedural scenes with exact ground truth (the paper's building, fortress
// and city), sizes in metres, and camera layouts around them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "meshnbv/camera.h"
#include "meshnbv/mesh.h"

namespace meshnbv::synth {

// Face attribute "material" (float-coded integer) selects the texture
// pattern of each face: see texture.h.
constexpr const char* kMaterialAttribute = "material";

struct GeneratorOptions {
  std::uint64_t seed = 1;
  // Target edge length of the triangulation (metres): surfaces are
  // subdivided so that degradations and PRI have faces to work on.
  double edge_length = 0.0;  // 0 = generator default
};

// A block with facade texture (windows), a roof slab, parapet and roof details.
TriangleMesh make_building(const GeneratorOptions& options = {});
// Curtain walls and towers around a court, on a ground plane.
TriangleMesh make_fortress(const GeneratorOptions& options = {});
// A grid of blocks of different heights on a ground plane.
TriangleMesh make_city(const GeneratorOptions& options = {});
// The edge length a scene uses when GeneratorOptions::edge_length is 0
// (building 0.3, fortress 0.6, city 0.8 metres); 0 for other names.
double default_edge_length(const std::string& scene);
// "building", "fortress", "city"; throws Error otherwise.
TriangleMesh make_scene_mesh(const std::string& name, const GeneratorOptions& options = {});

// Closed axis-aligned box split into a grid with cells no longer than
// `edge_length`; normals outward. `material` per face.
TriangleMesh make_box(const Vec3& min, const Vec3& max, double edge_length, int material);
// Closed prism (cylinder approximation) with `sides` sides around the z axis.
TriangleMesh make_prism(const Vec3& base_center, double radius, double height, int sides,
                        double edge_length, int material);
// A flat rectangle at height z facing +z (bounded: its border is a boundary).
TriangleMesh make_ground(const Vec3& min, const Vec3& max, double edge_length, int material);

enum class CameraLayout { Ring, Hemisphere, Orbit, Grid };
// "ring", "hemisphere", "orbit", "grid"
CameraLayout parse_camera_layout(const std::string& name);
std::string camera_layout_name(CameraLayout layout);

struct CameraSetOptions {
  CameraLayout layout = CameraLayout::Ring;
  int count = 24;
  int width = 640, height = 480;
  double horizontal_fov_degrees = 60.0;
  // The bounding box's corners stay within this share of the image from
  // every camera (one distance for the whole set).
  double fill = 0.9;
  double elevation_degrees = 25.0;  // ring; orbit uses several elevations
  std::uint64_t seed = 1;           // small deterministic jitter of the orbit
};

// Cameras looking at the mesh's bounding-box centre, world +z up; `grid`
// instead flies a survey over the box: nadir photos on a lawnmower grid
// over its footprint, high enough for 60% overlap between neighbours, each
// seeing only part of the scene.
std::vector<PinholeCamera> make_cameras(const TriangleMesh& mesh, const CameraSetOptions& options);

}  // namespace meshnbv::synth
