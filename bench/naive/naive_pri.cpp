// The whole PRI process against a naive reference and the paper-style
// baseline (issue #19), on one scene (bench/naive/run.sh: Middlebury
// templeRing, 47 views of 640x480, with the reference mesh of bench/eval),
// in alternating rounds of one run:
//
//  * compute_pri: the core, default options, all cores, the scene's image
//    cache emptied before each round (every photo decoded inside the call),
//    and its first phase (select_pri_views) timed on its own after it;
//  * naive: the SPEC's definitions written the plain way on one thread:
//    each photo decoded once (cv::imread, luminance), one occlusion ray per
//    vertex and view, a face's views those that see its three vertices
//    from its front within 80 degrees of its normal, r and the edge margin
//    by compute_pri's rules, each lattice point projected by the camera
//    and read bilinearly, all patches kept, and the SSD of every pair of
//    views (O(m^2 n));
//  * paper: the paper's OpenCV warping (bench/pri_baseline.h: an affine
//    warp of a 9x9 region per face and view, r = 8) on one thread, after
//    decoding the photos once and the core's view selection (its time
//    included).
//
// Usage: naive_pri SCENE MESH OUT.json [rounds]
// Writes medians, every round's times, the ratios and how far the naive
// and the core's PRI agree (Pearson, Spearman, faces observed by one only).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numeric>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "../pri_baseline.h"
#include "meshnbv/error.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"
#include "meshnbv/pri.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/visibility.h"

using namespace meshnbv;

