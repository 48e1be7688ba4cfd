// Helpers of bench_pri.cpp (header-only: bench/CMakeLists.txt builds one
// executable per bench_*.cpp).
//
//  * select_views_like_core(): a copy of the view selection that
//    compute_pri() runs before sampling (core/src/pri.cpp: mesh validation,
//    Embree BVH, vertex visibility, back-face and grazing rules, interior
//    occlusion, max_views_per_face). It gives the benchmark the per-face view
//    lists (which compute_pri does not return) and the time of the selection
//    phase, so that the sampling + comparison time of compute_pri can be
//    obtained by subtraction. bench_pri checks at start-up that its view
//    counts equal compute_pri's pri_views; keep it in step with pri.cpp.
//
//  * baseline_pri(): the paper's original implementation of the patch
//    comparison (Morreale et al. 2018, OpenCV): for each face and each view
//    that sees it, the face's bounding region is warped with
//    cv::getAffineTransform + cv::warpAffine (INTER_LINEAR) onto a canonical
//    right triangle with legs of r pixels ((r+1)^2 patch, r = samples per
//    side), a triangle mask keeps the (r+1)(r+2)/2 pixels x + y <= r -- the
//    same lattice as the core's -- and every pair of patches is compared with
//    SSD over the masked pixels (cv::norm NORM_L2SQR with mask / count).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "meshnbv/pri.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/scene.h"
#include "meshnbv/visibility.h"

namespace meshnbv::bench {

struct Selection {
  std::vector<std::size_t> image_views;      // scene view of each camera below
  std::vector<PinholeCamera> cams;
  std::vector<std::vector<int>> views;       // per face: indices into cams, ascending
  std::vector<int> samples_per_side;         // per face (automatic rule when options say 0)
};

namespace detail {

inline double projected_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

inline bool interior_unoccluded(const TriangleMesh& mesh, const RayCaster& caster, std::size_t f,
                                const Vec3& c, const PriOptions& o, double abs_eps) {
  const Face& face = mesh.faces[f];
  const Vec3 &a = mesh.vertices[face[0]], &b = mesh.vertices[face[1]], &d = mesh.vertices[face[2]];
  const Vec3 points[4] = {(a + b + d) / 3.0, 0.5 * (a + b), 0.5 * (b + d), 0.5 * (d + a)};
  return caster.segments_clear4(c, points, o.visibility.relative_eps, abs_eps);
}

inline void select_face(const TriangleMesh& mesh, const std::vector<Vec3>& normals,
                        const VertexVisibility& vis, const RayCaster& caster,
                        const std::vector<PinholeCamera>& cams, const std::vector<Vec3>& centres,
                        std::size_t f, const PriOptions& o, double abs_eps, std::vector<int>* views,
                        int* samples_per_side) {
  struct Candidate {
    int view;
    double angle, area, max_edge;
  };
  std::vector<Candidate> candidates;
  const Vec3 centroid = mesh.face_centroid(f);
  const Face& face = mesh.faces[f];
  const double min_cosine = std::cos(o.max_incidence_angle * M_PI / 180.0);
  for (std::size_t i = 0; i < cams.size(); ++i) {
    if (!face_visible(mesh, normals, vis, f, i, centres[i])) continue;
    Vec2 p[3];
    for (int k = 0; k < 3; ++k) cams[i].project(mesh.vertices[face[k]], &p[k]);
    const double cosine = normals[f].dot((centres[i] - centroid).normalized());
    if (cosine < min_cosine) continue;
    if (o.check_interior_occlusion && !interior_unoccluded(mesh, caster, f, centres[i], o, abs_eps))
      continue;
    const double max_edge =
        std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
    candidates.push_back({int(i), std::acos(std::clamp(cosine, -1.0, 1.0)),
                          projected_area(p[0], p[1], p[2]), max_edge});
  }
  if (o.max_views_per_face > 0 && int(candidates.size()) > o.max_views_per_face) {
    std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
      if (a.angle != b.angle) return a.angle < b.angle;
      return a.area > b.area;
    });
    candidates.resize(std::size_t(o.max_views_per_face));
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.view < b.view; });
  }
  double max_edge = 0;
  views->clear();
  for (const auto& c : candidates) {
    views->push_back(c.view);
    max_edge = std::max(max_edge, c.max_edge);
  }
  *samples_per_side =
      o.samples_per_side > 0 ? o.samples_per_side : std::clamp(int(std::ceil(max_edge)), 2, 32);
}

}  // namespace detail

