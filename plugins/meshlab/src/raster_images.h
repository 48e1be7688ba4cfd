// Rasters' images for the core. MeshLab holds each raster's image decoded
// (Plane::image, a QImage); the plugin converts those pixels once into a
// meshnbv::Image that the core's view holds in memory (View::pixels): no
// temporary file, and what the filters compare is what MeshLab shows.
#pragma once

#include <QImage>

#include "meshnbv/image.h"

namespace meshnbv::meshlab {

// The pixels the core's loader would decode from the same file:
// grey for grey formats and grey palettes, else RGB (alpha dropped
// without blending); 16-bit formats (Grayscale16, RGBA64) stay 16-bit, as
// the core's loader keeps 16-bit files, the others are 8-bit.
// Throws meshnbv::Error for a null image.
Image image_from_qimage(const QImage& image);

}  // namespace meshnbv::meshlab
