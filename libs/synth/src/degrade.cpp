// Degraded reconstructions of a ground-truth mesh (OpenMesh for the
// decimation) and the per-face error against it (SurfaceDistance).
// OpenMesh's VectorT default constructor leaves its elements uninitialised by
// design; GCC reports that at the std::allocator line where OpenMesh's
// property arrays grow (a system header included before any push below), so
// this one warning is off for the whole file.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include "meshnbv/synth/degrade.h"

#include <algorithm>
#include <memory>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "meshnbv/error.h"
#include "meshnbv/surface_distance.h"
#include "meshnbv/synth/openmesh.h"

namespace meshnbv::synth {

// ---------------------------------------------------------------------------
// Parsing

namespace {

constexpr const char* kKinds = "noise, dent, bump, hole, decimate or field";

double default_strength(DegradationKind kind) {
  switch (kind) {
    case DegradationKind::Noise: return 0.005;
    case DegradationKind::Dent:
    case DegradationKind::Bump: return 0.02;
    case DegradationKind::Hole: return 0.0;
    case DegradationKind::Decimate: return 0.8;
    case DegradationKind::Field: return 0.002;
  }
  return 0.0;
}

double default_radius(DegradationKind kind) {
  if (kind == DegradationKind::Field) return 0.03;
  return kind == DegradationKind::Hole ? 0.08 : 0.15;
}

bool is_regional(DegradationKind kind) { return kind != DegradationKind::Decimate; }

// The whole of `field` as a finite number, or Error naming `what`.
double parse_number(const std::string& text, const std::string& field, const char* what) {
  if (field.empty())
    throw Error("degradation '" + text + "': empty " + what + " (expected a number)");
  const char* begin = field.c_str();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  if (end == begin || *end != '\0' || errno == ERANGE || !std::isfinite(value) ||
      std::isspace(static_cast<unsigned char>(field.front())))
    throw Error("degradation '" + text + "': " + what + " '" + field + "' is not a number");
  return value;
}

// Throws Error when `d` cannot be applied; `label` names it in messages.
void check_degradation(const Degradation& d, const std::string& label) {
  if (!std::isfinite(d.strength) || d.strength < 0)
    throw Error("degradation '" + label + "': strength must be a non-negative number, got " +
                format_option_value(d.strength));
  if (d.kind == DegradationKind::Decimate && !(d.strength < 1.0))
    throw Error("degradation '" + label +
                "': decimate strength is the fraction of faces removed and must be in [0, 1), "
                "got " + format_option_value(d.strength));
  if (d.kind != DegradationKind::Decimate && !(d.strength <= 1.0))
    throw Error("degradation '" + label +
                "': strength is a share of the bounding-box diagonal and must be in [0, 1], got " +
                format_option_value(d.strength));
  if (is_regional(d.kind) && (!std::isfinite(d.radius) || d.radius <= 0 || d.radius > 10))
    throw Error("degradation '" + label +
                "': radius must be a positive number, at most 10 (a share of the bounding-box "
                "diagonal), got " + format_option_value(d.radius));
}

}  // namespace

std::string degradation_name(DegradationKind kind) {
  switch (kind) {
    case DegradationKind::Noise: return "noise";
    case DegradationKind::Dent: return "dent";
    case DegradationKind::Bump: return "bump";
    case DegradationKind::Hole: return "hole";
    case DegradationKind::Decimate: return "decimate";
    case DegradationKind::Field: return "field";
  }
  return "unknown";
}

Degradation parse_degradation(const std::string& text) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t colon = text.find(':', start);
    fields.push_back(text.substr(start, colon == std::string::npos ? std::string::npos
                                                                     : colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  if (fields.size() > 3)
    throw Error("degradation '" + text +
                "': too many ':' fields (expected kind[:strength[:radius]])");

  Degradation d;
  const std::string& name = fields[0];
  bool known = false;
  for (DegradationKind kind : {DegradationKind::Noise, DegradationKind::Dent, DegradationKind::Bump,
                               DegradationKind::Hole, DegradationKind::Decimate,
                               DegradationKind::Field})
    if (name == degradation_name(kind)) {
      d.kind = kind;
      known = true;
    }
  if (!known)
    throw Error("unknown degradation '" + name + "' (expected " + kKinds + ")");

  d.strength = default_strength(d.kind);
  d.radius = default_radius(d.kind);
  if (fields.size() > 1) d.strength = parse_number(text, fields[1], "strength");
  if (fields.size() > 2) {
    if (!is_regional(d.kind))
      throw Error("degradation '" + text + "': decimate takes no radius");
    d.radius = parse_number(text, fields[2], "radius");
  }
  check_degradation(d, text);
  return d;
}

// ---------------------------------------------------------------------------
// Degradation

namespace {

// Random numbers from the bits of mt19937_64 alone (the standard
// distributions differ between library implementations).
constexpr double kTwoPi = 6.283185307179586476925286766559;

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  // Uniform in [0, 1).
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Standard normal (Box-Muller, one value per call).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
  }

 private:
  std::mt19937_64 engine_;
};

// A uniformly random point of the surface, preferring faces that do not
// point downwards (n.z > -0.5) so that the region can be seen from cameras
// above the ground; all faces when none qualifies.
Vec3 random_surface_point(const TriangleMesh& mesh, Random& random) {
  std::vector<double> cumulative;
  std::vector<std::size_t> ids;
  for (int pass = 0; pass < 2 && ids.empty(); ++pass) {
    double sum = 0;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      const double area = mesh.face_area(f);
      if (!(area > 0)) continue;
      if (pass == 0 && !(mesh.face_normal(f).z() > -0.5)) continue;
      sum += area;
      cumulative.push_back(sum);
      ids.push_back(f);
    }
  }
  if (ids.empty())
    throw Error("degrade: the mesh has no face of non-zero area to place a region on");
  const double pick = random.uniform() * cumulative.back();
  std::size_t k = static_cast<std::size_t>(
      std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin());
  k = std::min(k, ids.size() - 1);
  double u = random.uniform();
  double v = random.uniform();
  if (u + v > 1.0) {
    u = 1.0 - u;
    v = 1.0 - v;
  }
  const Face& face = mesh.faces[ids[k]];
  const Vec3& a = mesh.vertices[face[0]];
  return a + u * (mesh.vertices[face[1]] - a) + v * (mesh.vertices[face[2]] - a);
}