// The selection phase of compute_pri (same steps, same thread count).
inline Selection select_views_like_core(const Scene& scene, const PriOptions& o) {
  const TriangleMesh& mesh = scene.mesh;
  mesh.validate(scene.mesh_path);
  Selection s;
  std::vector<Vec3> centres;
  for (std::size_t i = 0; i < scene.views.size(); ++i)
    if (scene.views[i].has_image() && scene.views[i].used) {
      scene.views[i].camera.check("view '" + scene.views[i].label + "'");
      s.image_views.push_back(i);
      s.cams.push_back(scene.views[i].camera);
      centres.push_back(s.cams.back().center());
    }
  const std::size_t F = mesh.num_faces();
  s.views.resize(F);
  s.samples_per_side.resize(F);
  const int threads = o.threads > 0 ? o.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  arena.execute([&] {
    const RayCaster caster(mesh);
    const VertexVisibility vis(mesh, caster, s.cams, o.visibility);
    const std::vector<Vec3> normals = mesh.face_normals();
    const double abs_eps = o.visibility.absolute_eps_of_diagonal * mesh.bounding_box().diagonal();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, F), [&](const auto& r) {
      for (std::size_t f = r.begin(); f < r.end(); ++f)
        detail::select_face(mesh, normals, vis, caster, s.cams, centres, f, o, abs_eps, &s.views[f],
                            &s.samples_per_side[f]);
    });
  });
  return s;
}

// Luminance planes (CV_32F, [0, 1], 0.299 R + 0.587 G + 0.114 B) of the
// selection's views, for the baseline.
inline std::vector<cv::Mat> grey_planes(const Scene& scene, const Selection& s) {
  std::vector<cv::Mat> out;
  for (std::size_t v : s.image_views) {
    const auto image = scene.image(v);
    const int type = image->channels() == 1 ? CV_8UC1 : CV_8UC3;
    const cv::Mat wrap(image->height(), image->width(), type, const_cast<std::uint8_t*>(image->data()));
    cv::Mat f, grey;
    wrap.convertTo(f, image->channels() == 1 ? CV_32FC1 : CV_32FC3, 1.0 / 255.0);
    if (image->channels() == 1) grey = f;
    else cv::cvtColor(f, grey, cv::COLOR_RGB2GRAY);
    out.push_back(grey);
  }
  return out;
}

// The triangle mask of the canonical (r+1) x (r+1) patch: x + y <= r.
inline cv::Mat canonical_mask(int r) {
  cv::Mat mask(r + 1, r + 1, CV_8U, cv::Scalar(0));
  const cv::Point tri[3] = {{r, 0}, {0, r}, {0, 0}};
  cv::fillConvexPoly(mask, tri, 3, cv::Scalar(255));
  return mask;
}

// PRI (SSD) of the given faces by the paper's warping method, with the
// selection's views and a fixed r. pri[f] is written for the listed faces
// only (NaN when fewer than 2 views).
inline void baseline_pri(const TriangleMesh& mesh, const Selection& s,
                         const std::vector<cv::Mat>& grey, const std::vector<std::size_t>& faces,
                         int r, int threads, std::vector<float>* pri) {
  const cv::Mat mask = canonical_mask(r);
  const double count = double(cv::countNonZero(mask));
  const cv::Point2f canonical[3] = {{float(r), 0.f}, {0.f, float(r)}, {0.f, 0.f}};
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, faces.size(), 64), [&](const auto& range) {
      std::vector<cv::Mat> patches;
      for (std::size_t j = range.begin(); j < range.end(); ++j) {
        const std::size_t f = faces[j];
        const std::vector<int>& views = s.views[f];
        if (patches.size() < views.size()) patches.resize(views.size());
        const Face& face = mesh.faces[f];
        for (std::size_t k = 0; k < views.size(); ++k) {
          const PinholeCamera& cam = s.cams[std::size_t(views[k])];
          const cv::Mat& image = grey[std::size_t(views[k])];
          cv::Point2f p[3];
          for (int q = 0; q < 3; ++q) {
            Vec2 px;
            cam.project(mesh.vertices[face[q]], &px);
            p[q] = cv::Point2f(float(px.x()), float(px.y()));
          }
          // Bounding region (one pixel of margin for the bilinear neighbours).
          cv::Rect box = cv::boundingRect(std::vector<cv::Point2f>(p, p + 3));
          box.x -= 1, box.y -= 1, box.width += 2, box.height += 2;
          box &= cv::Rect(0, 0, image.cols, image.rows);
          cv::Point2f local[3];
          for (int q = 0; q < 3; ++q) local[q] = p[q] - cv::Point2f(float(box.x), float(box.y));
          const cv::Mat warp = cv::getAffineTransform(local, canonical);
          cv::warpAffine(image(box), patches[k], warp, cv::Size(r + 1, r + 1), cv::INTER_LINEAR,
                         cv::BORDER_REPLICATE);
        }
        if (views.size() < 2) {
          (*pri)[f] = std::numeric_limits<float>::quiet_NaN();
          continue;
        }
        double sum = 0;
        std::size_t pairs = 0;
        for (std::size_t a = 0; a < views.size(); ++a)
          for (std::size_t b = a + 1; b < views.size(); ++b, ++pairs)
            sum += cv::norm(patches[a], patches[b], cv::NORM_L2SQR, mask) / count;
        (*pri)[f] = float(sum / double(pairs));
      }
    });
  });
}

}  // namespace meshnbv::bench
