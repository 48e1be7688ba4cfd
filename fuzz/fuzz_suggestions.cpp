// The suggestions JSON read back by `meshnbv mission` (libs/mission).
#include "fuzz_target.h"
#include "meshnbv/error.h"
#include "meshnbv/mission/suggestions.h"

MESHNBV_FUZZ_TARGET(suggestions) {
  try {
    const auto s = meshnbv::mission::parse_suggestions_json(
        std::string(reinterpret_cast<const char*>(data), size), "suggestions.json");
    FUZZ_CHECK(!s.suggestions.empty());
    for (const auto& m : s.suggestions) m.camera.check();
  } catch (const meshnbv::Error&) {
  }
  return 0;
}
