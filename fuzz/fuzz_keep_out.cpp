// Keep-out polygons, GeoJSON (`meshnbv mission --keep-out`, libs/mission).
#include "fuzz_target.h"
#include "meshnbv/error.h"
#include "meshnbv/mission/airspace.h"

MESHNBV_FUZZ_TARGET(keep_out) {
  try {
    const auto k = meshnbv::mission::parse_keep_out_geojson(
        std::string(reinterpret_cast<const char*>(data), size), "keep_out.geojson");
    for (const auto& p : k.polygons) {
      FUZZ_CHECK(p.lonlat.size() >= 3 && p.floor < p.ceiling);
      FUZZ_CHECK(!meshnbv::mission::ring_self_intersects(p.lonlat));
    }
  } catch (const meshnbv::Error&) {
  }
  return 0;
}
