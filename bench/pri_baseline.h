// Helpers of bench_pri.cpp (header-only: bench/CMakeLists.txt builds one
// executable per bench_*.cpp).
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

// The per-face view lists come from the core (select_pri_views), so the
// baseline compares exactly the views compute_pri compares.
using Selection = PriViewSelection;

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
        const std::vector<int>& views = s.faces[f].views;
        if (patches.size() < views.size()) patches.resize(views.size());
        const Face& face = mesh.faces[f];
        for (std::size_t k = 0; k < views.size(); ++k) {
          const PinholeCamera& cam = s.cameras[std::size_t(views[k])];
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
