// OBJ reader on top of tinyobjloader. Only positions and polygons are used;
// normals, texture coordinates and materials are ignored, so a missing .mtl
// never fails a read. Polygons are fan-triangulated here (not by
// tinyobjloader) so that OBJ, PLY and OFF give the same triangles.
//
// Face numbers in messages are 0-based polygon positions over the whole
// file (all objects and groups), before triangulation.
#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <tiny_obj_loader.h>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"

namespace meshnbv::io {
namespace {

// tinyobjloader reports "... line 12.)" inside its text; pull the number out
// so the Error carries it like the other readers do.
long line_in_message(const std::string& message) {
  const std::size_t at = message.find("line ");
  if (at == std::string::npos) return -1;
  long line = 0;
  bool any = false;
  for (std::size_t i = at + 5;
       i < message.size() && std::isdigit(static_cast<unsigned char>(message[i])); ++i) {
    line = line * 10 + (message[i] - '0');
    any = true;
  }
  return any ? line : -1;
}

std::string first_line(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
  return line;
}

// tinyobjloader drops faces with fewer than 3 vertices with only a warning
// and no position; find the first such `f` line ourselves to name it.
long find_short_face_line(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  long number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream words(line.substr(0, line.find('#')));
    std::string word;
    if (!(words >> word) || word != "f") continue;
    int count = 0;
    while (words >> word) ++count;
    if (count < 3) return number;
  }
  return -1;
}

// A plain decimal number, as tinyobjloader parses it: [+-] digits [. digits]
// [e [+-] digits]. Anything else ("nan", "inf", hex, "1,5", "x") it silently
// reads as 0, and an exponent of 10 digits overflows its int (undefined
// behaviour), so such numbers are refused before it sees them.
bool is_decimal(const std::string& token) {
  std::size_t i = 0, digits = 0;
  const std::size_t n = token.size();
  auto is_digit = [&](std::size_t k) {
    return k < n && std::isdigit(static_cast<unsigned char>(token[k]));
  };
  if (i < n && (token[i] == '+' || token[i] == '-')) ++i;
  while (is_digit(i)) ++i, ++digits;
  if (i < n && token[i] == '.') {
    ++i;
    while (is_digit(i)) ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < n && (token[i] == 'e' || token[i] == 'E')) {
    ++i;
    if (i < n && (token[i] == '+' || token[i] == '-')) ++i;
    const std::size_t first = i;
    while (is_digit(i)) ++i;
    if (i == first || i - first > 6) return false;
  }
  return i == n;
}

// The text tinyobjloader gets: only the statements we use, `v` (checked
// here: x y z and any w or colour values must be finite decimal numbers),
// `f`, `o` and `g`. The others (vt, vn, vp, vw, l, p, s, t, usemtl, mtllib,
// ...) carry nothing we read, and tinyobjloader 2.0.0rc10 parses some of
// them with undefined behaviour on hostile numbers (vw joint ids cast to int
// unchecked, exponents overflowing an int): they are blanked, keeping the
// line breaks so that line numbers in its messages stay right. Lines end at
// \n, \r or \r\n, as in tinyobjloader.
std::string used_statements(const std::string& text, const std::string& path) {
  std::string out = text;
  long line = 0, vertex = 0;
  std::size_t pos = 0;
  while (pos < out.size()) {
    std::size_t end = out.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = out.size();
    ++line;
    const std::size_t i = out.find_first_not_of(" \t", pos);
    const bool statement = i != std::string::npos && i + 1 < end &&
                           (out[i + 1] == ' ' || out[i + 1] == '\t');
    const char keyword = statement ? out[i] : '\0';
    if (keyword == 'v') {
      std::string rest = out.substr(i + 2, end - i - 2);
      std::istringstream words(rest.substr(0, rest.find('#')));
      const std::string element = "vertex " + std::to_string(vertex++);
      std::string word;
      int count = 0;
      while (words >> word) {
        if (!is_decimal(word))
          throw Error("coordinate '" + word + "' is not a number", path, line, element);
        if (!std::isfinite(std::strtod(word.c_str(), nullptr)))
          throw Error("coordinate '" + word + "' is out of range", path, line, element);
        ++count;
      }
      if (count < 3) throw Error("expected x y z, got fewer numbers", path, line, element);
    } else if (keyword != 'f' && keyword != 'o' && keyword != 'g') {
      std::fill(out.begin() + static_cast<std::ptrdiff_t>(pos),
                out.begin() + static_cast<std::ptrdiff_t>(end), ' ');
    }
    pos = end + 1;
  }
  return out;
}

tinyobj::ObjReader parse(const std::string& raw_text, const std::string& path) {
  const std::string text = used_statements(raw_text, path);
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // we fan-triangulate, like the PLY reader
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // Parsing from a string with no material text: `mtllib` is ignored.
  if (!reader.ParseFromString(text, std::string(), config)) {
    const std::string message = first_line(reader.Error());
    throw Error("invalid OBJ: " + (message.empty() ? std::string("parse failed") : message), path,
                line_in_message(reader.Error()));
  }
  if (reader.Warning().find("Degenerated face") != std::string::npos)
    throw Error("face with fewer than 3 vertices", path, find_short_face_line(text));
  return reader;
}

void check_index(int index, int vertex_count, std::size_t face, const std::string& path) {
  if (index >= 0 && index < vertex_count) return;
  // tinyobjloader has already made the index 0-based (and resolved negative,
  // relative indices), so report it in the file's 1-based convention.
  const std::string what =
      index < 0 ? "a relative (negative) vertex index points before the first vertex"
                : "vertex index " + std::to_string(static_cast<long long>(index) + 1) +
                      " (1-based) out of range";
  throw Error(what + " (the file has " + std::to_string(vertex_count) + " vertices)", path, -1,
              "face " + std::to_string(face));
}

void add_shape(const tinyobj::shape_t& shape, int vertex_count, const std::string& path,
               std::size_t* polygon, TriangleMesh* mesh) {
  const std::vector<tinyobj::index_t>& indices = shape.mesh.indices;
  std::size_t total = 0;
  for (unsigned char n : shape.mesh.num_face_vertices) total += n;
  // num_face_vertices is an unsigned char: a polygon of 256+ vertices wraps.
  if (total != indices.size())
    throw Error("a polygon in object '" + shape.name +
                    "' has more than 255 vertices, which is not supported",
                path);
  std::size_t offset = 0;
  for (unsigned char n : shape.mesh.num_face_vertices) {
    for (std::size_t k = 0; k < n; ++k)
      check_index(indices[offset + k].vertex_index, vertex_count, *polygon, path);
    for (std::size_t k = 1; k + 1 < n; ++k)
      mesh->faces.push_back({indices[offset].vertex_index, indices[offset + k].vertex_index,
                             indices[offset + k + 1].vertex_index});
    offset += n;
    ++*polygon;
  }
}

}  // namespace

TriangleMesh read_obj(const std::string& path) {
  const std::string text = read_file(path);
  const tinyobj::ObjReader reader = parse(text, path);
  const std::vector<tinyobj::real_t>& coords = reader.GetAttrib().vertices;
  if (coords.size() / 3 > static_cast<std::size_t>(INT_MAX)) throw Error("too many vertices", path);
  TriangleMesh mesh;
  mesh.vertices.reserve(coords.size() / 3);
  for (std::size_t i = 0; i + 2 < coords.size(); i += 3)
    mesh.vertices.emplace_back(coords[i], coords[i + 1], coords[i + 2]);
  const int vertex_count = static_cast<int>(mesh.vertices.size());
  std::size_t polygon = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes())
    add_shape(shape, vertex_count, path, &polygon, &mesh);
  mesh.validate(path);
  return mesh;
}

}  // namespace meshnbv::io
