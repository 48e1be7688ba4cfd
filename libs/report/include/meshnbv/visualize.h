// Pictures for users: quality maps rendered with our renderer, camera
// frustums drawn over them, a colour scale, a histogram.
#pragma once

#include <string>
#include <vector>

#include "meshnbv/camera.h"
#include "meshnbv/image.h"
#include "meshnbv/mesh.h"

namespace meshnbv {

// A camera to draw as a frustum: apex at its centre, base = its image
// corners at `depth` (z in its frame).
struct FrustumOverlay {
  PinholeCamera camera;
  Rgb8 colour{255, 0, 0};
  double depth = 1.0;
  int thickness = 2;
  std::string label;  // drawn next to the base when not empty
};

// A camera at the given azimuth/elevation (degrees, world +z up) looking at
// the centre of `points`, far enough for all of them to be in the picture.
PinholeCamera overview_camera(const std::vector<Vec3>& points, double azimuth, double elevation,
                              int width, int height);

// Draws the frustums' edges (clipped at the viewer's near plane) on `image`
// as seen by `viewer`.
void draw_frustums(Image& image, const PinholeCamera& viewer, const std::vector<FrustumOverlay>& frustums);

// A vertical green-to-red colour bar with its value range, and a grey patch
// for "unobserved", in the image's top-right corner.
void draw_color_scale(Image& image, double lo, double hi, const std::string& title);

// A bar chart of `values` (NaN ignored) in `bins` equal bins.
Image histogram_image(const std::vector<float>& values, int bins, int width, int height,
                      const std::string& title);

// Share of pixels that differ from `background` by more than 2 levels.
double coverage(const Image& image, const Vec3& background);

}  // namespace meshnbv
