#include "meshnbv/raycaster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <embree3/rtcore.h>

#include "meshnbv/error.h"

namespace meshnbv {

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  // Offset-relative double vertices and the faces, for closest-point queries.
  std::vector<Vec3> vertices;
  std::vector<Face> faces;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {
// Closest point to p on the segment [a, b].
Vec3 closest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0)) return a;
  const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return a + t * ab;
}

// Closest point to p on the triangle (a, b, c), by the Voronoi regions of
// its vertices, edges and face (Ericson, Real-Time Collision Detection,
// 5.1.5); degenerate triangles fall back to their three edges.
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  if (!(ab.cross(ac).squaredNorm() > 0)) {
    const Vec3 q[3] = {closest_on_segment(p, a, b), closest_on_segment(p, b, c),
                       closest_on_segment(p, c, a)};
    int best = 0;
    for (int k = 1; k < 3; ++k)
      if ((q[k] - p).squaredNorm() < (q[best] - p).squaredNorm()) best = k;
    return q[best];
  }
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

struct PointQueryState {
  const RayCaster::Impl* impl;
  Vec3 query;  // offset-relative
  Vec3 best = Vec3::Zero();
  double best_d2 = std::numeric_limits<double>::infinity();
  int face = -1;
};

bool point_query_callback(RTCPointQueryFunctionArguments* args) {
  auto* state = static_cast<PointQueryState*>(args->userPtr);
  const Face& f = state->impl->faces[args->primID];
  const auto& v = state->impl->vertices;
  const Vec3 q = closest_on_triangle(state->query, v[std::size_t(f[0])], v[std::size_t(f[1])],
                                     v[std::size_t(f[2])]);
  const double d2 = (q - state->query).squaredNorm();
  if (d2 < state->best_d2) {
    state->best_d2 = d2;
    state->best = q;
    state->face = int(args->primID);
    // Shrink the search radius (float, rounded up so the exact best stays inside).
    args->query->radius = std::nextafter(float(std::sqrt(d2)), std::numeric_limits<float>::infinity());
    return true;
  }
  return false;
}

void check_device(RTCDevice device, const char* what) {
  const RTCError err = rtcGetDeviceError(device);
  if (err != RTC_ERROR_NONE)
    throw Error(std::string("Embree error ") + std::to_string(int(err)) + " in " + what);
}

void fill_ray(RTCRay* ray, const Vec3& o, const Vec3& d, double t_min, double t_max) {
  ray->org_x = float(o.x());
  ray->org_y = float(o.y());
  ray->org_z = float(o.z());
  ray->dir_x = float(d.x());
  ray->dir_y = float(d.y());
  ray->dir_z = float(d.z());
  ray->tnear = float(t_min);
  ray->tfar = std::isfinite(t_max) ? float(t_max) : std::numeric_limits<float>::infinity();
  ray->time = 0.0f;
  ray->mask = 0xFFFFFFFFu;  // Debian's Embree has ray masks on: 0 would hit nothing
  ray->id = 0;
  ray->flags = 0;
}
}  // namespace

RayCaster::RayCaster(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  mesh.validate();
  const BoundingBox box = mesh.bounding_box();
  offset_ = box.empty() ? Vec3::Zero() : box.center();
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw Error("cannot create an Embree device");
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  if (!mesh.faces.empty()) {
    RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.faces.size()));
    check_device(impl_->device, "buffer allocation");
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      const Vec3 p = mesh.vertices[i] - offset_;
      vb[3 * i] = float(p.x());
      vb[3 * i + 1] = float(p.y());
      vb[3 * i + 2] = float(p.z());
    }
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      for (int k = 0; k < 3; ++k) ib[3 * f + k] = unsigned(mesh.faces[f][k]);
    impl_->vertices.reserve(mesh.vertices.size());
    for (const Vec3& v : mesh.vertices) impl_->vertices.push_back(v - offset_);
    impl_->faces = mesh.faces;
    rtcCommitGeometry(geom);
    rtcAttachGeometry(impl_->scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(impl_->scene);
  check_device(impl_->device, "scene build");
}

RayCaster::~RayCaster() = default;

double RayCaster::closest_point(const Vec3& p, Vec3* point, int* face) const {
  if (impl_->faces.empty()) throw Error("closest point on a mesh without faces");
  if (!p.allFinite()) throw Error("closest point of a non-finite point");
  PointQueryState state;
  state.impl = impl_.get();
  state.query = p - offset_;
  RTCPointQuery query;
  query.x = float(state.query.x());
  query.y = float(state.query.y());
  query.z = float(state.query.z());
  query.time = 0.0f;
  query.radius = std::numeric_limits<float>::infinity();
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(impl_->scene, &query, &context, point_query_callback, &state);
  if (state.face < 0) throw Error("closest point query found no face");
  if (point) *point = state.best + offset_;
  if (face) *face = state.face;
  return std::sqrt(state.best_d2);
}

bool RayCaster::intersect(const Vec3& origin, const Vec3& direction, RayHit* hit, double t_min,
                          double t_max) const {
  const double len = direction.norm();
  if (!(len > 0)) return false;
  const Vec3 d = direction / len;
  RTCRayHit rh;
  fill_ray(&rh.ray, origin - offset_, d, t_min, t_max);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(impl_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit->distance = rh.ray.tfar;
  hit->face = int(rh.hit.primID);
  hit->u = rh.hit.u;
  hit->v = rh.hit.v;
  return true;
}

bool RayCaster::occluded(const Vec3& origin, const Vec3& direction, double t_min,
                         double t_max) const {
  const double len = direction.norm();
  if (!(len > 0) || !(t_max > t_min)) return false;
  RTCRay ray;
  fill_ray(&ray, origin - offset_, direction / len, t_min, t_max);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(impl_->scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar = -inf on a hit
}

bool RayCaster::segment_clear(const Vec3& from, const Vec3& to, double relative_eps,
                              double absolute_eps) const {
  const Vec3 d = to - from;
  const double length = d.norm();
  const double t_max = (1.0 - relative_eps) * length - absolute_eps;
  if (t_max <= 0) return true;
  return !occluded(from, d, 0.0, t_max);
}

bool RayCaster::segments_clear4(const Vec3& from, const Vec3 (&to)[4], double relative_eps,
                                double absolute_eps) const {
  alignas(16) int valid[4];
  alignas(16) RTCRay4 rays;
  const Vec3 o = from - offset_;
  bool any = false;
  for (int k = 0; k < 4; ++k) {
    const Vec3 d = to[k] - from;
    const double length = d.norm();
    const double t_max = (1.0 - relative_eps) * length - absolute_eps;
    valid[k] = t_max > 0 && length > 0 ? -1 : 0;
    any = any || valid[k];
    const Vec3 u = length > 0 ? Vec3(d / length) : Vec3(0, 0, 1);
    rays.org_x[k] = float(o.x());
    rays.org_y[k] = float(o.y());
    rays.org_z[k] = float(o.z());
    rays.dir_x[k] = float(u.x());
    rays.dir_y[k] = float(u.y());
    rays.dir_z[k] = float(u.z());
    rays.tnear[k] = 0.0f;
    rays.tfar[k] = valid[k] ? float(t_max) : 0.0f;
    rays.time[k] = 0.0f;
    rays.mask[k] = 0xFFFFFFFFu;
    rays.id[k] = unsigned(k);
    rays.flags[k] = 0;
  }
  if (!any) return true;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcOccluded4(valid, impl_->scene, &context, &rays);
  for (int k = 0; k < 4; ++k)
    if (valid[k] && rays.tfar[k] < 0.0f) return false;
  return true;
}

}  // namespace meshnbv
