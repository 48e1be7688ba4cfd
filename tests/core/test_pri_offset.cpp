// The offset measure (PriOptions::measure = offset) recovers a known
// displacement: a textured plane z = 0 is rendered by four cameras 5 m
// above it, and PRI is computed on the same plane moved by d along its
// normal. The sweep finds where the views agree again, so PRI (scene
// units) is |d| on the faces away from the border, for either sign of d,
// and near zero on the true plane. The expected values are written out
// here: no PRI run provides them.
#include <algorithm>
#include <cmath>
#include <vector>

#include "meshnbv/pri.h"
#include "plane_scene.h"

using namespace meshnbv;
using test::kPlaneEyes;
using test::kPlaneNoise;

namespace {

// The views of the true plane z = 0 (faces of 0.25 m), 400x300, f = 360 px.
Scene rendered_plane() {
  test::PlaneSceneOptions o;
  o.edge = 0.25;
  o.texture_seed = 5;
  o.texture_scale = 0.05;
  o.scale = 2;
  return test::plane_scene("pri_offset", kPlaneNoise, kPlaneEyes, o);
}

// The scene's mesh moved by dz along the plane's normal.
Scene moved(const Scene& s, double dz) {
  Scene out = s;
  for (Vec3& v : out.mesh.vertices) v.z() += dz;
  return out;
}

// Median PRI over the observed faces away from the plane's border.
double interior_median(const Scene& s, const PriResult& r, std::size_t* count) {
  std::vector<double> v;
  for (std::size_t f = 0; f < r.pri.size(); ++f) {
    const Vec3 c = s.mesh.face_centroid(f);
    if (r.status[f] == FaceStatus::Observed && std::abs(c.x()) < 1.2 && std::abs(c.y()) < 1.2)
      v.push_back(r.pri[f]);
  }
  *count = v.size();
  if (v.empty()) return std::nan("");
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

PriOptions offset_options() {
  PriOptions o;
  o.measure = Measure::Offset;
  return o;
}

}  // namespace

TEST(PriOffset, TruePlaneHasNearZeroOffset) {
  const Scene s = rendered_plane();
  const PriResult r = compute_pri(s, offset_options());
  std::size_t n = 0;
  const double m = interior_median(s, r, &n);
  EXPECT_GT(n, 100u);
  EXPECT_LT(m, 0.005) << "median offset on the true plane (m)";
}

// Displacements of about 1 and 2 pixels in the view where the normal moves
// the face most: at the plane's centre that view moves 360 px (the focal
// length) x sin(angle between ray and normal) / distance = 27.6 px per metre
// (29-34 px at (+-1, 1)), so 0.035 m and 0.07 m; up and down. Within the
// default sweep of +-3 px.
TEST(PriOffset, RecoversTheDisplacementOfAMovedPlane) {
  const Scene s = rendered_plane();
  for (double d : {0.035, -0.035, 0.07, -0.07}) {
    const PriResult r = compute_pri(moved(s, d), offset_options());
    std::size_t n = 0;
    const double m = interior_median(s, r, &n);
    EXPECT_GT(n, 100u) << d;
    EXPECT_NEAR(m, std::abs(d), 0.15 * std::abs(d)) << "median offset for a plane moved by " << d << " m";
  }
}

// The order follows the displacement, up to and beyond the sweep's range
// (0.2 m is 5.5-7 px: the estimate saturates near the range, 3 px = 0.1 m,
// but stays above the 2 px one).
TEST(PriOffset, GrowsWithTheDisplacement) {
  const Scene s = rendered_plane();
  double previous = -1;
  for (double d : {0.0, 0.02, 0.04, 0.07, 0.2}) {
    const PriResult r = compute_pri(moved(s, d), offset_options());
    std::size_t n = 0;
    const double m = interior_median(s, r, &n);
    EXPECT_GT(m, previous) << d;
    previous = m;
  }
}

// Beyond the range the sweep's least cost is at its end, and the cost falls
// steadily to it (offset_steady): most interior faces of the plane moved by
// 0.2 m (5.5-7 px) are marked so, and keep at least most of the range
// (3 px = 0.1 m at the centre); on the true plane the least cost is inside
// the sweep and hardly any face is marked.
TEST(PriOffset, MarksASteadyFallToTheEndBeyondTheRange) {
  const Scene s = rendered_plane();
  for (double d : {0.0, 0.2}) {
    const PriResult r = compute_pri(moved(s, d), offset_options());
    ASSERT_EQ(r.offset_steady.size(), r.pri.size());
    std::size_t interior = 0, steady = 0;
    for (std::size_t f = 0; f < r.pri.size(); ++f) {
      const Vec3 c = s.mesh.face_centroid(f);
      if (r.status[f] != FaceStatus::Observed || std::abs(c.x()) > 1.2 || std::abs(c.y()) > 1.2) continue;
      ++interior;
      const float mark = r.offset_steady[f];
      EXPECT_TRUE(mark == 0.0f || mark == 1.0f) << f;
      if (mark == 1.0f) {
        ++steady;
        EXPECT_EQ(r.offset_precision[f], 0.0f) << "a steady end has no curvature: face " << f;
      }
    }
    ASSERT_GT(interior, 100u);
    const double share = double(steady) / double(interior);
    if (d == 0.0) EXPECT_LT(share, 0.05) << "true plane";
    else EXPECT_GT(share, 0.8) << "plane moved by " << d << " m";  // measured 0.96 (true plane: 0)
  }
}
