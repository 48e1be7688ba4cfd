// EXIF of a photo through exiv2 (io/exif.h): GPS and focal length.
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
  return 0;
}
