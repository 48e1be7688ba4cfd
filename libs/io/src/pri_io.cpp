// Reading a PRI back for a scene's own mesh (`meshnbv suggest --pri`).
#include "meshnbv/io/pri_io.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/results.h"

namespace meshnbv::io {

namespace {

// How far a coordinate stored as `type` may be from `x`: one step of the
// type's grid at x (a correctly rounded write is within half of it).
double storage_step(double x, PlyCoordinateType type) {
  const double a = std::abs(x);
  switch (type) {
    case PlyCoordinateType::Float32: {
      const float f = static_cast<float>(a);
      if (!std::isfinite(f)) return std::numeric_limits<double>::infinity();
      return double(std::nextafter(f, std::numeric_limits<float>::infinity())) - double(f);
    }
    case PlyCoordinateType::Float64:
      return std::nextafter(a, std::numeric_limits<double>::infinity()) - a;
    case PlyCoordinateType::Integer: return 1.0;
  }
  return 0.0;
}

std::string point_text(const Vec3& p) {
  std::ostringstream ss;
  ss.precision(17);
  ss << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return ss.str();
}

}  // namespace

std::vector<float> read_pri_for_mesh(const std::string& path, const TriangleMesh& mesh) {
  PlyFileInfo info;
  if (extension_lower(path) != ".ply")
    throw Error("the PRI mesh must be a PLY file (written by meshnbv pri)", path);
  const TriangleMesh file = read_ply_with_info(path, &info);
  const std::vector<float>* q = file.face_attribute("quality");
  if (!q) throw Error("no per-face 'quality' in the PRI mesh (write it with meshnbv pri)", path);
  const std::string different =
      "; the PRI was computed on a different mesh than the scene's (pass the mesh it was "
      "computed on with --mesh, or compute it again)";
  if (file.num_faces() != mesh.num_faces() || file.num_vertices() != mesh.num_vertices())
    throw Error("the PRI mesh has " + std::to_string(file.num_vertices()) + " vertices and " +
                    std::to_string(file.num_faces()) + " faces, the scene's mesh " +
                    std::to_string(mesh.num_vertices()) + " and " +
                    std::to_string(mesh.num_faces()) + different,
                path);
  for (std::size_t f = 0; f < mesh.num_faces(); ++f)
    if (file.faces[f] != mesh.faces[f])
      throw Error("face " + std::to_string(f) + " has other vertices in the PRI mesh than in the "
                  "scene's" + different,
                  path);
  const char* precision = info.coordinates == PlyCoordinateType::Float64   ? "double"
                          : info.coordinates == PlyCoordinateType::Float32 ? "float"
                                                                           : "integer";
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    const Vec3& a = mesh.vertices[v];
    const Vec3& b = file.vertices[v];
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(a[k] - b[k]) <= storage_step(a[k], info.coordinates)))
        throw Error("vertex " + std::to_string(v) + " is at " + point_text(b) +
                        " in the PRI mesh and at " + point_text(a) + " in the scene's, further "
                        "apart than the file's " + precision + " precision" + different,
                    path);
  }
  return *q;
}

PriPrevious read_pri_previous(const std::string& path) {
  if (extension_lower(path) != ".ply")
    throw Error("the previous PRI must be a PLY file written by meshnbv pri", path);
  PriPrevious out;
  PlyFileInfo info;
  out.mesh = read_ply_with_info(path, &info);
  read_pri_key_comments(info.comments, &out.result);
  const std::size_t F = out.mesh.num_faces();
  auto need = [&](const char* name) -> const std::vector<float>& {
    const std::vector<float>* a = out.mesh.face_attribute(name);
    if (!a)
      throw Error(std::string("no per-face '") + name + "' in the previous PRI (write it with meshnbv pri " +
                      "of this version)",
                  path);
    return *a;
  };
  auto count = [&](const char* name, std::vector<int>* to, double max) {
    const std::vector<float>& a = need(name);
    to->resize(F);
    for (std::size_t f = 0; f < F; ++f) {
      if (!(a[f] >= 0 && a[f] <= max && a[f] == std::floor(a[f])))
        throw Error("face " + std::to_string(f) + " has " + name + " " + std::to_string(a[f]) +
                        ", not a count meshnbv pri writes",
                    path);
      (*to)[f] = int(a[f]);
    }
  };
  PriResult& r = out.result;
  r.pri = need("quality");
  count("pri_views", &r.pri_views, 1e7);
  count("pri_pairs", &r.pri_pairs, 1e7);
  count("pri_samples", &r.pri_samples, 1e7);
  r.pri_texture = need("pri_texture");
  r.evidence_key.assign(F, 0);
  const int shift[3] = {0, 22, 43}, bits[3] = {22, 21, 21};
  for (int k = 0; k < 3; ++k) {
    std::vector<int> part;
    count(kPriKeyAttributes[k], &part, double((1 << bits[k]) - 1));
    for (std::size_t f = 0; f < F; ++f) r.evidence_key[f] |= std::uint64_t(part[f]) << shift[k];
  }
  if (out.mesh.face_attribute("pri_offset_signed")) {
    r.offset_signed = need("pri_offset_signed");
    r.offset_precision = need("pri_offset_precision");
    r.offset_pixel = need("pri_offset_pixel");
    r.offset_steady = need("pri_offset_steady");
  }
  r.status.resize(F);
  for (std::size_t f = 0; f < F; ++f)
    r.status[f] = !std::isnan(r.pri[f]) ? FaceStatus::Observed
                  : r.pri_views[f] >= 2 ? FaceStatus::Textureless
                                        : FaceStatus::Unobserved;
  out.mesh.face_attributes.clear();
  out.mesh.face_colors.clear();
  return out;
}

}  // namespace meshnbv::io
