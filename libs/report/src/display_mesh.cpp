// The report's display mesh: OpenMesh quadric decimation above a face
// budget, with each removed face handed to the neighbour that covers it.
// OpenMesh's VectorT default constructor leaves its elements uninitialised by
// design (see libs/synth/src/degrade.cpp): this one warning is off here.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include "meshnbv/display_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "meshnbv/error.h"
#include "meshnbv/synth/openmesh.h"


namespace meshnbv {
namespace {

using synth::OmMesh;

// A binary module that vetoes nothing and records, for the two faces each
// collapse v0 -> v1 removes, the face that takes over their area: the
// neighbour across the edge at v0 (its corner v0 moves to v1, stretching it
// over the removed face), else the one across the edge at v1.
template <typename MeshT>
class ModTakeOverT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModTakeOverT, MeshT, TakeOver);

  explicit ModTakeOverT(MeshT& mesh) : Base(mesh, true) {}

  std::vector<int>* parent = nullptr;  // per face: the face that took it over, or -1

  void preprocess_collapse(const CollapseInfo& ci) override {
    const Mesh& m = Base::mesh();
    auto take_over = [&](typename Mesh::FaceHandle removed, typename Mesh::HalfedgeHandle at_v0,
                         typename Mesh::HalfedgeHandle at_v1) {
      if (!removed.is_valid()) return;
      typename Mesh::FaceHandle heir = at_v0.is_valid() ? m.face_handle(at_v0) : typename Mesh::FaceHandle();
      if (!heir.is_valid() && at_v1.is_valid()) heir = m.face_handle(at_v1);
      (*parent)[std::size_t(removed.idx())] = heir.is_valid() ? heir.idx() : -1;
    };
    take_over(ci.fl, ci.v0vl, ci.vlv1);
    take_over(ci.fr, ci.vrv0, ci.v1vr);
  }
};

void fill_members(DisplayMesh* d) {
  const std::size_t n = d->mesh.faces.size();
  d->member_begin.assign(n + 1, 0);
  for (int f : d->display_face) ++d->member_begin[std::size_t(f) + 1];
  for (std::size_t k = 0; k < n; ++k) d->member_begin[k + 1] += d->member_begin[k];
  d->members.assign(d->display_face.size(), 0);
  std::vector<std::uint32_t> next(d->member_begin.begin(), d->member_begin.end() - 1);
  for (std::size_t f = 0; f < d->display_face.size(); ++f)
    d->members[next[std::size_t(d->display_face[f])]++] = std::uint32_t(f);
}

}  // namespace

DisplayMesh display_mesh(const TriangleMesh& mesh, std::size_t max_faces) {
  if (max_faces == 0) throw Error("display mesh: the face budget must be at least 1");
  DisplayMesh d;
  const std::size_t n = mesh.faces.size();
  if (n <= max_faces) {
    d.mesh.vertices = mesh.vertices;
    d.mesh.faces = mesh.faces;
    d.display_face.resize(n);
    for (std::size_t f = 0; f < n; ++f) d.display_face[f] = int(f);
    d.source_vertex.resize(mesh.vertices.size());
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) d.source_vertex[v] = int(v);
    fill_members(&d);
    return d;
  }

  // Faces OpenMesh rejects stay as they are: their vertices do not move.
  OmMesh om;
  std::vector<std::size_t> rejected;
  const std::vector<int> om_face = synth::to_openmesh(mesh, om, rejected);

  std::vector<int> parent(om.n_faces(), -1);
  const std::size_t target = max_faces > rejected.size() ? max_faces - rejected.size() : 0;
  {
    OpenMesh::Decimater::DecimaterT<OmMesh> decimater(om);
    OpenMesh::Decimater::ModQuadricT<OmMesh>::Handle quadric;          // priority: quadric error
    OpenMesh::Decimater::ModNormalFlippingT<OmMesh>::Handle no_flips;  // veto fold-overs
    ModTakeOverT<OmMesh>::Handle take_over;
    decimater.add(quadric);
    decimater.add(no_flips);
    decimater.add(take_over);
    decimater.module(quadric).unset_max_err();
    decimater.module(take_over).parent = &parent;
    if (!decimater.initialize()) throw Error("display mesh: OpenMesh decimater failed to initialise");
    decimater.decimate_to_faces(0, target);
  }

  // Display faces: the OpenMesh faces still there, then the rejected ones.
  std::vector<int> display_of_om(om.n_faces(), -1);
  std::vector<int> vertex_index(mesh.vertices.size(), -1);
  auto index_of = [&](int v) {
    if (vertex_index[std::size_t(v)] < 0) {
      vertex_index[std::size_t(v)] = int(d.mesh.vertices.size());
      const OmMesh::Point& p = om.point(OmMesh::VertexHandle(v));
      d.mesh.vertices.emplace_back(p[0], p[1], p[2]);
      d.source_vertex.push_back(v);  // to_openmesh adds the vertices in order
    }
    return vertex_index[std::size_t(v)];
  };
  for (const auto fh : om.faces()) {
    if (om.status(fh).deleted()) continue;
    Face face{};
    int k = 0;
    for (const auto vh : om.fv_range(fh)) face[std::size_t(k++)] = index_of(vh.idx());
    display_of_om[std::size_t(fh.idx())] = int(d.mesh.faces.size());
    d.mesh.faces.push_back(face);
  }
  d.display_face.assign(n, -1);
  for (std::size_t f : rejected) {
    Face face = mesh.faces[f];
    for (int& i : face) i = index_of(i);
    d.display_face[f] = int(d.mesh.faces.size());
    d.mesh.faces.push_back(face);
  }
  if (d.mesh.faces.empty()) throw Error("display mesh: the decimation left no face");

  // Each removed face follows its heirs to a face still there (memoised:
  // every chain is walked once).
  std::vector<int> resolved(om.n_faces(), -2);  // -2: not yet
  auto resolve = [&](int start) {
    std::vector<int> chain;
    int f = start, found = -1;
    while (f >= 0) {
      if (resolved[std::size_t(f)] != -2) { found = resolved[std::size_t(f)]; break; }
      if (display_of_om[std::size_t(f)] >= 0) { found = display_of_om[std::size_t(f)]; break; }
      chain.push_back(f);
      if (chain.size() > om.n_faces()) break;  // a cycle cannot occur; guard anyway
      f = parent[std::size_t(f)];
    }
    for (int c : chain) resolved[std::size_t(c)] = found;
    return found;
  };
  std::vector<std::size_t> orphans;  // removed with no neighbour left (isolated pieces)
  for (std::size_t f = 0; f < n; ++f) {
    if (om_face[f] < 0) continue;
    const int target_face = resolve(om_face[f]);
    if (target_face >= 0) d.display_face[f] = target_face;
    else orphans.push_back(f);
  }
  // A piece collapsed away entirely: its faces go to the display face whose
  // centroid is nearest (rare, so a plain scan).
  if (!orphans.empty()) {
    std::vector<Vec3> centroids(d.mesh.faces.size());
    for (std::size_t k = 0; k < centroids.size(); ++k) centroids[k] = d.mesh.face_centroid(k);
    for (std::size_t f : orphans) {
      const Vec3 c = mesh.face_centroid(f);
      std::size_t best = 0;
      for (std::size_t k = 1; k < centroids.size(); ++k)
        if ((centroids[k] - c).squaredNorm() < (centroids[best] - c).squaredNorm()) best = k;
      d.display_face[f] = int(best);
    }
  }
  d.decimated = true;
  fill_members(&d);
  return d;
}

