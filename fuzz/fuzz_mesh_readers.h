// One body for the mesh format targets: write the input with the format's
// extension, read it, exercise what was read.
#pragma once

#include "fuzz_target.h"
#include "meshnbv/error.h"
#include "meshnbv/io/mesh_io.h"

namespace meshnbv::fuzz {

template <class Reader>
int fuzz_mesh(const std::string& file_name, const std::string& text, Reader read) {
  const std::string path = write_text(file_name, text);
  TriangleMesh mesh;
  try {
    mesh = read(path);
  } catch (const Error&) {
    return 0;  // refused with a message: fine
  }
  exercise_mesh(mesh);
  return 0;
}

}  // namespace meshnbv::fuzz
