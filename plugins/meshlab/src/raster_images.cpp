#include "raster_images.h"

#include <QFileInfo>
#include <QTemporaryDir>

#include "meshnbv/error.h"

namespace meshnbv::meshlab {

Image image_from_qimage(const QImage& image) {
  if (image.isNull()) throw Error("empty image");
  // Grey as the core's loader sees grey files: grey formats, and palettes of
  // greys (low-depth grey PNGs). Not a colour image whose pixels happen to
  // be grey (isGrayscale() alone would say so): that one stays RGB.
  const QImage::Format f = image.format();
  const bool is_grey = f == QImage::Format_Grayscale8 || f == QImage::Format_Grayscale16 ||
                    ((f == QImage::Format_Indexed8 || f == QImage::Format_Mono ||
                      f == QImage::Format_MonoLSB) && image.isGrayscale());
  if (is_grey) {
    const QImage grey = image.convertToFormat(QImage::Format_Grayscale8);
    Image out(grey.width(), grey.height(), 1);
    for (int y = 0; y < grey.height(); ++y) {
      const uchar* row = grey.constScanLine(y);
      std::copy(row, row + grey.width(), out.pixel(0, y));
    }
    return out;
  }
  // Non-premultiplied ARGB32 keeps the colour channels as stored; alpha is
  // dropped without blending, as the core's loader does.
  const QImage argb = image.convertToFormat(QImage::Format_ARGB32);
  Image out(argb.width(), argb.height(), 3);
  for (int y = 0; y < argb.height(); ++y) {
    const QRgb* row = reinterpret_cast<const QRgb*>(argb.constScanLine(y));
    std::uint8_t* dst = out.pixel(0, y);
    for (int x = 0; x < argb.width(); ++x, dst += 3) {
      dst[0] = std::uint8_t(qRed(row[x]));
      dst[1] = std::uint8_t(qGreen(row[x]));
      dst[2] = std::uint8_t(qBlue(row[x]));
    }
  }
  return out;
}

RasterImageFiles::RasterImageFiles() = default;
RasterImageFiles::~RasterImageFiles() = default;

std::string RasterImageFiles::path_for(const std::string& file, const QImage& image,
                                       const std::string& label) {
  const QFileInfo info(QString::fromStdString(file));
  if (!file.empty() && info.isFile() && info.isReadable()) return file;
  if (image.isNull())
    throw Error("raster '" + label + "': its image '" + file +
                "' is neither loaded nor readable on disk");
  if (!dir_) {
    dir_ = std::make_unique<QTemporaryDir>();
    if (!dir_->isValid()) throw Error("cannot create a temporary folder for raster images");
  }
  const Image copy = image_from_qimage(image);
  const std::string path = dir_->filePath(QString("raster_%1.%2")
                                              .arg(copies_)
                                              .arg(copy.channels() == 1 ? "pgm" : "ppm"))
                               .toStdString();
  copy.save(path);
  ++copies_;
  return path;
}

}  // namespace meshnbv::meshlab
