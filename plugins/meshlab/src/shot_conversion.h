// VCG shots (MeshLab's raster cameras) <-> the core's PinholeCamera, as
// docs/conventions.md maps them for .mlp files:
//   C = shot.GetViewPoint(), Rv = upper 3x3 of shot.Extrinsics.Rot() (rows =
//   camera axes, the camera looks along -z, y up), R = diag(1, -1, -1) Rv;
//   fx = FocalMm / PixelSizeMm.x, fy = FocalMm / PixelSizeMm.y;
//   VCG pixels have their origin at the image's bottom-left corner, y up:
//   cx = CenterPx.x - 0.5, cy = H - CenterPx.y - 0.5.
#pragma once

#include <string>

#include <vcg/math/shot.h>

#include "meshnbv/camera.h"

namespace meshnbv::meshlab {

// MeshLab keeps cameras and filter parameters in float. A float is turned
// into the double of its shortest decimal representation, so that a value
// MeshLab parsed from text ("0.33" in a script, a camera of a project that
// MeshLab wrote with 6 significant digits) becomes the same double the
// core gets from the same text.
double decimal(float value);

// Throws meshnbv::Error (naming `what`) for an orthographic camera, lens
// distortion, a non-positive pixel size or an invalid result.
PinholeCamera camera_from_shot(const vcg::Shot<float>& shot, const std::string& what = "raster");

// The shot of `camera` (no distortion; PixelSizeMm.x fixed, any value gives
// the same pixels).
vcg::Shot<float> shot_from_camera(const PinholeCamera& camera);

}  // namespace meshnbv::meshlab