namespace {

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Bilinear read of a CV_32F plane, false outside [0, W-1] x [0, H-1].
bool bilinear(const cv::Mat& g, double x, double y, float* out) {
  if (!(x >= 0 && y >= 0 && x <= g.cols - 1.0 && y <= g.rows - 1.0)) return false;
  const int ix = std::min(int(x), g.cols - 2), iy = std::min(int(y), g.rows - 2);
  const double wx = x - ix, wy = y - iy;
  const float* r0 = g.ptr<float>(iy) + ix;
  const float* r1 = g.ptr<float>(iy + 1) + ix;
  *out = float((1 - wy) * ((1 - wx) * r0[0] + wx * r0[1]) + wy * ((1 - wx) * r1[0] + wx * r1[1]));
  return true;
}

// Seconds of the naive reference's stages: decode, visibility, faces.
struct NaiveStages {
  double decode = 0, visibility = 0, faces = 0;
};

std::vector<float> naive_pri(const Scene& scene, NaiveStages* stages) {
  const TriangleMesh& mesh = scene.mesh;
  double t = now_s();
  const std::size_t V = scene.views.size(), F = mesh.num_faces();
  // Each photo decoded once.
  std::vector<cv::Mat> grey(V);
  for (std::size_t i = 0; i < V; ++i) {
    const cv::Mat bgr = cv::imread(scene.views[i].image_path, cv::IMREAD_COLOR);
    if (bgr.empty()) throw Error("naive: cannot read " + scene.views[i].image_path);
    cv::Mat f;
    bgr.convertTo(f, CV_32FC3, 1.0 / 255.0);
    cv::cvtColor(f, grey[i], cv::COLOR_BGR2GRAY);
  }
  stages->decode = now_s() - t;
  t = now_s();
  // One ray per vertex and view.
  const RayCaster caster(mesh);
  const double abs_eps = 1e-6 * mesh.bounding_box().diagonal();
  std::vector<char> visible(mesh.num_vertices() * V);
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v)
    for (std::size_t i = 0; i < V; ++i)
      visible[v * V + i] = point_visible(caster, scene.views[i].camera, mesh.vertices[v], 1e-4, abs_eps);
  stages->visibility = now_s() - t;
  t = now_s();
  const double min_cosine = std::cos(80.0 * M_PI / 180.0);
  std::vector<float> pri(F, std::nanf(""));
  std::vector<std::vector<float>> patches;
  for (std::size_t f = 0; f < F; ++f) {
    const Face& face = mesh.faces[f];
    const Vec3 &v0 = mesh.vertices[face[0]], &v1 = mesh.vertices[face[1]], &v2 = mesh.vertices[face[2]];
    const Vec3 g = (v0 + v1 + v2) / 3.0;
    const Vec3 n = (v1 - v0).cross(v2 - v0).normalized();
    std::vector<std::size_t> views;
    double max_edge = 0, shrink = 0;
    for (std::size_t i = 0; i < V; ++i) {
      if (!visible[face[0] * V + i] || !visible[face[1] * V + i] || !visible[face[2] * V + i]) continue;
      const PinholeCamera& cam = scene.views[i].camera;
      const Vec3 c = cam.center();
      if (n.dot(c - g) <= 0 || n.dot((c - g).normalized()) < min_cosine) continue;
      Vec2 p[3];
      for (int k = 0; k < 3; ++k) cam.project(mesh.vertices[face[k]], &p[k]);
      const double e = std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
      const double area =
          0.5 * std::abs((p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x());
      const double inner = 2.0 * area / (3.0 * e);
      max_edge = std::max(max_edge, e);
      shrink = std::max(shrink, inner > 0 ? 0.5 / inner : 1.0);
      views.push_back(i);
    }
    if (views.size() < 2) continue;
    const int r = std::clamp(int(std::ceil(max_edge)), 2, 32);
    const double keep = 1.0 - std::min(shrink, 0.5);
    const Vec3 w0 = g + keep * (v0 - g), w1 = g + keep * (v1 - g), w2 = g + keep * (v2 - g);
    patches.clear();
    for (std::size_t i : views) {
      std::vector<float> patch;
      bool ok = true;
      for (int a = 0; a <= r && ok; ++a)
        for (int b = 0; b <= r - a && ok; ++b) {
          const Vec3 X = (double(a) * w0 + double(b) * w1 + double(r - a - b) * w2) / double(r);
          Vec2 px;
          float s;
          ok = scene.views[i].camera.project(X, &px) && bilinear(grey[i], px.x(), px.y(), &s);
          patch.push_back(s);
        }
      if (ok) patches.push_back(std::move(patch));
    }
    if (patches.size() < 2) continue;
    double sum = 0;
    std::size_t pairs = 0;
    for (std::size_t a = 0; a < patches.size(); ++a)
      for (std::size_t b = a + 1; b < patches.size(); ++b, ++pairs) {
        double ssd = 0;
        for (std::size_t k = 0; k < patches[a].size(); ++k)
          ssd += double(patches[a][k] - patches[b][k]) * double(patches[a][k] - patches[b][k]);
        sum += ssd / double(patches[a].size());
      }
    pri[f] = float(sum / double(pairs));
  }
  stages->faces = now_s() - t;
  return pri;
}

std::vector<float> paper_pri(const Scene& scene) {
  PriOptions o;
  o.threads = 1;
  o.samples_per_side = 8;
  o.edge_margin = 0;  // the warp takes the whole triangle
  const bench::Selection s = select_pri_views(scene, o);
  const std::vector<cv::Mat> grey = bench::grey_planes(scene, s);
  std::vector<std::size_t> faces(scene.mesh.num_faces());
  std::iota(faces.begin(), faces.end(), std::size_t(0));
  std::vector<float> pri(faces.size(), std::nanf(""));
  bench::baseline_pri(scene.mesh, s, grey, faces, 8, 1, &pri);
  return pri;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::vector<double> ranks(const std::vector<double>& x) {
  std::vector<std::size_t> order(x.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  std::vector<double> r(x.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && x[order[j + 1]] == x[order[i]]) ++j;
    for (std::size_t k = i; k <= j; ++k) r[order[k]] = 0.5 * double(i + j);
    i = j + 1;
  }
  return r;
}

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const double ma = std::accumulate(a.begin(), a.end(), 0.0) / double(a.size());
  const double mb = std::accumulate(b.begin(), b.end(), 0.0) / double(b.size());
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    sab += (a[k] - ma) * (b[k] - mb), saa += (a[k] - ma) * (a[k] - ma), sbb += (b[k] - mb) * (b[k] - mb);
  return sab / std::sqrt(saa * sbb);
}

nlohmann::json agreement(const std::vector<float>& x, const std::vector<float>& core) {
  std::vector<double> a, b;
  std::size_t one_only = 0;
  for (std::size_t f = 0; f < x.size(); ++f) {
    if (std::isfinite(x[f]) && std::isfinite(core[f]))
      a.push_back(x[f]), b.push_back(core[f]);
    else if (std::isfinite(x[f]) != std::isfinite(core[f]))
      ++one_only;
  }
  return {{"faces_both", a.size()},
          {"faces_one_only", one_only},
          {"pearson", a.size() > 2 ? pearson(a, b) : 0.0},
          {"spearman", a.size() > 2 ? pearson(ranks(a), ranks(b)) : 0.0}};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: naive_pri SCENE MESH OUT.json [rounds]\n");
    return 2;
  }
  try {
    Scene scene = io::read_scene(argv[1]);
    scene.mesh = io::read_ply(argv[2]);
    const int rounds = argc > 4 ? std::max(1, std::atoi(argv[4])) : 3;
    std::map<std::string, std::vector<double>> times;
    std::vector<float> core, naive, paper;
    for (int round = 0; round < rounds; ++round) {
      // Alternate the order so that neither side always runs first.
      const bool core_first = round % 2 == 0;
      auto run_core = [&] {
        scene.images = std::make_shared<ImageCache>();
        const double t0 = now_s();
        const PriResult r = compute_pri(scene);
        times["compute_pri"].push_back(now_s() - t0);
        core = r.pri;
        // Its first phase alone (visibility and view selection; no photo
        // read): the rest of compute_pri is decoding and sampling.
        const double t1 = now_s();
        (void)select_pri_views(scene, PriOptions());
        times["compute_pri_selection"].push_back(now_s() - t1);
      };
      auto run_naive = [&] {
        const double t0 = now_s();
        NaiveStages st;
        naive = naive_pri(scene, &st);
        times["naive"].push_back(now_s() - t0);
        times["naive_decode"].push_back(st.decode);
        times["naive_visibility"].push_back(st.visibility);
        times["naive_faces"].push_back(st.faces);
      };
      auto run_paper = [&] {
        scene.images = std::make_shared<ImageCache>();
        const double t0 = now_s();
        paper = paper_pri(scene);
        times["paper"].push_back(now_s() - t0);
      };
      if (core_first)
        run_core(), run_naive(), run_paper();
      else
        run_paper(), run_naive(), run_core();
      std::fprintf(stderr, "round %d: compute_pri %.3f s, naive %.3f s, paper %.3f s\n", round,
                   times["compute_pri"].back(), times["naive"].back(), times["paper"].back());
    }
    nlohmann::json out;
    out["scene"] = argv[1];
    out["mesh"] = argv[2];
    out["faces"] = scene.mesh.num_faces();
    out["views"] = scene.views.size();
    out["threads_compute_pri"] = "all cores";
    out["rounds"] = rounds;
    for (const auto& [name, t] : times) {
      out["seconds"][name] = t;
      out["median_seconds"][name] = median(t);
    }
    out["naive_over_compute_pri"] = median(times["naive"]) / median(times["compute_pri"]);
    out["paper_over_compute_pri"] = median(times["paper"]) / median(times["compute_pri"]);
    out["agreement_with_compute_pri"] = {{"naive", agreement(naive, core)},
                                         {"paper", agreement(paper, core)}};
    std::ofstream(argv[3]) << out.dump(2) << "\n";
    std::printf("%s\n", out.dump(2).c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "naive_pri: %s\n", e.what());
    return 1;
  }
  return 0;
}