struct PositionHash {
  std::size_t operator()(const Vec3& p) const {
    std::size_t h = 0;
    for (int i = 0; i < 3; ++i) {
      double c = p[i] == 0.0 ? 0.0 : p[i];  // -0 and +0 alike
      std::uint64_t bits;
      std::memcpy(&bits, &c, sizeof bits);
      h ^= std::hash<std::uint64_t>()(bits) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    }
    return h;
  }
};

// Vertices at exactly the same position (unwelded copies, e.g. touching
// components or per-face vertices) form one group and are displaced
// together, so a regional degradation never opens a crack between them.
// group[v] is the group of vertex v; groups are numbered in vertex order.
// normals[g] is the area-weighted normal of all faces around group g.
struct VertexGroups {
  std::vector<int> group;
  std::vector<Vec3> normals;
};

VertexGroups group_vertices(const TriangleMesh& mesh) {
  VertexGroups out;
  out.group.resize(mesh.vertices.size());
  std::unordered_map<Vec3, int, PositionHash> first;
  first.reserve(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    auto [it, inserted] = first.emplace(mesh.vertices[v], static_cast<int>(out.normals.size()));
    if (inserted) out.normals.push_back(Vec3::Zero());
    out.group[v] = it->second;
  }
  for (const Face& face : mesh.faces) {
    const Vec3& a = mesh.vertices[face[0]];
    const Vec3 weighted = (mesh.vertices[face[1]] - a).cross(mesh.vertices[face[2]] - a);
    // A face that touches one group twice (degenerate) adds its normal once per corner; harmless.
    for (int k = 0; k < 3; ++k) out.normals[out.group[face[k]]] += weighted;
  }
  for (Vec3& n : out.normals) {
    const double len = n.norm();
    n = len > 0 ? Vec3(n / len) : Vec3::Zero();
  }
  return out;
}

// Smooth falloff: 1 at the centre, 0 (with zero slope) at the border.
double falloff(double distance, double radius) {
  const double t = distance / radius;
  const double s = 1.0 - t * t;
  return s > 0 ? s * s : 0.0;
}

