// The georeference JSON of `meshnbv mission --georef` (libs/mission):
// parsed and, when accepted, converted through PROJ.
#include "fuzz_target.h"
#include "meshnbv/error.h"
#include "meshnbv/mission/georef.h"

MESHNBV_FUZZ_TARGET(georef) {
  try {
    const auto g = meshnbv::mission::parse_georef_json(
        std::string(reinterpret_cast<const char*>(data), size), "georef.json");
    const meshnbv::mission::GeoFrame f(g);
    FUZZ_CHECK(f.metres_per_unit() > 0);
    (void)f.to_wgs84(meshnbv::Vec3::Zero());
  } catch (const meshnbv::Error&) {
  }
  return 0;
}
