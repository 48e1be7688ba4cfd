// The georeference of `meshnbv mission --georef` (libs/mission): a JSON
// file, or the argument forms "ecef" and "enu:LAT,LON,H"; parsed and, when
// accepted, localized (geocentric and ENU frames) and converted through PROJ.
#include "fuzz_target.h"
#include "meshnbv/error.h"
#include "meshnbv/mission/georef.h"

MESHNBV_FUZZ_TARGET(georef) {
  using namespace meshnbv;
  try {
    const std::string text(reinterpret_cast<const char*>(data), size);
    auto g = text.rfind("enu:", 0) == 0 || text == "ecef" ? mission::parse_georef_argument(text)
                                                         : mission::parse_georef_json(text, "georef.json");
    if (mission::is_curved_frame(g)) {
      // A small site around the scene's origin in its own units.
      const std::vector<Vec3> points = {Vec3::Zero(), Vec3(10, 0, 0), Vec3(0, 10, 0), Vec3(0, 0, 10),
                                        Vec3(10, 10, 5)};
      g = mission::localize_georef(g, points);
    }
    const mission::GeoFrame f(g);
    FUZZ_CHECK(f.metres_per_unit() > 0);
    (void)f.to_wgs84(Vec3::Zero());
  } catch (const Error&) {
  }
  return 0;
}
