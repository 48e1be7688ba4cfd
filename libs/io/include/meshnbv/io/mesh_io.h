// Mesh files: PLY (ASCII, binary little/big endian; read and write), OBJ
// and OFF (read). Polygons are fan-triangulated; unknown PLY properties are
// skipped; PLY per-face `quality` (float) and `red green blue` (uchar) are
// read into face_attributes["quality"] and face_colors.
#pragma once

#include <string>
#include <vector>

#include "meshnbv/mesh.h"

namespace meshnbv::io {

TriangleMesh read_ply(const std::string& path);
// What a PLY file stores its vertex coordinates as: the coarsest type of x,
// y and z (Integer < Float32 < Float64), so how far a coordinate read back
// may be from the value that was written.
enum class PlyCoordinateType { Integer, Float32, Float64 };
struct PlyFileInfo {
  PlyCoordinateType coordinates = PlyCoordinateType::Float32;
  std::vector<std::string> comments;  // each "comment" line's text
};
// (A name of its own: an overload of read_ply could not be passed as a template argument.)
TriangleMesh read_ply_with_info(const std::string& path, PlyFileInfo* info);
TriangleMesh read_obj(const std::string& path);
TriangleMesh read_off(const std::string& path);
// By extension (.ply, .obj, .off); throws Error for anything else.
TriangleMesh read_mesh(const std::string& path);

struct PlyWriteOptions {
  bool binary = true;             // binary little endian, else ASCII
  // Vertex coordinates as double. When false, they are still written as
  // double if rounding to float would move a vertex by more than 1e-6 of
  // the bounding-box diagonal (a mesh far from the origin, georeferenced)
  // or a coordinate is beyond float's range.
  bool double_precision = false;
  // With double_precision false: double as soon as any coordinate is not
  // exactly a float, so that the file gives back the very mesh (a PRI mesh
  // that `meshnbv pri --previous` reuses face by face).
  bool exact_coordinates = false;
  bool overwrite = true;          // false: throw if the file exists
  std::string comment = "written by MeshNBV";
  std::vector<std::string> comments;  // more comment lines, after `comment`
};

// Writes vertices, faces, every per-face attribute as a float property of
// that name (so "quality" is MeshLab's face quality) and face colours as
// `red green blue` uchar. Atomic: the file appears only when complete.
void write_ply(const TriangleMesh& mesh, const std::string& path,
               const PlyWriteOptions& options = {});

}  // namespace meshnbv::io
