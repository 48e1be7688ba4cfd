// The report's display mesh (display_mesh.h): below the face budget the
// mesh itself; above it a decimated mesh whose faces carry the PRI of the
// original faces they stand for.
//
// Geometry: a closed unit sphere (latitude-longitude grid, fans at the
// poles), PRI 1 on x < 0 and 3 on x >= 0, unobserved (NaN) above z = 0.7;
// faces with x < -0.5 rest on 2 views only.
#include <cmath>
#include <limits>
#include <set>

#include "meshnbv/display_mesh.h"
#include "meshnbv/error.h"
#include "test_util.h"

using namespace meshnbv;

namespace {

TriangleMesh sphere(int rings, int segments) {
  TriangleMesh m;
  m.vertices.emplace_back(0, 0, 1);
  for (int r = 1; r < rings; ++r) {
    const double theta = M_PI * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * M_PI * s / segments;
      m.vertices.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
  }
  m.vertices.emplace_back(0, 0, -1);
  const int south = int(m.vertices.size()) - 1;
  auto at = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) m.faces.push_back({0, at(1, s), at(1, s + 1)});
  for (int r = 1; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      m.faces.push_back({at(r, s), at(r + 1, s), at(r + 1, s + 1)});
      m.faces.push_back({at(r, s), at(r + 1, s + 1), at(r, s + 1)});
    }
  for (int s = 0; s < segments; ++s) m.faces.push_back({south, at(rings - 1, s + 1), at(rings - 1, s)});
  return m;
}

PriResult two_sided_pri(const TriangleMesh& m) {
  PriResult r;
  const std::size_t n = m.num_faces();
  r.pri.resize(n);
  r.pri_views.assign(n, 4);
  r.pri_pairs.assign(n, 6);
  r.pri_samples.assign(n, 16);
  r.pri_texture.assign(n, 0.1f);
  r.status.resize(n);
  for (std::size_t f = 0; f < n; ++f) {
    const Vec3 c = m.face_centroid(f);
    r.pri[f] = c.z() > 0.7 ? std::numeric_limits<float>::quiet_NaN() : (c.x() < 0 ? 1.0f : 3.0f);
    if (c.x() < -0.5) r.pri_views[f] = 2;
  }
  return r;
}

}  // namespace

TEST(DisplayMesh, BelowTheBudgetNothingChanges) {
  const TriangleMesh m = sphere(40, 60);
  const DisplayMesh d = display_mesh(m, m.num_faces());
  EXPECT_FALSE(d.decimated);
  ASSERT_EQ(d.mesh.faces, m.faces);
  ASSERT_EQ(d.mesh.vertices, m.vertices);
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    ASSERT_EQ(d.display_face[f], int(f));
    ASSERT_EQ(d.member_begin[f + 1] - d.member_begin[f], 1u);
    ASSERT_EQ(d.members[d.member_begin[f]], f);
  }
  const PriResult pri = two_sided_pri(m);
  const DisplayPri shown = display_pri(d, m, pri, 0.01);
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    if (std::isnan(pri.pri[f])) {
      EXPECT_TRUE(std::isnan(shown.pri[f]));
      EXPECT_EQ(shown.flags[f], kDisplayUnobserved);
    } else {
      EXPECT_EQ(shown.pri[f], pri.pri[f]);
      EXPECT_EQ(shown.flags[f], pri.pri_views[f] == 2 ? kDisplayTwoViews : 0);
    }
  }
}

