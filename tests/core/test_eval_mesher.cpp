// The Delaunay visibility mesher on points sampled from known closed
// surfaces, seen by known cameras.
// Geometry: a unit sphere at the origin, or an axis-aligned box; cameras on
// a sphere of radius 4 around it; a point is seen by a camera when the
// surface faces it (convex shapes: nothing else occludes).
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>

#include "meshnbv/error.h"
#include "meshnbv/eval/metrics.h"
#include "meshnbv/eval/visibility_mesher.h"
#include "meshnbv/synth/generators.h"
#include "test_util.h"

namespace meshnbv::eval {
namespace {

std::vector<Vec3> fibonacci_sphere(int n, double radius) {
  std::vector<Vec3> out;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const double r = std::sqrt(1.0 - z * z);
    out.emplace_back(radius * r * std::cos(golden * i), radius * r * std::sin(golden * i), radius * z);
  }
  return out;
}

// Points seen by the cameras towards which their normal faces.
std::vector<SparsePoint> observe(const std::vector<Vec3>& points, const std::vector<Vec3>& normals,
                                 const std::vector<Vec3>& centres) {
  std::vector<SparsePoint> out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    SparsePoint p;
    p.position = points[i];
    for (std::size_t c = 0; c < centres.size(); ++c)
      if (normals[i].dot((centres[c] - points[i]).normalized()) > 0.3) p.views.push_back(int(c));
    out.push_back(p);
  }
  return out;
}

double signed_volume(const TriangleMesh& m) {
  double v = 0;
  for (const Face& f : m.faces)
    v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]])) / 6.0;
  return v;
}

TEST(EvalMesher, SphereIsClosedOutwardAndOnTheSurface) {
  const std::vector<Vec3> pts = fibonacci_sphere(1500, 1.0);
  const std::vector<Vec3> centres = fibonacci_sphere(20, 4.0);
  const VisibilityMesherResult r = mesh_from_visibility(observe(pts, pts, centres), centres);
  const TriangleMesh& m = r.mesh;
  ASSERT_FALSE(m.empty());
  EXPECT_EQ(r.points, 1500u);
  EXPECT_EQ(r.failed_rays, 0u);
  EXPECT_TRUE(check_mesh(m).closed()) << check_mesh(m).boundary_edges << " boundary edges";
  EXPECT_EQ(m.num_faces(), 2 * 1500u - 4);  // the convex hull of points on a sphere
  // Outward: positive volume close to the ball's (the polyhedron is inscribed).
  EXPECT_NEAR(signed_volume(m), 4.0 / 3.0 * M_PI, 0.03);
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const Vec3 c = m.face_centroid(f);
    EXPECT_GT(m.face_normal(f).dot(c.normalized()), 0.9);
    EXPECT_GT(c.norm(), 0.99);
  }
}

TEST(EvalMesher, BoxMatchesTheTruth) {
  // Points on a 2 x 1 x 1 box (a grid of 0.05 on each face), normals of their faces.
  const TriangleMesh box = synth::make_box(Vec3(-1, -0.5, -0.5), Vec3(1, 0.5, 0.5), 0.1, 0);
  std::vector<Vec3> pts, normals;
  for (const Vec3& p : sample_surface(box, 0.05, 3)) {
    Vec3 n = Vec3::Zero();
    const Vec3 q(p.x() / 1.0, p.y() / 0.5, p.z() / 0.5);
    int axis = 0;
    q.cwiseAbs().maxCoeff(&axis);
    n[axis] = q[axis] > 0 ? 1 : -1;
    pts.push_back(p);
    normals.push_back(n);
  }
  const std::vector<Vec3> centres = fibonacci_sphere(30, 4.0);
  const VisibilityMesherResult r = mesh_from_visibility(observe(pts, normals, centres), centres);
  ASSERT_FALSE(r.mesh.empty());
  EXPECT_GT(signed_volume(r.mesh), 0.9 * 2.0);
  EXPECT_LT(signed_volume(r.mesh), 2.0 + 1e-9);
  EvaluationOptions o;
  o.thresholds = {0.01, 0.02};
  o.sample_spacing = 0.01;
  const EvaluationResult e = evaluate_reconstruction(r.mesh, box, o);
  EXPECT_LT(e.accuracy[1].second, 0.01);  // 90% of the surface within 1 cm of the truth
  EXPECT_GT(e.completeness[1].second, 0.97);
}

