// OFF reader (ascii). Accepts the header variants [ST][C][N]OFF: the extra
// per-vertex columns they announce (texture coordinates, colours, normals)
// are ignored, as are per-face colour columns. `#` starts a comment.
// Declared counts are checked against the file size before anything is
// reserved, so a corrupt header cannot trigger a huge allocation.
//
// Vertex and face numbers in messages are 0-based positions in the file.
#include <climits>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"

namespace meshnbv::io {
namespace {

// Lines of tokens with comments removed; blank lines are skipped.
class OffLines {
 public:
  OffLines(std::string text, const std::string& path)
      : tokens_(std::move(text), path), path_(path) {}

  bool next(std::vector<std::string>* words) {
    while (tokens_.next_line(words)) {
      strip_comment(words);
      if (!words->empty()) return true;
    }
    return false;
  }

  // Like next(), but the end of the file is an error naming what was expected.
  void require(std::vector<std::string>* words, const std::string& expected) {
    if (!next(words)) throw Error("unexpected end of file: expected " + expected, path_, line());
  }

  long line() const { return tokens_.line(); }

 private:
  static void strip_comment(std::vector<std::string>* words) {
    for (std::size_t i = 0; i < words->size(); ++i) {
      const std::size_t hash = (*words)[i].find('#');
      if (hash == std::string::npos) continue;
      (*words)[i].resize(hash);
      words->resize((*words)[i].empty() ? i : i + 1);
      return;
    }
  }

  TextTokens tokens_;
  std::string path_;
};

// [ST][C][N]OFF; "4OFF"/"nOFF" (other dimensions) and binary OFF are refused.
bool is_off_keyword(std::string word) {
  if (word.compare(0, 2, "ST") == 0) word.erase(0, 2);
  if (!word.empty() && word[0] == 'C') word.erase(0, 1);
  if (!word.empty() && word[0] == 'N') word.erase(0, 1);
  return word == "OFF";
}

struct OffCounts {
  long long vertices = 0;
  long long faces = 0;
};

OffCounts read_header(OffLines* lines, const std::string& path) {
  std::vector<std::string> w;
  if (!lines->next(&w) || !is_off_keyword(w[0]))
    throw Error("not an OFF file: expected 'OFF' (or COFF, NOFF, ...) on the first line", path,
                lines->line());
  if (w.size() > 1 && w[1] == "BINARY")
    throw Error("binary OFF is not supported; convert it to ascii OFF or PLY", path, lines->line());
  // The counts may follow the keyword on the same line.
  w.erase(w.begin());
  if (w.empty()) lines->require(&w, "the counts line '<vertices> <faces> <edges>'");
  if (w.size() < 2 || w.size() > 3)
    throw Error("expected '<vertices> <faces> [<edges>]'", path, lines->line());
  OffCounts c;
  c.vertices = parse_int(w[0], path, lines->line(), "the vertex count");
  c.faces = parse_int(w[1], path, lines->line(), "the face count");
  if (c.vertices < 0 || c.faces < 0) throw Error("negative count", path, lines->line());
  return c;
}

// A vertex line is at least "0 0 0\n" (6 bytes), a face "3 0 1 2\n" (8).
void check_counts_fit(const OffCounts& c, std::uintmax_t file_bytes, long line,
                      const std::string& path) {
  const std::uintmax_t vmax = file_bytes / 6 + 1, fmax = file_bytes / 8 + 1;
  const bool too_many =
      static_cast<std::uintmax_t>(c.vertices) > vmax ||
      static_cast<std::uintmax_t>(c.faces) > fmax ||
      static_cast<std::uintmax_t>(c.vertices) * 6 + static_cast<std::uintmax_t>(c.faces) * 8 >
          file_bytes + 1;
  if (too_many)
    throw Error("header declares " + std::to_string(c.vertices) + " vertices and " +
                    std::to_string(c.faces) + " faces, more than a " + std::to_string(file_bytes) +
                    "-byte file can hold; the file is truncated or its header is corrupt",
                path, line);
  if (c.vertices > INT_MAX) throw Error("too many vertices", path, line);
}

void read_vertices(OffLines* lines, long long count, const std::string& path, TriangleMesh* mesh) {
  std::vector<std::string> w;
  mesh->vertices.reserve(static_cast<std::size_t>(count));
  for (long long i = 0; i < count; ++i) {
    const std::string name = "vertex " + std::to_string(i);
    lines->require(&w, name + " (the header declares " + std::to_string(count) + " vertices)");
    if (w.size() < 3) throw Error("expected x y z", path, lines->line(), name);
    Vec3 p;
    for (int k = 0; k < 3; ++k)
      p[k] = parse_double(w[k], path, lines->line(), name + " coordinate");
    mesh->vertices.push_back(p);
  }
}

void read_faces(OffLines* lines, long long count, const std::string& path, TriangleMesh* mesh) {
  std::vector<std::string> w;
  std::vector<int> polygon;
  const long long nv = static_cast<long long>(mesh->vertices.size());
  mesh->faces.reserve(static_cast<std::size_t>(count));
  for (long long i = 0; i < count; ++i) {
    const std::string name = "face " + std::to_string(i);
    lines->require(&w, name + " (the header declares " + std::to_string(count) + " faces)");
    const long line = lines->line();
    const long long n = parse_int(w[0], path, line, "the vertex count of " + name);
    if (n < 3)
      throw Error("polygon with " + w[0] + " vertices (at least 3 needed)", path, line, name);
    // Columns after the n indices are an optional colour: ignored.
    if (static_cast<long long>(w.size()) - 1 < n)
      throw Error("expected " + w[0] + " vertex indices, got " + std::to_string(w.size() - 1), path,
                  line, name);
    polygon.clear();
    for (long long k = 0; k < n; ++k) {
      const long long index =
          parse_int(w[static_cast<std::size_t>(k + 1)], path, line, "a vertex index");
      if (index < 0 || index >= nv)
        throw Error("vertex index " + std::to_string(index) + " out of range (the file has " +
                        std::to_string(nv) + " vertices)",
                    path, line, name);
      polygon.push_back(static_cast<int>(index));
    }
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)  // fan, like the PLY reader
      mesh->faces.push_back({polygon[0], polygon[k], polygon[k + 1]});
  }
}

}  // namespace

TriangleMesh read_off(const std::string& path) {
  std::string text = read_file(path);
  const std::uintmax_t bytes = text.size();
  OffLines lines(std::move(text), path);
  const OffCounts counts = read_header(&lines, path);
  check_counts_fit(counts, bytes, lines.line(), path);
  TriangleMesh mesh;
  read_vertices(&lines, counts.vertices, path, &mesh);
  read_faces(&lines, counts.faces, path, &mesh);
  mesh.validate(path);
  return mesh;
}

}  // namespace meshnbv::io