TEST(DisplayMesh, DecimatedFacesStandForNearbyOriginalFaces) {
  const TriangleMesh m = sphere(100, 160);  // 31,680 faces
  const std::size_t budget = 3000;
  const DisplayMesh d = display_mesh(m, budget);
  ASSERT_TRUE(d.decimated);
  EXPECT_LE(d.mesh.num_faces(), budget);
  EXPECT_GT(d.mesh.num_faces(), budget / 2);
  // Still the sphere: every display vertex on it.
  for (const Vec3& v : d.mesh.vertices) EXPECT_NEAR(v.norm(), 1.0, 0.05);
  // Every original face stands in exactly one display face, near it: the
  // display faces are about 0.1 across here.
  ASSERT_EQ(d.display_face.size(), m.num_faces());
  ASSERT_EQ(d.member_begin.size(), d.mesh.num_faces() + 1);
  ASSERT_EQ(d.member_begin.back(), m.num_faces());
  std::set<std::uint32_t> seen;
  for (std::size_t k = 0; k < d.mesh.num_faces(); ++k) {
    ASSERT_GT(d.member_begin[k + 1], d.member_begin[k]) << "display face " << k << " stands for no face";
    for (std::uint32_t i = d.member_begin[k]; i < d.member_begin[k + 1]; ++i) {
      const std::uint32_t f = d.members[i];
      ASSERT_EQ(d.display_face[f], int(k));
      ASSERT_TRUE(seen.insert(f).second);
      EXPECT_LT((m.face_centroid(f) - d.mesh.face_centroid(k)).norm(), 0.35) << "face " << f;
    }
  }
}

TEST(DisplayMesh, DecimatedValuesComeFromTheFacesTheyCover) {
  const TriangleMesh m = sphere(100, 160);
  const PriResult pri = two_sided_pri(m);
  const DisplayMesh d = display_mesh(m, 3000);
  const DisplayPri shown = display_pri(d, m, pri, 0.01);
  ASSERT_EQ(shown.pri.size(), d.mesh.num_faces());
  std::size_t far_left = 0, far_right = 0, top = 0;
  for (std::size_t k = 0; k < d.mesh.num_faces(); ++k) {
    // The area-weighted mean of the observed members, by hand.
    double area = 0, observed = 0, sum = 0, two = 0;
    for (std::uint32_t i = d.member_begin[k]; i < d.member_begin[k + 1]; ++i) {
      const std::size_t f = d.members[i];
      area += m.face_area(f);
      if (std::isnan(pri.pri[f])) continue;
      observed += m.face_area(f);
      sum += m.face_area(f) * pri.pri[f];
      if (pri.pri_views[f] == 2) two += m.face_area(f);
    }
    if (observed < 0.5 * area) {
      EXPECT_TRUE(std::isnan(shown.pri[k]));
      EXPECT_EQ(shown.flags[k], kDisplayUnobserved);
      continue;
    }
    EXPECT_NEAR(shown.pri[k], sum / observed, 1e-5);
    EXPECT_EQ((shown.flags[k] & kDisplayTwoViews) != 0, two > 0.5 * observed);
    // Away from the borders of the regions, exactly the side's value.
    const Vec3 c = d.mesh.face_centroid(k);
    if (c.z() < 0.5 && c.x() < -0.3) {
      EXPECT_EQ(shown.pri[k], 1.0f);
      ++far_left;
    }
    if (c.z() < 0.5 && c.x() > 0.3) {
      EXPECT_EQ(shown.pri[k], 3.0f);
      ++far_right;
    }
    if (c.x() < -0.7 && c.z() < 0.5) {
      EXPECT_TRUE(shown.flags[k] & kDisplayTwoViews);
    }
  }
  for (std::size_t k = 0; k < d.mesh.num_faces(); ++k)
    if (d.mesh.face_centroid(k).z() > 0.85) {
      EXPECT_TRUE(std::isnan(shown.pri[k]));
      ++top;
    }
  EXPECT_GT(far_left, 300u);
  EXPECT_GT(far_right, 300u);
  EXPECT_GT(top, 10u);
}

TEST(DisplayMesh, FacesOpenMeshCannotHoldAreKept) {
  TriangleMesh m = sphere(60, 80);
  // A third face on an edge of the sphere (non-manifold) and a repeated index.
  const int extra = int(m.vertices.size());
  m.vertices.emplace_back(0.0, 0.0, 2.0);
  const Face on_edge{m.faces[100][0], m.faces[100][1], extra};
  m.faces.push_back(on_edge);
  m.faces.push_back({1, 1, 2});
  const DisplayMesh d = display_mesh(m, 2000);
  ASSERT_TRUE(d.decimated);
  const std::size_t n = m.num_faces();
  for (std::size_t f : {n - 2, n - 1}) {
    const Face& shown = d.mesh.faces[std::size_t(d.display_face[f])];
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(d.mesh.vertices[std::size_t(shown[std::size_t(k)])], m.vertices[std::size_t(m.faces[f][std::size_t(k)])]);
  }
}

