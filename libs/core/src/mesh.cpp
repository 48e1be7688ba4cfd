#include "meshnbv/mesh.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "meshnbv/error.h"

namespace meshnbv {

void BoundingBox::extend(const Vec3& p) {
  min = min.cwiseMin(p);
  max = max.cwiseMax(p);
}

std::array<Vec3, 8> BoundingBox::corners() const {
  std::array<Vec3, 8> out;
  for (int i = 0; i < 8; ++i)
    out[i] = Vec3((i & 1) ? max.x() : min.x(), (i & 2) ? max.y() : min.y(),
                  (i & 4) ? max.z() : min.z());
  return out;
}

namespace {
Vec3 face_cross(const TriangleMesh& m, std::size_t f) {
  const Face& face = m.faces[f];
  const Vec3& a = m.vertices[face[0]];
  return (m.vertices[face[1]] - a).cross(m.vertices[face[2]] - a);
}
}  // namespace

Vec3 TriangleMesh::face_normal(std::size_t f) const {
  Vec3 n = face_cross(*this, f);
  double len = n.norm();
  return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

double TriangleMesh::face_area(std::size_t f) const { return 0.5 * face_cross(*this, f).norm(); }

Vec3 TriangleMesh::face_centroid(std::size_t f) const {
  const Face& face = faces[f];
  return (vertices[face[0]] + vertices[face[1]] + vertices[face[2]]) / 3.0;
}

std::vector<Vec3> TriangleMesh::face_normals() const {
  std::vector<Vec3> out(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) out[f] = face_normal(f);
  return out;
}

std::vector<double> TriangleMesh::face_areas() const {
  std::vector<double> out(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) out[f] = face_area(f);
  return out;
}

std::vector<Vec3> TriangleMesh::vertex_normals() const {
  std::vector<Vec3> out(vertices.size(), Vec3::Zero());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    Vec3 weighted = face_cross(*this, f);  // |cross| = 2 * area: area weighting
    for (int k = 0; k < 3; ++k) out[faces[f][k]] += weighted;
  }
  for (auto& n : out) {
    double len = n.norm();
    n = len > 0 ? Vec3(n / len) : Vec3::Zero();
  }
  return out;
}

BoundingBox TriangleMesh::bounding_box() const {
  BoundingBox box;
  for (const auto& v : vertices)
    if (v.allFinite()) box.extend(v);
  return box;
}

double TriangleMesh::total_area() const {
  double sum = 0;
  for (std::size_t f = 0; f < faces.size(); ++f) sum += face_area(f);
  return sum;
}

void TriangleMesh::set_face_attribute(const std::string& name, std::vector<float> values) {
  if (values.size() != faces.size())
    throw Error("face attribute '" + name + "' has " + std::to_string(values.size()) +
                " values for " + std::to_string(faces.size()) + " faces");
  face_attributes[name] = std::move(values);
}

const std::vector<float>* TriangleMesh::face_attribute(const std::string& name) const {
  auto it = face_attributes.find(name);
  return it == face_attributes.end() ? nullptr : &it->second;
}

void TriangleMesh::validate(const std::string& source) const {
  for (std::size_t v = 0; v < vertices.size(); ++v)
    if (!vertices[v].allFinite())
      throw Error("non-finite (NaN or inf) coordinate", source, -1, "vertex " + std::to_string(v));
  const long long n = static_cast<long long>(vertices.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      if (faces[f][k] < 0 || faces[f][k] >= n)
        throw Error("vertex index " + std::to_string(faces[f][k]) + " out of range [0, " +
                        std::to_string(n) + ")",
                    source, -1, "face " + std::to_string(f));
  for (const auto& [name, values] : face_attributes)
    if (values.size() != faces.size())
      throw Error("face attribute '" + name + "' has " + std::to_string(values.size()) +
                      " values for " + std::to_string(faces.size()) + " faces",
                  source);
  if (!face_colors.empty() && face_colors.size() != faces.size())
    throw Error("face colours: " + std::to_string(face_colors.size()) + " for " +
                    std::to_string(faces.size()) + " faces",
                source);
}

void TriangleMesh::append(const TriangleMesh& other) {
  const std::size_t old_faces = faces.size();
  const int offset = static_cast<int>(vertices.size());
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  for (Face f : other.faces) {
    for (int& i : f) i += offset;
    faces.push_back(f);
  }
  // Attributes survive only when both sides have them.
  for (auto it = face_attributes.begin(); it != face_attributes.end();) {
    const auto* theirs = other.face_attribute(it->first);
    if (!theirs || it->second.size() != old_faces) {
      it = face_attributes.erase(it);
    } else {
      it->second.insert(it->second.end(), theirs->begin(), theirs->end());
      ++it;
    }
  }
  if (old_faces == 0 && face_attributes.empty()) face_attributes = other.face_attributes;
  if (face_colors.size() == old_faces && other.face_colors.size() == other.faces.size() &&
      (old_faces > 0 || !other.face_colors.empty()))
    face_colors.insert(face_colors.end(), other.face_colors.begin(), other.face_colors.end());
  else
    face_colors.clear();
}

MeshCheck check_mesh(const TriangleMesh& mesh, double relative_area_epsilon) {
  MeshCheck out;
  for (const auto& v : mesh.vertices)
    if (!v.allFinite()) ++out.nonfinite_vertices;
  const double diag = mesh.bounding_box().diagonal();
  const double min_area = relative_area_epsilon * diag * diag;
  const long long n = static_cast<long long>(mesh.vertices.size());
  std::vector<char> referenced(mesh.vertices.size(), 0);
  // Undirected edge -> number of incident faces. Counted directly rather than
  // through OpenMesh because a half-edge structure cannot hold the
  // non-manifold edges we want to count.
  std::unordered_map<std::uint64_t, int> edge_faces;
  edge_faces.reserve(mesh.faces.size() * 2);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& face = mesh.faces[f];
    bool valid = true;
    for (int k = 0; k < 3; ++k) valid = valid && face[k] >= 0 && face[k] < n;
    if (!valid) {
      ++out.invalid_faces;
      continue;
    }
    if (face[0] == face[1] || face[1] == face[2] || face[0] == face[2]) {
      ++out.degenerate_faces;
      if (out.degenerate_face_ids.size() < 100) out.degenerate_face_ids.push_back(int(f));
      continue;
    }
    for (int k = 0; k < 3; ++k) referenced[face[k]] = 1;
    const double area = mesh.face_area(f);
    if (!(area > min_area)) {
      ++out.degenerate_faces;
      if (out.degenerate_face_ids.size() < 100) out.degenerate_face_ids.push_back(int(f));
    }
    for (int k = 0; k < 3; ++k) {
      std::uint64_t a = std::uint32_t(face[k]), b = std::uint32_t(face[(k + 1) % 3]);
      if (a > b) std::swap(a, b);
      ++edge_faces[(a << 32) | b];
    }
  }
  for (const auto& [edge, count] : edge_faces) {
    if (count == 1) ++out.boundary_edges;
    if (count >= 3) ++out.nonmanifold_edges;
  }
  out.unreferenced_vertices =
      static_cast<std::size_t>(std::count(referenced.begin(), referenced.end(), 0));
  return out;
}

}  // namespace meshnbv
