// Rasters' images for the core. The core reads a view's image from its
// path (through the scene's bounded cache), exactly as `meshnbv pri` does,
// so a raster whose file is on disk is given by its path: the results equal
// the command line's on the same project. Only an image that MeshLab holds
// without a readable file gets a lossless temporary copy (PGM/PPM), written
// here and deleted with this object.
#pragma once

#include <memory>
#include <string>

#include <QImage>

#include "meshnbv/image.h"

class QTemporaryDir;

namespace meshnbv::meshlab {

// 8-bit grey (grey formats and grey palettes) or RGB (anything else; alpha
// dropped, as the core's loader does).
Image image_from_qimage(const QImage& image);

class RasterImageFiles {
 public:
  RasterImageFiles();
  ~RasterImageFiles();
  RasterImageFiles(const RasterImageFiles&) = delete;
  RasterImageFiles& operator=(const RasterImageFiles&) = delete;

  // A path the core can read for a raster whose image MeshLab loaded from
  // `file`: `file` itself when it exists, else a temporary copy of `image`.
  // Throws meshnbv::Error when neither is available.
  std::string path_for(const std::string& file, const QImage& image, const std::string& label);
  int copies() const { return copies_; }

 private:
  std::unique_ptr<QTemporaryDir> dir_;
  int copies_ = 0;
};

}  // namespace meshnbv::meshlab