TEST(DisplayMesh, ZeroBudgetIsRefused) {
  EXPECT_THROW(display_mesh(sphere(10, 10), 0), Error);
}

// The interaction mesh: the display mesh decimated again, its maps composed
// from the original faces, its vertices display vertices, its values
// area-weighted over the original faces.
TEST(DisplayMesh, CoarseCopyComposesTheMaps) {
  const TriangleMesh m = sphere(100, 160);  // 31,680 faces
  const DisplayMesh d = display_mesh(m, 8000);
  const CoarseDisplayMesh c = coarse_display_mesh(d, 1500);
  ASSERT_TRUE(c.mesh.decimated);
  EXPECT_LE(c.mesh.mesh.num_faces(), 1500u);
  ASSERT_EQ(c.coarse_face.size(), d.mesh.num_faces());
  ASSERT_EQ(c.mesh.display_face.size(), m.num_faces());
  for (std::size_t f = 0; f < m.num_faces(); ++f)
    ASSERT_EQ(c.mesh.display_face[f], c.coarse_face[std::size_t(d.display_face[f])]) << "face " << f;
  ASSERT_EQ(c.mesh.member_begin.back(), m.num_faces());
  for (std::size_t k = 0; k + 1 < c.mesh.member_begin.size(); ++k)
    for (std::uint32_t i = c.mesh.member_begin[k]; i < c.mesh.member_begin[k + 1]; ++i)
      ASSERT_EQ(c.mesh.display_face[c.mesh.members[i]], int(k));
  ASSERT_EQ(c.mesh.source_vertex.size(), c.mesh.mesh.vertices.size());
  for (std::size_t v = 0; v < c.mesh.mesh.vertices.size(); ++v) {
    const int s = c.mesh.source_vertex[v];
    ASSERT_GE(s, 0);
    ASSERT_LT(std::size_t(s), d.mesh.vertices.size());
    EXPECT_EQ(c.mesh.mesh.vertices[v], d.mesh.vertices[std::size_t(s)]);
  }
  // Values: the area-weighted PRI of the original faces each coarse face stands for.
  const PriResult pri = two_sided_pri(m);
  const DisplayPri shown = display_pri(c.mesh, m, pri, 0.01);
  for (std::size_t k = 0; k + 1 < c.mesh.member_begin.size(); ++k) {
    double sum = 0, area = 0, all = 0;
    for (std::uint32_t i = c.mesh.member_begin[k]; i < c.mesh.member_begin[k + 1]; ++i) {
      const std::uint32_t f = c.mesh.members[i];
      const double a = m.face_area(f);
      all += a;
      if (std::isnan(pri.pri[f])) continue;
      sum += a * pri.pri[f];
      area += a;
    }
    if (area < 0.5 * all)
      EXPECT_TRUE(std::isnan(shown.pri[k])) << "coarse face " << k;
    else
      EXPECT_NEAR(shown.pri[k], sum / area, 1e-4) << "coarse face " << k;
  }
  // At or below the budget: the display mesh itself, face for face (still
  // "decimated": it stands for the original faces as the display mesh does).
  const CoarseDisplayMesh same = coarse_display_mesh(d, d.mesh.num_faces());
  EXPECT_EQ(same.mesh.mesh.faces, d.mesh.faces);
  EXPECT_EQ(same.mesh.display_face, d.display_face);
  for (std::size_t k = 0; k < same.coarse_face.size(); ++k) ASSERT_EQ(same.coarse_face[k], int(k));
  EXPECT_THROW(coarse_display_mesh(d, 0), Error);
}
