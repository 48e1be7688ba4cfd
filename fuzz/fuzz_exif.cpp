// EXIF of a photo through exiv2 (io/exif.h): GPS and focal length, and the
// header `meshnbv info` reads (size, bit depth, orientation tag).
#include <cmath>

#include "fuzz_target.h"
#include "meshnbv/error.h"
#include "meshnbv/io/exif.h"

MESHNBV_FUZZ_TARGET(exif) {
  try {
    const meshnbv::io::ExifInfo e = meshnbv::io::read_exif_from_memory(
        std::string(reinterpret_cast<const char*>(data), size), "photo.jpg");
    if (e.latitude) FUZZ_CHECK(std::abs(*e.latitude) <= 90);
    if (e.longitude) FUZZ_CHECK(std::abs(*e.longitude) <= 180);
  } catch (const meshnbv::Error&) {
  }
  try {
    const auto h = meshnbv::io::read_photo_header_from_memory(
        std::string(reinterpret_cast<const char*>(data), size), "photo.jpg");
    if (h) FUZZ_CHECK(h->orientation >= 0 && h->orientation <= 8 && h->bits >= 0 && h->bits <= 64);
  } catch (const meshnbv::Error&) {
  }
  return 0;
}
