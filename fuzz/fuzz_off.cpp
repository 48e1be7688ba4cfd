// OFF and its [ST][C][N]OFF variants.
#include "fuzz_mesh_readers.h"

MESHNBV_FUZZ_TARGET(off) {
  return meshnbv::fuzz::fuzz_mesh("input.off",
                                  std::string(reinterpret_cast<const char*>(data), size),
                                  meshnbv::io::read_off);
}
