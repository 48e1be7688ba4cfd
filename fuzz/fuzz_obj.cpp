// OBJ (tinyobjloader underneath, our checks on top).
#include "fuzz_mesh_readers.h"

MESHNBV_FUZZ_TARGET(obj) {
  return meshnbv::fuzz::fuzz_mesh("input.obj",
                                  std::string(reinterpret_cast<const char*>(data), size),
                                  meshnbv::io::read_obj);
}
