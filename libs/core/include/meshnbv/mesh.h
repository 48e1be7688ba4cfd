// Triangle mesh of the core: positions, triangles, per-face attributes.
// Normals and areas are always computed from the geometry, never trusted
// from a file (SPEC section 1).
#pragma once

#include <limits>
#include <map>
#include <string>
#include <vector>

#include "meshnbv/types.h"

namespace meshnbv {

struct BoundingBox {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return !(min.x() <= max.x()); }
  void extend(const Vec3& p);
  Vec3 center() const { return 0.5 * (min + max); }
  Vec3 extent() const { return max - min; }
  double diagonal() const { return empty() ? 0.0 : (max - min).norm(); }
  // The 8 corners, x varying fastest.
  std::array<Vec3, 8> corners() const;
};

// Result of check_mesh(): counts of every defect a later stage cares about.
struct MeshCheck {
  std::size_t nonfinite_vertices = 0;    // NaN or inf coordinates
  std::size_t invalid_faces = 0;         // a vertex index out of range
  std::size_t degenerate_faces = 0;      // repeated index or (numerically) zero area
  std::size_t boundary_edges = 0;        // edges with exactly one incident face
  std::size_t nonmanifold_edges = 0;     // edges with three or more incident faces
  std::size_t unreferenced_vertices = 0;
  std::vector<int> degenerate_face_ids;  // at most 100, for messages
  bool closed() const { return boundary_edges == 0 && nonmanifold_edges == 0; }
};

class TriangleMesh {
 public:
  std::vector<Vec3> vertices;
  std::vector<Face> faces;
  // Per-face float attributes by name (e.g. "quality"), each faces.size() long.
  std::map<std::string, std::vector<float>> face_attributes;
  // Per-face colours: empty, or faces.size() long.
  std::vector<Rgb8> face_colors;

  std::size_t num_vertices() const { return vertices.size(); }
  std::size_t num_faces() const { return faces.size(); }
  bool empty() const { return faces.empty(); }

  // Unit normal by the right-hand rule (zero for a degenerate face).
  Vec3 face_normal(std::size_t f) const;
  double face_area(std::size_t f) const;
  Vec3 face_centroid(std::size_t f) const;
  std::vector<Vec3> face_normals() const;
  std::vector<double> face_areas() const;
  // Area-weighted mean of the incident face normals, normalised.
  std::vector<Vec3> vertex_normals() const;
  BoundingBox bounding_box() const;
  double total_area() const;

  // Sets (or replaces) a per-face attribute; throws Error if the size is wrong.
  void set_face_attribute(const std::string& name, std::vector<float> values);
  // nullptr when absent.
  const std::vector<float>* face_attribute(const std::string& name) const;

  // Throws Error naming the first face whose index is out of range or the
  // first vertex with a NaN/inf coordinate, and attribute arrays of the
  // wrong length. Readers call it before returning.
  void validate(const std::string& source = {}) const;

  // Appends another mesh (indices shifted); attributes present in both are kept.
  void append(const TriangleMesh& other);
};

// Counts defects; never throws. A face is degenerate when two indices repeat
// or its area is below `relative_area_epsilon` * diagonal^2.
MeshCheck check_mesh(const TriangleMesh& mesh, double relative_area_epsilon = 1e-14);

}  // namespace meshnbv
