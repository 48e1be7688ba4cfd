// Mesh files: PLY (ASCII, binary little/big endian; read and write), OBJ
// and OFF (read). Polygons are fan-triangulated; unknown PLY properties are
// skipped; PLY per-face `quality` (float) and `red green blue` (uchar) are
// read into face_attributes["quality"] and face_colors.
#pragma once

#include <string>

#include "meshnbv/mesh.h"

namespace meshnbv::io {

TriangleMesh read_ply(const std::string& path);
TriangleMesh read_obj(const std::string& path);
TriangleMesh read_off(const std::string& path);
// By extension (.ply, .obj, .off); throws Error for anything else.
TriangleMesh read_mesh(const std::string& path);

struct PlyWriteOptions {
  bool binary = true;             // binary little endian, else ASCII
  bool double_precision = false;  // vertex coordinates as double
  bool overwrite = true;          // false: throw if the file exists
  std::string comment = "written by MeshNBV";
};

// Writes vertices, faces, every per-face attribute as a float property of
// that name (so "quality" is MeshLab's face quality) and face colours as
// `red green blue` uchar. Atomic: the file appears only when complete.
void write_ply(const TriangleMesh& mesh, const std::string& path,
               const PlyWriteOptions& options = {});

}  // namespace meshnbv::io