CoarseDisplayMesh coarse_display_mesh(const DisplayMesh& display, std::size_t max_faces) {
  if (max_faces == 0) throw Error("interaction mesh: the face budget must be at least 1");
  DisplayMesh step = display_mesh(display.mesh, max_faces);  // display faces -> coarse faces
  CoarseDisplayMesh out;
  out.coarse_face = std::move(step.display_face);
  out.mesh.mesh = std::move(step.mesh);
  out.mesh.source_vertex = std::move(step.source_vertex);
  out.mesh.decimated = display.decimated || step.decimated;
  out.mesh.display_face.resize(display.display_face.size());
  for (std::size_t f = 0; f < display.display_face.size(); ++f)
    out.mesh.display_face[f] = out.coarse_face[std::size_t(display.display_face[f])];
  fill_members(&out.mesh);
  return out;
}

DisplayPri display_pri(const DisplayMesh& display, const TriangleMesh& original, const PriResult& pri,
                       double low_texture_below) {
  const std::size_t n = original.faces.size();
  if (pri.pri.size() != n || pri.pri_views.size() != n || pri.pri_texture.size() != n ||
      display.display_face.size() != n)
    throw Error("display mesh: " + std::to_string(n) + " faces but PRI of " + std::to_string(pri.pri.size()) +
                " and a map of " + std::to_string(display.display_face.size()));
  auto flags_of = [&](std::size_t f) {
    if (std::isnan(pri.pri[f])) return std::uint8_t(kDisplayUnobserved);
    std::uint8_t flags = 0;
    if (pri.pri_views[f] == 2) flags |= kDisplayTwoViews;
    // NaN texture (no samples read) counts as low, as in pri_evidence.
    if (!(pri.pri_texture[f] >= low_texture_below)) flags |= kDisplayLowTexture;
    return flags;
  };
  const std::size_t m = display.mesh.faces.size();
  DisplayPri out;
  out.pri.assign(m, std::numeric_limits<float>::quiet_NaN());
  out.flags.assign(m, 0);
  if (!display.decimated) {
    for (std::size_t f = 0; f < n; ++f) {
      out.pri[f] = pri.pri[f];
      out.flags[f] = flags_of(f);
    }
    return out;
  }
  for (std::size_t d = 0; d < m; ++d) {
    double area = 0, observed = 0, sum = 0, two_views = 0, low_texture = 0;
    for (std::uint32_t k = display.member_begin[d]; k < display.member_begin[d + 1]; ++k) {
      const std::size_t f = display.members[k];
      // A zero-area face still counts a little, so that a display face made
      // of degenerate faces only is not left without a value.
      const double a = std::max(original.face_area(f), 1e-300);
      area += a;
      const std::uint8_t flags = flags_of(f);
      if (flags & kDisplayUnobserved) continue;
      observed += a;
      sum += a * pri.pri[f];
      if (flags & kDisplayTwoViews) two_views += a;
      if (flags & kDisplayLowTexture) low_texture += a;
    }
    if (!(observed >= 0.5 * area) || observed <= 0) {
      out.flags[d] = kDisplayUnobserved;
      continue;
    }
    out.pri[d] = float(sum / observed);
    if (two_views > 0.5 * observed) out.flags[d] |= kDisplayTwoViews;
    if (low_texture > 0.5 * observed) out.flags[d] |= kDisplayLowTexture;
  }
  return out;
}

}  // namespace meshnbv
