// The Delaunay visibility mesher's time (bench/mesher/run.sh): points like
// the dense backend's fused ones (area-uniform on a synthetic scene's true
// surface, noise along the normal of 0.1% of the diagonal), each seen by
// its most frontal unoccluded ring cameras, meshed by mesh_from_visibility
// with the loop's options on 1 and 2 threads. Prints one JSON object per
// line: scene, points, threads, round, seconds (and the phases unless
// MESHNBV_MESHER_BENCH_NO_PHASES, for a build before they existed), and the
// output's size and a checksum of its vertices that does not depend on
// their order (the same surface from any build and thread count).
//
//   mesher_bench SCENE POINTS VIEWS_PER_POINT ROUNDS THREADS...
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "meshnbv/camera.h"
#include "meshnbv/eval/visibility_mesher.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/synth/generators.h"

using namespace meshnbv;

namespace {

std::vector<eval::SparsePoint> fused_like_points(const TriangleMesh& mesh,
                                                 const std::vector<PinholeCamera>& cams, std::size_t count,
                                                 std::size_t views_per_point) {
  const RayCaster caster(mesh);
  const std::vector<double> areas = mesh.face_areas();
  const std::vector<Vec3> normals = mesh.face_normals();
  const double noise = 1e-3 * mesh.bounding_box().diagonal();
  std::mt19937_64 rng(7);
  std::discrete_distribution<std::size_t> pick(areas.begin(), areas.end());
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, noise);
  std::vector<eval::SparsePoint> points;
  while (points.size() < count) {
    const std::size_t f = pick(rng);
    double a = u(rng), b = u(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const Face& t = mesh.faces[f];
    const Vec3 on = mesh.vertices[std::size_t(t[0])] +
                    a * (mesh.vertices[std::size_t(t[1])] - mesh.vertices[std::size_t(t[0])]) +
                    b * (mesh.vertices[std::size_t(t[2])] - mesh.vertices[std::size_t(t[0])]);
    std::vector<std::pair<double, int>> seen;  // (-cos, camera)
    for (std::size_t c = 0; c < cams.size(); ++c) {
      const Vec3 to = cams[c].center() - on;
      const double cosine = normals[f].dot(to.normalized());
      Vec2 px;
      if (cosine <= 0.2 || !cams[c].project(on, &px) || !cams[c].in_image(px)) continue;
      if (!caster.segment_clear(cams[c].center(), on, 1e-4, 1e-6)) continue;
      seen.emplace_back(-cosine, int(c));
    }
    if (seen.size() < 3) continue;
    std::sort(seen.begin(), seen.end());
    eval::SparsePoint p;
    p.position = on + gauss(rng) * normals[f];
    for (std::size_t k = 0; k < std::min(views_per_point, seen.size()); ++k)
      p.views.push_back(seen[k].second);
    points.push_back(std::move(p));
  }
  return points;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: mesher_bench SCENE POINTS VIEWS_PER_POINT ROUNDS THREADS...\n");
    return 2;
  }
  const std::string scene = argv[1];
  const auto count = std::size_t(std::atol(argv[2]));
  const auto views = std::size_t(std::atol(argv[3]));
  const int rounds = std::atoi(argv[4]);
  const TriangleMesh truth = synth::make_scene_mesh(scene);
  synth::CameraSetOptions co;
  co.count = 24;
  const std::vector<PinholeCamera> cams = synth::make_cameras(truth, co);
  const std::vector<eval::SparsePoint> points = fused_like_points(truth, cams, count, views);
  std::vector<Vec3> centres;
  for (const PinholeCamera& c : cams) centres.push_back(c.center());
  for (int round = 0; round < rounds; ++round)
    for (int a = 5; a < argc; ++a) {
      const int threads = std::atoi(argv[a]);
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
      const eval::VisibilityMesherResult r = eval::mesh_from_visibility(points, centres);
      long long checksum = 0;  // integers: the same in any vertex order
      for (const Vec3& v : r.mesh.vertices)
        checksum += std::llround(1e6 * v.x()) + 2 * std::llround(1e6 * v.y()) + 3 * std::llround(1e6 * v.z());
      std::printf(
          "{\"scene\": \"%s\", \"points\": %zu, \"views_per_point\": %zu, \"threads\": %d, \"round\": %d, "
          "\"seconds\": %.4f, ",
          scene.c_str(), points.size(), views, threads, round, r.seconds);
#ifndef MESHNBV_MESHER_BENCH_NO_PHASES
      std::printf("\"seconds_delaunay\": %.4f, \"seconds_visibility\": %.4f, \"seconds_labelling\": %.4f, ",
                  r.seconds_delaunay, r.seconds_visibility, r.seconds_labelling);
#endif
      std::printf(
          "\"rays\": %zu, \"tetrahedra\": %zu, \"faces\": %zu, \"vertices\": %zu, \"vertex_checksum\": "
          "%lld}\n",
          r.rays, r.tetrahedra, r.mesh.num_faces(), r.mesh.num_vertices(), checksum);
      std::fflush(stdout);
    }
  return 0;
}
