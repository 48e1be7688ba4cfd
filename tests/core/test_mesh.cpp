#include <cmath>

#include "meshnbv/error.h"
#include "meshnbv/mesh.h"
#include "test_util.h"

using namespace meshnbv;

namespace {
// Unit cube, 12 outward-facing triangles: closed and manifold.
TriangleMesh cube() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  m.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}
}  // namespace

TEST(Mesh, CubeNormalsAreaAndBox) {
  const TriangleMesh m = cube();
  EXPECT_NEAR(m.total_area(), 6.0, 1e-12);
  const auto normals = m.face_normals();
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    // Outward: the normal points away from the cube centre.
    EXPECT_GT(normals[f].dot(m.face_centroid(f) - Vec3(0.5, 0.5, 0.5)), 0) << "face " << f;
    EXPECT_NEAR(normals[f].norm(), 1.0, 1e-12);
  }
  const auto vn = m.vertex_normals();
  EXPECT_NEAR((vn[7] - Vec3(1, 1, 1).normalized()).norm(), 0, 1e-12);
  const BoundingBox box = m.bounding_box();
  EXPECT_EQ(box.min, Vec3(0, 0, 0));
  EXPECT_EQ(box.max, Vec3(1, 1, 1));
  EXPECT_NEAR(box.diagonal(), std::sqrt(3.0), 1e-12);
}

TEST(Mesh, CheckClosedCube) {
  const MeshCheck c = check_mesh(cube());
  EXPECT_EQ(c.boundary_edges, 0u);
  EXPECT_EQ(c.nonmanifold_edges, 0u);
  EXPECT_EQ(c.degenerate_faces, 0u);
  EXPECT_TRUE(c.closed());
}

TEST(Mesh, CheckFindsBoundaryNonManifoldAndDegenerate) {
  TriangleMesh m = cube();
  m.faces.pop_back();  // opens the cube: 3 boundary edges
  MeshCheck open = check_mesh(m);
  EXPECT_EQ(open.boundary_edges, 3u);
  EXPECT_FALSE(open.closed());

  TriangleMesh fin = cube();
  fin.vertices.emplace_back(0.5, -1, 0);
  fin.faces.push_back({0, 1, 8});  // a third face on edge (0,1)
  const MeshCheck nm = check_mesh(fin);
  EXPECT_EQ(nm.nonmanifold_edges, 1u);
  EXPECT_EQ(nm.boundary_edges, 2u);

  TriangleMesh degenerate = cube();
  degenerate.vertices.emplace_back(0.5, 0, 0);  // on edge 0-1: collinear face
  degenerate.faces.push_back({0, 1, 8});
  degenerate.faces.push_back({2, 2, 3});
  const MeshCheck d = check_mesh(degenerate);
  EXPECT_EQ(d.degenerate_faces, 2u);
  ASSERT_EQ(d.degenerate_face_ids.size(), 2u);
  EXPECT_EQ(d.degenerate_face_ids[0], 12);
  EXPECT_EQ(d.degenerate_face_ids[1], 13);
  EXPECT_EQ(degenerate.face_normal(12), Vec3::Zero());
}

TEST(Mesh, CheckCountsNonFiniteAndInvalid) {
  TriangleMesh m = cube();
  m.vertices[3].x() = NAN;
  m.faces.push_back({0, 1, 99});
  const MeshCheck c = check_mesh(m);
  EXPECT_EQ(c.nonfinite_vertices, 1u);
  EXPECT_EQ(c.invalid_faces, 1u);
}

TEST(Mesh, ValidateNamesTheCulprit) {
  TriangleMesh m = cube();
  m.faces[5][1] = 8;
  MESHNBV_EXPECT_ERROR_CONTAINS(m.validate("x.ply"), "face 5");
  TriangleMesh n = cube();
  n.vertices[2].y() = INFINITY;
  MESHNBV_EXPECT_ERROR_CONTAINS(n.validate("x.ply"), "vertex 2");
}

TEST(Mesh, FaceAttributesAreSizeChecked) {
  TriangleMesh m = cube();
  m.set_face_attribute("quality", std::vector<float>(12, 0.5f));
  ASSERT_NE(m.face_attribute("quality"), nullptr);
  EXPECT_FLOAT_EQ((*m.face_attribute("quality"))[11], 0.5f);
  EXPECT_EQ(m.face_attribute("missing"), nullptr);
  MESHNBV_EXPECT_ERROR_CONTAINS(m.set_face_attribute("q", std::vector<float>(3)), "3 values");
}

TEST(Mesh, AppendShiftsIndicesAndKeepsSharedAttributes) {
  TriangleMesh a = cube(), b = cube();
  a.set_face_attribute("quality", std::vector<float>(12, 1.0f));
  b.set_face_attribute("quality", std::vector<float>(12, 2.0f));
  b.set_face_attribute("other", std::vector<float>(12, 3.0f));
  a.append(b);
  EXPECT_EQ(a.num_vertices(), 16u);
  EXPECT_EQ(a.num_faces(), 24u);
  EXPECT_EQ(a.faces[12][0], 8);
  ASSERT_NE(a.face_attribute("quality"), nullptr);
  EXPECT_FLOAT_EQ((*a.face_attribute("quality"))[20], 2.0f);
  EXPECT_EQ(a.face_attribute("other"), nullptr);
  EXPECT_NO_THROW(a.validate());
}
