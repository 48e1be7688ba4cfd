#include "raster_images.h"

#include <QRgba64>

#include "meshnbv/error.h"

namespace meshnbv::meshlab {
namespace {

bool is_16_bit_colour(QImage::Format f) {
  return f == QImage::Format_RGBA64 || f == QImage::Format_RGBX64 ||
         f == QImage::Format_RGBA64_Premultiplied;
}

}  // namespace

Image image_from_qimage(const QImage& image) {
  if (image.isNull()) throw Error("empty image");
  // Grey as the core's loader sees grey files: grey formats, and palettes of
  // greys (low-depth grey PNGs). Not a colour image whose pixels happen to
  // be grey (isGrayscale() alone would say so): that one stays RGB.
  const QImage::Format f = image.format();
  const bool is_grey = f == QImage::Format_Grayscale8 || f == QImage::Format_Grayscale16 ||
                    ((f == QImage::Format_Indexed8 || f == QImage::Format_Mono ||
                      f == QImage::Format_MonoLSB) && image.isGrayscale());
  if (f == QImage::Format_Grayscale16) {
    // Kept at 16 bits, as the core keeps 16-bit files.
    Image out(image.width(), image.height(), 1, 16);
    for (int y = 0; y < image.height(); ++y) {
      const quint16* row = reinterpret_cast<const quint16*>(image.constScanLine(y));
      std::copy(row, row + image.width(), out.pixel16(0, y));
    }
    return out;
  }
  if (is_grey) {
    const QImage grey = image.convertToFormat(QImage::Format_Grayscale8);
    Image out(grey.width(), grey.height(), 1);
    for (int y = 0; y < grey.height(); ++y) {
      const uchar* row = grey.constScanLine(y);
      std::copy(row, row + grey.width(), out.pixel(0, y));
    }
    return out;
  }
  if (is_16_bit_colour(f)) {
    // Non-premultiplied 16-bit colour, channels as stored (alpha dropped),
    // kept at 16 bits.
    const QImage rgba = image.convertToFormat(QImage::Format_RGBA64);
    Image out(rgba.width(), rgba.height(), 3, 16);
    for (int y = 0; y < rgba.height(); ++y) {
      const QRgba64* row = reinterpret_cast<const QRgba64*>(rgba.constScanLine(y));
      std::uint16_t* dst = out.pixel16(0, y);
      for (int x = 0; x < rgba.width(); ++x, dst += 3) {
        dst[0] = row[x].red();
        dst[1] = row[x].green();
        dst[2] = row[x].blue();
      }
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

}  // namespace meshnbv::meshlab
