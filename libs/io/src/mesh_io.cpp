// read_mesh: picks the reader from the file extension.
#include "meshnbv/io/mesh_io.h"

#include <string>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"

namespace meshnbv::io {

TriangleMesh read_mesh(const std::string& path) {
  // By extension, not content: the formats have no common magic number and
  // OBJ has none at all.
  const std::string ext = extension_lower(path);
  if (ext == ".ply") return read_ply(path);
  if (ext == ".obj") return read_obj(path);
  if (ext == ".off") return read_off(path);
  throw Error("unsupported mesh format '" + (ext.empty() ? std::string("(no extension)") : ext) +
                  "' (expected .ply, .obj or .off)",
              path);
}

}  // namespace meshnbv::io
