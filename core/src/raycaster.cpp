#include "meshnbv/raycaster.h"

#include <cmath>

#include <embree3/rtcore.h>

#include "meshnbv/error.h"

namespace meshnbv {

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {
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
    rtcCommitGeometry(geom);
    rtcAttachGeometry(impl_->scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(impl_->scene);
  check_device(impl_->device, "scene build");
}

RayCaster::~RayCaster() = default;

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
