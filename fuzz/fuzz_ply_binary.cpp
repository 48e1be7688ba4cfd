// PLY binary bodies behind a fixed, valid header, so that mutations land in
// the data rather than in the header text. Input: byte 0 picks the header
// (encoding, types, extra elements), bytes 1-2 the vertex and face counts,
// the rest is the body.
#include <cstdio>

#include "fuzz_mesh_readers.h"

namespace {

const char* const kHeaders[] = {
    // little endian, float xyz, uchar/int indices, quality and colour
    "format binary_little_endian 1.0\n"
    "element vertex %u\nproperty float x\nproperty float y\nproperty float z\n"
    "element face %u\nproperty list uchar int vertex_indices\nproperty float quality\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n",
    // the same, big endian
    "format binary_big_endian 1.0\n"
    "element vertex %u\nproperty float x\nproperty float y\nproperty float z\n"
    "element face %u\nproperty list uchar int vertex_indices\nproperty float quality\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n",
    // double coordinates, int/uint indices, skipped vertex properties
    "format binary_little_endian 1.0\n"
    "element vertex %u\nproperty double x\nproperty double y\nproperty double z\n"
    "property list uchar float normal_list\nproperty short flags\n"
    "element face %u\nproperty list int uint vertex_index\nproperty double value\n",
    // faces first, an element to skip in between, small types
    "format binary_big_endian 1.0\n"
    "element face %u\nproperty list ushort ushort vertex_indices\nproperty int tag\n"
    "element material 2\nproperty list uint float values\nproperty uchar id\n"
    "element vertex %u\nproperty char x\nproperty short y\nproperty uint16 z\n",
};

}  // namespace

MESHNBV_FUZZ_TARGET(ply_binary) {
  if (size < 3) return 0;
  const unsigned which = data[0] % (sizeof(kHeaders) / sizeof(kHeaders[0]));
  const unsigned vertices = data[1], faces = data[2];
  char header[1024];
  if (which == 3)  // this header declares the faces first
    std::snprintf(header, sizeof(header), kHeaders[which], faces, vertices);
  else
    std::snprintf(header, sizeof(header), kHeaders[which], vertices, faces);
  std::string text = std::string("ply\n") + header + "end_header\n";
  text.append(reinterpret_cast<const char*>(data) + 3, size - 3);
  return meshnbv::fuzz::fuzz_mesh("input.ply", text, meshnbv::io::read_ply);
}