// Noise, dent and bump: moves the vertices strictly inside the ball.
void displace_region(TriangleMesh& mesh, const Degradation& d, const Vec3& center, double radius,
                     double diagonal, Random& random) {
  const VertexGroups groups = group_vertices(mesh);
  const std::size_t n_groups = groups.normals.size();
  std::vector<char> done(n_groups, 0);
  std::vector<Vec3> offset(n_groups, Vec3::Zero());
  const double amplitude = d.strength * diagonal;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const int g = groups.group[v];
    if (!done[g]) {
      done[g] = 1;
      const double w = falloff((mesh.vertices[v] - center).norm(), radius);
      if (w > 0) {
        double along = 0;
        switch (d.kind) {
          case DegradationKind::Noise: along = random.normal() * amplitude * w; break;
          case DegradationKind::Dent: along = -amplitude * w; break;
          case DegradationKind::Bump: along = amplitude * w; break;
          default: break;
        }
        offset[g] = along * groups.normals[g];
      }
    }
    if (offset[g] != Vec3::Zero()) mesh.vertices[v] += offset[g];
  }
}

// Field: a smooth displacement along the normals over the whole mesh, a sum
// of Gaussian bumps of random sign and size (standard deviations in
// [0.5, 1.5] x radius, about one bump per radius^2 of the bounding box's
// surface), scaled so that its largest magnitude is the amplitude, plus
// Gaussian noise of a quarter of the amplitude per vertex.
void displace_field(TriangleMesh& mesh, const Degradation& d, double diagonal, Random& random) {
  const VertexGroups groups = group_vertices(mesh);
  const std::size_t n_groups = groups.normals.size();
  std::vector<Vec3> position(n_groups);
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) position[groups.group[v]] = mesh.vertices[v];
  const double radius = d.radius * diagonal;
  const BoundingBox box = mesh.bounding_box();
  const Vec3 e = box.max - box.min;
  const double area = 2 * (e.x() * e.y() + e.y() * e.z() + e.z() * e.x());
  const int bumps = std::clamp(int(std::ceil(area / (radius * radius))), 4, 4000);
  std::vector<double> field(n_groups, 0.0);
  for (int b = 0; b < bumps; ++b) {
    const Vec3 centre = random_surface_point(mesh, random);
    const double sigma = radius * (0.5 + random.uniform());
    const double sign = random.uniform() < 0.5 ? -1.0 : 1.0;
    const double inv = 1.0 / (2 * sigma * sigma);
    for (std::size_t g = 0; g < n_groups; ++g) {
      const double r2 = (position[g] - centre).squaredNorm();
      if (r2 < 16 * sigma * sigma) field[g] += sign * std::exp(-r2 * inv);
    }
  }
  double peak = 0;
  for (double x : field) peak = std::max(peak, std::abs(x));
  const double amplitude = d.strength * diagonal;
  std::vector<Vec3> offset(n_groups);
  for (std::size_t g = 0; g < n_groups; ++g)
    offset[g] = (amplitude * (peak > 0 ? field[g] / peak : 0.0) + 0.25 * amplitude * random.normal()) *
                groups.normals[g];
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) mesh.vertices[v] += offset[groups.group[v]];
}

// Keeps the faces with keep[f], drops the vertices no longer referenced and
// keeps face attributes and colours aligned.
TriangleMesh keep_faces(const TriangleMesh& mesh, const std::vector<char>& keep) {
  TriangleMesh out;
  std::vector<int> remap(mesh.vertices.size(), -1);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (!keep[f]) continue;
    Face face = mesh.faces[f];
    for (int& i : face) {
      if (remap[i] < 0) {
        remap[i] = static_cast<int>(out.vertices.size());
        out.vertices.push_back(mesh.vertices[i]);
      }
      i = remap[i];
    }
    out.faces.push_back(face);
  }
  for (const auto& [name, values] : mesh.face_attributes) {
    std::vector<float> kept;
    kept.reserve(out.faces.size());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      if (keep[f]) kept.push_back(values[f]);
    out.face_attributes[name] = std::move(kept);
  }
  if (mesh.face_colors.size() == mesh.faces.size())
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      if (keep[f]) out.face_colors.push_back(mesh.face_colors[f]);
  return out;
}

