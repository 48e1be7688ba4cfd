// PLY, whole files: header parsing, ascii and binary bodies (seeds of all
// three encodings).
#include "fuzz_mesh_readers.h"

MESHNBV_FUZZ_TARGET(ply) {
  return meshnbv::fuzz::fuzz_mesh("input.ply",
                                  std::string(reinterpret_cast<const char*>(data), size),
                                  meshnbv::io::read_ply);
}