TEST(EvalMesher, ConcavityIsCarvedByVisibility) {
  // Points on a sphere and on a cube-shaped dent in its top (the
  // dent is seen only from above): the mesh must follow the dent, which the
  // convex hull of the points (what a mesher without visibility would give) does not.
  std::vector<Vec3> pts, normals;
  for (const Vec3& p : fibonacci_sphere(3000, 1.0))
    if (!(std::abs(p.x()) < 0.35 && std::abs(p.y()) < 0.35 && p.z() > 0)) {
      pts.push_back(p);
      normals.push_back(p);
    }
  // The dent's floor at z = 0.4, its four walls from z = 0.4 to the sphere.
  for (double x = -0.34; x <= 0.34; x += 0.04)
    for (double y = -0.34; y <= 0.34; y += 0.04) {
      pts.emplace_back(x, y, 0.4);
      normals.emplace_back(0, 0, 1);
    }
  std::vector<Vec3> centres;
  for (int k = 0; k < 12; ++k) {
    const double a = 2 * M_PI * k / 12;
    centres.emplace_back(0.8 * std::cos(a), 0.8 * std::sin(a), 4.0);  // above
    centres.emplace_back(4 * std::cos(a), 4 * std::sin(a), 0.0);      // around
  }
  std::vector<SparsePoint> obs = observe(pts, normals, centres);
  // Only the cameras above see the dent's floor (the rim hides it from the ring).
  for (SparsePoint& p : obs)
    if (std::abs(p.position.z() - 0.4) < 1e-9) {
      std::vector<int> above;
      for (int v : p.views)
        if (centres[std::size_t(v)].z() > 1) above.push_back(v);
      p.views = above;
    }
  const VisibilityMesherResult r = mesh_from_visibility(obs, centres);
  ASSERT_FALSE(r.mesh.empty());
  // The centre of the dent floor is on the surface: nothing above it.
  const Vec3 probe(0, 0, 0.4);
  double nearest = 1e9;
  for (std::size_t f = 0; f < r.mesh.num_faces(); ++f)
    nearest = std::min(nearest, (r.mesh.face_centroid(f) - probe).norm());
  EXPECT_LT(nearest, 0.05);
  for (std::size_t f = 0; f < r.mesh.num_faces(); ++f) {
    const Vec3 c = r.mesh.face_centroid(f);
    if (std::abs(c.x()) < 0.2 && std::abs(c.y()) < 0.2) {
      EXPECT_LT(c.z(), 0.45) << "face over the dent";
    }
  }
}

TEST(EvalMesher, SeparatelyObservedPartsAreNotBridged) {
  // Points on two facades of a 2 x 2 x 2 box (x = 1 and y = 1), each seen
  // only by its own three cameras: with FacetSupport::Edges no triangle may
  // join them, since no camera saw points of both facades.
  std::vector<SparsePoint> pts;
  const std::vector<Vec3> centres{Vec3(6, -0.5, 0), Vec3(6, 0, 0.5), Vec3(6, 0.3, -0.4),
                                  Vec3(-0.5, 6, 0), Vec3(0, 6, 0.5), Vec3(0.3, 6, -0.4)};
  for (double a = -0.9; a <= 0.5; a += 0.1)
    for (double b = -0.9; b <= 0.9; b += 0.1) {
      pts.push_back({Vec3(1, a, b), {0, 1, 2}});
      pts.push_back({Vec3(a, 1, b), {3, 4, 5}});
    }
  VisibilityMesherOptions edges;
  edges.facet_support = FacetSupport::Edges;
  const VisibilityMesherResult r = mesh_from_visibility(pts, centres, edges);
  ASSERT_FALSE(r.mesh.empty());
  for (const Face& f : r.mesh.faces) {
    int on_x = 0, on_y = 0;
    for (int v : f) {
      on_x += std::abs(r.mesh.vertices[std::size_t(v)].x() - 1) < 1e-9;
      on_y += std::abs(r.mesh.vertices[std::size_t(v)].y() - 1) < 1e-9;
    }
    EXPECT_TRUE(on_x == 3 || on_y == 3) << "a triangle joins the two facades";
  }
  // Both facades are there, facing their cameras.
  std::size_t x_faces = 0, y_faces = 0;
  for (std::size_t f = 0; f < r.mesh.num_faces(); ++f) {
    const Vec3 n = r.mesh.face_normal(f);
    x_faces += n.x() > 0.99;
    y_faces += n.y() > 0.99;
  }
  EXPECT_GT(x_faces, 200u);
  EXPECT_GT(y_faces, 200u);
  // With the default rule (a camera of any corner faces it) the corner is
  // closed by bridging triangles; with Common, as with Edges, it is not.
  const VisibilityMesherResult any = mesh_from_visibility(pts, centres);
  EXPECT_GT(any.mesh.num_faces(), r.mesh.num_faces());
  VisibilityMesherOptions common;
  common.facet_support = FacetSupport::Common;
  EXPECT_EQ(mesh_from_visibility(pts, centres, common).mesh.num_faces(), r.mesh.num_faces());
}

