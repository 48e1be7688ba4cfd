#include "shot_conversion.h"

#include <charconv>
#include <cstdlib>

#include "meshnbv/error.h"

namespace meshnbv::meshlab {
namespace {

// What the core writes into .mlp files too (libs/io/src/mlp.cpp).
constexpr float kPixelSizeMm = 0.0369161f;

}  // namespace

double decimal(float value) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof(text) - 1, value);
  if (result.ec != std::errc()) return double(value);
  *result.ptr = '\0';
  return std::strtod(text, nullptr);
}

PinholeCamera camera_from_shot(const vcg::Shot<float>& shot, const std::string& what) {
  const vcg::Camera<float>& in = shot.Intrinsics;
  if (in.cameraType != vcg::Camera<float>::PERSPECTIVE)
    throw Error(what + ": only perspective cameras are supported (CameraType " +
                std::to_string(in.cameraType) + ")");
  if (in.k[0] != 0.0f || in.k[1] != 0.0f)
    throw Error(what + ": lens distortion is not supported (VCG's model is not a radial "
                       "polynomial); undistort the images and set LensDistortion to 0 0");
  if (!(in.PixelSizeMm[0] > 0) || !(in.PixelSizeMm[1] > 0))
    throw Error(what + ": PixelSizeMm must be positive");
  PinholeCamera cam;
  cam.width = in.ViewportPx[0];
  cam.height = in.ViewportPx[1];
  const double focal = decimal(in.FocalMm);
  cam.fx = focal / decimal(in.PixelSizeMm[0]);
  cam.fy = focal / decimal(in.PixelSizeMm[1]);
  cam.cx = decimal(in.CenterPx[0]) - 0.5;
  cam.cy = cam.height - decimal(in.CenterPx[1]) - 0.5;
  const vcg::Matrix44<float> rot = shot.Extrinsics.Rot();
  for (int c = 0; c < 3; ++c) {
    cam.R(0, c) = decimal(rot[0][c]);
    cam.R(1, c) = -decimal(rot[1][c]);
    cam.R(2, c) = -decimal(rot[2][c]);
  }
  const vcg::Point3<float> centre = shot.GetViewPoint();
  cam.set_center(Vec3(decimal(centre[0]), decimal(centre[1]), decimal(centre[2])));
  cam.check(what);
  return cam;
}

vcg::Shot<float> shot_from_camera(const PinholeCamera& camera) {
  if (camera.has_distortion())
    throw Error("a MeshLab raster cannot hold this lens (" + camera.lens_description() +
                "); undistort the images first");
  vcg::Shot<float> shot;
  vcg::Camera<float>& in = shot.Intrinsics;
  in.cameraType = vcg::Camera<float>::PERSPECTIVE;
  in.FocalMm = float(camera.fx * kPixelSizeMm);
  in.PixelSizeMm = vcg::Point2<float>(kPixelSizeMm, float(camera.fx * kPixelSizeMm / camera.fy));
  in.ViewportPx = vcg::Point2<int>(camera.width, camera.height);
  in.CenterPx = vcg::Point2<float>(float(camera.cx + 0.5), float(camera.height - camera.cy - 0.5));
  in.DistorCenterPx = in.CenterPx;
  in.k[0] = in.k[1] = in.k[2] = in.k[3] = 0;
  vcg::Matrix44<float> rot;
  rot.SetIdentity();
  for (int c = 0; c < 3; ++c) {
    rot[0][c] = float(camera.R(0, c));
    rot[1][c] = float(-camera.R(1, c));
    rot[2][c] = float(-camera.R(2, c));
  }
  shot.Extrinsics.SetRot(rot);
  const Vec3 centre = camera.center();
  shot.Extrinsics.SetTra(vcg::Point3<float>(float(centre.x()), float(centre.y()), float(centre.z())));
  return shot;
}

}  // namespace meshnbv::meshlab