TriangleMesh cut_hole(const TriangleMesh& mesh, const Vec3& center, double radius) {
  std::vector<char> keep(mesh.faces.size(), 1);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    if ((mesh.face_centroid(f) - center).squaredNorm() < radius * radius) keep[f] = 0;
  return keep_faces(mesh, keep);
}

}  // namespace

namespace {
// OpenMesh reports rejected faces on its global error stream; the rejects
// are expected (to_openmesh hands them back), so the stream is muted meanwhile.
class MuteOpenMeshErrors {
 public:
  MuteOpenMeshErrors() : was_enabled_(::omerr().is_enabled()) {
    if (was_enabled_) ::omerr().disable();
  }
  ~MuteOpenMeshErrors() {
    if (was_enabled_) ::omerr().enable();
  }
  MuteOpenMeshErrors(const MuteOpenMeshErrors&) = delete;
  MuteOpenMeshErrors& operator=(const MuteOpenMeshErrors&) = delete;

 private:
  bool was_enabled_;
};
}  // namespace

std::vector<int> to_openmesh(const TriangleMesh& mesh, OmMesh& om, std::vector<std::size_t>& rejected) {
  rejected.clear();
  om.request_vertex_status();
  om.request_edge_status();
  om.request_face_status();
  om.request_face_normals();
  std::vector<OmMesh::VertexHandle> handles;
  handles.reserve(mesh.vertices.size());
  for (const Vec3& p : mesh.vertices) handles.push_back(om.add_vertex(OmMesh::Point(p.x(), p.y(), p.z())));
  std::vector<int> om_face(mesh.faces.size(), -1);
  {
    MuteOpenMeshErrors mute;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      const Face& face = mesh.faces[f];
      OmMesh::FaceHandle fh;
      if (face[0] != face[1] && face[1] != face[2] && face[0] != face[2])
        fh = om.add_face(handles[std::size_t(face[0])], handles[std::size_t(face[1])], handles[std::size_t(face[2])]);
      if (fh.is_valid()) om_face[f] = fh.idx();
      else rejected.push_back(f);
    }
  }
  for (std::size_t f : rejected)
    for (int i : mesh.faces[f]) om.status(handles[std::size_t(i)]).set_locked(true);
  om.update_face_normals();
  return om_face;
}

namespace {

// Quadric edge-collapse decimation (OpenMesh) to (1 - strength) of the faces.
//
// A face OpenMesh rejects (to_openmesh) is counted in `rejected`, keeps its
// vertices where they are, and is returned unchanged alongside the
// decimated rest.
// Separate components (e.g. a union of closed boxes) are fine.
//
// Per-face attributes and colours are dropped (none is kept): the faces are
// new, and no attribute of the input face set describes them. When nothing
// is to be removed (strength 0) the mesh is returned unchanged.
TriangleMesh decimate(const TriangleMesh& mesh, double strength, std::size_t& rejected) {
  rejected = 0;
  TriangleMesh out;
  if (mesh.faces.empty()) return out;
  const auto target_total = static_cast<std::size_t>(
      std::llround((1.0 - strength) * static_cast<double>(mesh.faces.size())));

  OmMesh om;
  std::vector<std::size_t> rejected_faces;
  to_openmesh(mesh, om, rejected_faces);
  rejected = rejected_faces.size();

  const std::size_t accepted = om.n_faces();
  const std::size_t target = target_total > rejected ? target_total - rejected : 0;
  if (target >= accepted) return mesh;  // nothing to remove: unchanged, attributes kept
  {
    OpenMesh::Decimater::DecimaterT<OmMesh> decimater(om);
    OpenMesh::Decimater::ModQuadricT<OmMesh>::Handle quadric;     // priority: quadric error
    OpenMesh::Decimater::ModNormalFlippingT<OmMesh>::Handle no_flips;  // veto fold-overs
    decimater.add(quadric);
    decimater.add(no_flips);
    decimater.module(quadric).unset_max_err();
    if (!decimater.initialize()) throw Error("decimate: OpenMesh decimater failed to initialise");
    decimater.decimate_to_faces(0, target);
  }

  // No garbage_collection(): it reorders elements. Handles of vertices still
  // alive are the input vertex indices, which the rejected faces use.
  std::vector<int> remap(mesh.vertices.size(), -1);
  auto index_of = [&](int v) {
    if (remap[v] < 0) {
      remap[v] = static_cast<int>(out.vertices.size());
      const OmMesh::Point& p = om.point(OmMesh::VertexHandle(v));
      out.vertices.emplace_back(p[0], p[1], p[2]);
    }
    return remap[v];
  };
  for (const auto fh : om.faces()) {
    if (om.status(fh).deleted()) continue;
    Face face{};
    int k = 0;
    for (const auto vh : om.fv_range(fh)) face[k++] = index_of(vh.idx());
    out.faces.push_back(face);
  }
  for (std::size_t f : rejected_faces) {
    Face face = mesh.faces[f];
    for (int& i : face) i = index_of(i);
    out.faces.push_back(face);
  }
  return out;
}

}  // namespace