TEST(EvalMesher, VoteLabellingAlsoGivesTheSphere) {
  const std::vector<Vec3> pts = fibonacci_sphere(800, 1.0);
  const std::vector<Vec3> centres = fibonacci_sphere(20, 4.0);
  VisibilityMesherOptions o;
  o.labelling = Labelling::Vote;
  const VisibilityMesherResult r = mesh_from_visibility(observe(pts, pts, centres), centres, o);
  EXPECT_TRUE(check_mesh(r.mesh).closed());
  EXPECT_NEAR(signed_volume(r.mesh), 4.0 / 3.0 * M_PI, 0.06);
}

TEST(EvalMesher, TooFewOrFlatPointsGiveAnEmptyMesh) {
  const std::vector<Vec3> centres{Vec3(0, 0, 5), Vec3(1, 0, 5)};
  std::vector<SparsePoint> three{{Vec3(0, 0, 0), {0, 1}}, {Vec3(1, 0, 0), {0, 1}}, {Vec3(0, 1, 0), {0, 1}}};
  EXPECT_TRUE(mesh_from_visibility(three, centres).mesh.empty());
  std::vector<SparsePoint> flat;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) flat.push_back({Vec3(i, j, 0), {0, 1}});
  EXPECT_TRUE(mesh_from_visibility(flat, centres).mesh.empty());
  // Points seen by one camera only are dropped (min_views_per_point = 2).
  std::vector<SparsePoint> single;
  for (const Vec3& p : fibonacci_sphere(50, 1.0)) single.push_back({p, {0}});
  const auto r = mesh_from_visibility(single, centres);
  EXPECT_TRUE(r.mesh.empty());
  EXPECT_EQ(r.points, 0u);
}

// The rays are traced in parallel and counted (integers): any thread count
// gives the same surface, vertex for vertex; and the graph cut's labelling
// (the cells reachable from the source) matches the count of its parts.
TEST(EvalMesher, ThreadCountDoesNotChangeTheSurface) {
  const std::vector<Vec3> pts = fibonacci_sphere(3000, 1.0);
  std::vector<Vec3> noisy;
  for (std::size_t i = 0; i < pts.size(); ++i) noisy.push_back(pts[i] * (1.0 + 0.01 * std::sin(37.0 * double(i))));
  const std::vector<Vec3> centres = fibonacci_sphere(20, 4.0);
  const std::vector<SparsePoint> obs = observe(noisy, pts, centres);
  VisibilityMesherResult one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = mesh_from_visibility(obs, centres);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = mesh_from_visibility(obs, centres);
  }
  ASSERT_FALSE(one.mesh.empty());
  EXPECT_EQ(one.rays, two.rays);
  EXPECT_EQ(one.free_tetrahedra, two.free_tetrahedra);
  EXPECT_EQ(one.occupied_tetrahedra, two.occupied_tetrahedra);
  EXPECT_EQ(one.free_tetrahedra + one.occupied_tetrahedra, one.tetrahedra);
  ASSERT_EQ(one.mesh.vertices, two.mesh.vertices);
  ASSERT_EQ(one.mesh.faces, two.mesh.faces);
  EXPECT_TRUE(check_mesh(one.mesh).closed());
  EXPECT_GT(one.seconds, 0.0);
  EXPECT_LE(one.seconds_delaunay + one.seconds_visibility + one.seconds_labelling, one.seconds);
}

// A point given twice (as a fused point and a sparse one may be) shares
// one vertex, and the views of both reach it.
TEST(EvalMesher, RepeatedPointsShareAVertex) {
  const std::vector<Vec3> pts = fibonacci_sphere(800, 1.0);
  const std::vector<Vec3> centres = fibonacci_sphere(20, 4.0);
  std::vector<SparsePoint> obs = observe(pts, pts, centres);
  const VisibilityMesherResult once = mesh_from_visibility(obs, centres);
  const std::size_t n = obs.size();
  for (std::size_t i = 0; i < n; i += 2) obs.push_back(obs[i]);
  const VisibilityMesherResult twice = mesh_from_visibility(obs, centres);
  EXPECT_EQ(twice.points, 800u);
  EXPECT_EQ(twice.mesh.num_vertices(), once.mesh.num_vertices());
  EXPECT_EQ(twice.mesh.num_faces(), once.mesh.num_faces());
  EXPECT_TRUE(check_mesh(twice.mesh).closed());
}

TEST(EvalMesher, BadCameraIndexIsAnError) {
  std::vector<SparsePoint> pts{{Vec3(0, 0, 0), {0, 3}}};
  MESHNBV_EXPECT_ERROR_CONTAINS(mesh_from_visibility(pts, {Vec3(0, 0, 5)}), "names camera 3");
  VisibilityMesherOptions o;
  o.surface_weight = -1;
  MESHNBV_EXPECT_ERROR_CONTAINS(mesh_from_visibility({}, {}, o), "surface_weight");
}

}  // namespace
}  // namespace meshnbv::eval
