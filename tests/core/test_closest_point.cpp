// RayCaster::closest_point (Embree point query + exact per-triangle closest
// point): one test per Voronoi region of a triangle, degenerate faces,
// far-from-origin meshes, and agreement with CGAL's SurfaceDistance.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "meshnbv/error.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/surface_distance.h"
#include "meshnbv/synth/generators.h"

namespace meshnbv {
namespace {

// The triangle (0,0,0), (1,0,0), (0,1,0) in the plane z = 0.
TriangleMesh unit_triangle(const Vec3& offset = Vec3::Zero()) {
  TriangleMesh m;
  m.vertices = {offset + Vec3(0, 0, 0), offset + Vec3(1, 0, 0), offset + Vec3(0, 1, 0)};
  m.faces = {{0, 1, 2}};
  return m;
}

void expect_closest(const RayCaster& caster, const Vec3& p, const Vec3& expected, double tol = 1e-12) {
  Vec3 q;
  int face = -1;
  const double d = caster.closest_point(p, &q, &face);
  EXPECT_NEAR((q - expected).norm(), 0.0, tol) << "query " << p.transpose();
  EXPECT_NEAR(d, (p - expected).norm(), tol);
  EXPECT_EQ(face, 0);
}

TEST(ClosestPoint, InteriorProjectsOntoThePlane) {
  const RayCaster c(unit_triangle());
  expect_closest(c, Vec3(0.2, 0.3, 0.7), Vec3(0.2, 0.3, 0));
  expect_closest(c, Vec3(0.2, 0.3, -2.0), Vec3(0.2, 0.3, 0));
}

TEST(ClosestPoint, VertexRegions) {
  const RayCaster c(unit_triangle());
  expect_closest(c, Vec3(-1, -1, 0.5), Vec3(0, 0, 0));
  expect_closest(c, Vec3(2, -0.5, 0.1), Vec3(1, 0, 0));
  expect_closest(c, Vec3(-0.5, 2, -0.3), Vec3(0, 1, 0));
}

TEST(ClosestPoint, EdgeRegions) {
  const RayCaster c(unit_triangle());
  expect_closest(c, Vec3(0.4, -1, 0.2), Vec3(0.4, 0, 0));   // edge v0-v1
  expect_closest(c, Vec3(-1, 0.6, 0.2), Vec3(0, 0.6, 0));   // edge v0-v2
  expect_closest(c, Vec3(1, 1, 0.0), Vec3(0.5, 0.5, 0));    // hypotenuse
}

TEST(ClosestPoint, PointOnTheSurfaceHasDistanceZero) {
  const RayCaster c(unit_triangle());
  expect_closest(c, Vec3(0.25, 0.25, 0), Vec3(0.25, 0.25, 0));
  expect_closest(c, Vec3(1, 0, 0), Vec3(1, 0, 0));
}

TEST(ClosestPoint, DegenerateFaceUsesItsEdges) {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};  // collinear: zero area
  m.faces = {{0, 1, 2}};
  const RayCaster c(m);
  Vec3 q;
  EXPECT_NEAR(c.closest_point(Vec3(1.5, 1, 0), &q), 1.0, 1e-12);
  EXPECT_NEAR((q - Vec3(1.5, 0, 0)).norm(), 0.0, 1e-12);
}

TEST(ClosestPoint, FarFromOriginKeepsPrecision) {
  // UTM-like coordinates: Embree works in floats relative to the box centre,
  // the closest point itself is computed in double.
  const Vec3 offset(5.0e5, 5.0e6, 250.0);
  const RayCaster c(unit_triangle(offset));
  expect_closest(c, offset + Vec3(0.2, 0.3, 0.01), offset + Vec3(0.2, 0.3, 0), 1e-9);
}

TEST(ClosestPoint, NearestOfSeveralFacesAndItsIndex) {
  TriangleMesh m = unit_triangle();
  const TriangleMesh far = unit_triangle(Vec3(0, 0, 5));
  m.vertices.insert(m.vertices.end(), far.vertices.begin(), far.vertices.end());
  m.faces.push_back({3, 4, 5});
  const RayCaster c(m);
  int face = -1;
  EXPECT_NEAR(c.closest_point(Vec3(0.1, 0.1, 4), nullptr, &face), 1.0, 1e-12);
  EXPECT_EQ(face, 1);
  EXPECT_NEAR(c.closest_point(Vec3(0.1, 0.1, 2), nullptr, &face), 2.0, 1e-12);
  EXPECT_EQ(face, 0);
}

TEST(ClosestPoint, BadQueriesThrow) {
  const RayCaster c(unit_triangle());
  EXPECT_THROW(c.closest_point(Vec3(NAN, 0, 0)), Error);
  EXPECT_THROW(c.closest_point(Vec3(INFINITY, 0, 0)), Error);
  const TriangleMesh empty;
  const RayCaster e(empty);
  EXPECT_THROW(e.closest_point(Vec3::Zero()), Error);
}

TEST(ClosestPoint, AgreesWithCgalOnAGeneratedScene) {
  const TriangleMesh mesh = synth::make_scene_mesh("fortress");
  const RayCaster embree(mesh);
  const SurfaceDistance cgal(mesh);
  const BoundingBox box = mesh.bounding_box();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p(box.min.x() + u(rng) * (box.max.x() - box.min.x()),
                 box.min.y() + u(rng) * (box.max.y() - box.min.y()),
                 box.min.z() + u(rng) * (box.max.z() - box.min.z()));
    ASSERT_NEAR(embree.closest_point(p), cgal.distance(p), 1e-9 * box.diagonal()) << p.transpose();
  }
}

}  // namespace
}  // namespace meshnbv