DegradeResult degrade(const TriangleMesh& truth, const std::vector<Degradation>& degradations,
                      std::uint64_t seed) {
  truth.validate("degrade: ground truth");
  if (truth.faces.empty()) throw Error("degrade: the ground-truth mesh has no faces");
  const double diagonal = truth.bounding_box().diagonal();
  if (!(diagonal > 0)) throw Error("degrade: the ground-truth mesh has a zero-size bounding box");

  DegradeResult result;
  result.mesh = truth;
  Random random(seed);
  for (std::size_t i = 0; i < degradations.size(); ++i) {
    const Degradation& d = degradations[i];
    check_degradation(d, degradation_name(d.kind) + " (#" + std::to_string(i + 1) + ")");
    if (d.kind == DegradationKind::Decimate) {
      std::size_t rejected = 0;  // not reported: DegradeResult has no field for it
      result.mesh = decimate(result.mesh, d.strength, rejected);
      continue;
    }
    if (d.kind == DegradationKind::Field) {
      displace_field(result.mesh, d, diagonal, random);
      continue;
    }
    const Vec3 center =
        d.center.allFinite() ? d.center : random_surface_point(result.mesh, random);
    result.region_centers.push_back(center);
    const double radius = d.radius * diagonal;
    if (d.kind == DegradationKind::Hole)
      result.mesh = cut_hole(result.mesh, center, radius);
    else
      displace_region(result.mesh, d, center, radius, diagonal, random);
  }
  return result;
}

// ---------------------------------------------------------------------------
// Error against the true surface

std::vector<float> face_distance_to_surface(const TriangleMesh& mesh, const TriangleMesh& truth,
                                            int samples_per_side) {
  if (samples_per_side < 0)
    throw Error("face_distance_to_surface: samples_per_side must be >= 0, got " +
                std::to_string(samples_per_side));
  mesh.validate("face_distance_to_surface: mesh");
  truth.validate("face_distance_to_surface: ground truth");
  if (truth.faces.empty())
    throw Error("face_distance_to_surface: the ground-truth mesh has no faces");
  std::unique_ptr<SurfaceDistance> surface;
  try {
    surface = std::make_unique<SurfaceDistance>(truth);
  } catch (const Error&) {
    throw Error("face_distance_to_surface: every ground-truth face is degenerate");
  }

  // Barycentric lattice: (i, j, r-i-j) / r, or the centroid when r = 0.
  const int r = samples_per_side;
  std::vector<Vec3> weights;
  if (r == 0) {
    weights.emplace_back(1.0 / 3, 1.0 / 3, 1.0 / 3);
  } else {
    for (int i = 0; i <= r; ++i)
      for (int j = 0; j <= r - i; ++j)
        weights.emplace_back(double(i) / r, double(j) / r, double(r - i - j) / r);
  }

  std::vector<float> out(mesh.faces.size(), 0.0f);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.faces.size(), 64),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t f = range.begin(); f != range.end(); ++f) {
                        const Face& face = mesh.faces[f];
                        const Vec3& a = mesh.vertices[face[0]];
                        const Vec3& b = mesh.vertices[face[1]];
                        const Vec3& c = mesh.vertices[face[2]];
                        double sum = 0;
                        for (const Vec3& w : weights) {
                          const Vec3 p = w[0] * a + w[1] * b + w[2] * c;
                          sum += surface->distance(p);
                        }
                        out[f] = static_cast<float>(sum / static_cast<double>(weights.size()));
                      }
                    });
  return out;
}

}  // namespace meshnbv::synth
