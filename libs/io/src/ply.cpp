// PLY reader and writer (ascii, binary little and big endian).
//
// Written by hand rather than through OpenMesh so that a hostile or broken
// file produces a precise meshnbv::Error (file, line, element) and never a
// huge allocation: declared element counts are checked against the bytes
// that actually follow the header before anything is reserved.
//
// Faces: scalar float/double properties are read into face_attributes under
// their own name (so "quality" and whatever write_ply stored come back);
// uchar red/green/blue into face_colors; everything else is skipped.
//
// Element numbers in messages are 0-based positions in the file ("face 0"
// is the first face of the face element), before triangulation.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"

namespace meshnbv::io {
namespace {

// ---------------------------------------------------------------- types ---

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8: return 1;
    case PlyType::Int16:
    case PlyType::UInt16: return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

bool is_integer(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

bool parse_type(const std::string& name, PlyType* out) {
  struct Alias {
    const char* name;
    PlyType type;
  };
  static const Alias kAliases[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const Alias& a : kAliases)
    if (name == a.name) {
      *out = a.type;
      return true;
    }
  return false;
}

// Inclusive value range of an integer type, for ascii range checks.
void integer_range(PlyType t, long long* lo, long long* hi) {
  switch (t) {
    case PlyType::Int8: *lo = -128, *hi = 127; return;
    case PlyType::UInt8: *lo = 0, *hi = 255; return;
    case PlyType::Int16: *lo = -32768, *hi = 32767; return;
    case PlyType::UInt16: *lo = 0, *hi = 65535; return;
    case PlyType::Int32: *lo = -2147483648LL, *hi = 2147483647LL; return;
    default: *lo = 0, *hi = 4294967295LL; return;
  }
}

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyProperty {
  std::string name;
  bool is_list = false;
  PlyType type = PlyType::Float32;      // scalar type, or list item type
  PlyType count_type = PlyType::UInt8;  // lists only
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  long line = 0;  // header line declaring it, for messages
};

// "3 faces", "3 vertices", "3 'material' elements": for count messages.
std::string element_count(const std::string& name, std::uint64_t n) {
  const std::string count = std::to_string(n);
  if (name == "vertex") return count + " vertices";
  if (name == "face") return count + " faces";
  return count + " '" + name + "' elements";
}

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;  // first byte after end_header's newline
  long lines = 0;               // header line count (ascii data starts after)
  std::vector<std::string> comments;  // text after "comment "
};

// --------------------------------------------------------------- header ---

std::vector<std::string> split_words(const std::string& line) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

class HeaderParser {
 public:
  HeaderParser(const std::string& data, const std::string& path) : data_(data), path_(path) {}

  PlyHeader parse() {
    std::string line;
    if (!next_line(&line) || line != "ply")
      throw Error("not a PLY file: the first line must be 'ply'", path_, 1);
    bool have_format = false;
    while (true) {
      if (!next_line(&line))
        throw Error("header has no 'end_header' line (file truncated or not a PLY file)", path_,
                    line_);
      std::vector<std::string> w = split_words(line);
      if (w.empty()) fail("empty header line");
      if (w[0] == "comment") {
        const std::size_t at = line.find("comment") + 7;
        header_.comments.push_back(at < line.size() ? line.substr(at + 1) : std::string());
        continue;
      }
      if (w[0] == "obj_info") continue;
      if (w[0] == "end_header") break;
      if (w[0] == "format") {
        if (have_format) fail("second 'format' line");
        parse_format(w);
        have_format = true;
      } else if (!have_format) {
        fail("expected 'format' after 'ply', got '" + w[0] + "'");
      } else if (w[0] == "element") {
        parse_element(w);
      } else if (w[0] == "property") {
        parse_property(w);
      } else {
        fail("unknown header keyword '" + w[0] + "'");
      }
    }
    if (!have_format) fail("no 'format' line before 'end_header'");
    header_.data_offset = pos_;
    header_.lines = line_;
    return header_;
  }

 private:
  [[noreturn]] void fail(const std::string& reason) const {
    throw Error("malformed PLY header: " + reason, path_, line_);
  }

  // The next line without its '\r'; false at end of data.
  bool next_line(std::string* line) {
    if (pos_ >= data_.size()) return false;
    std::size_t end = data_.find('\n', pos_);
    if (end == std::string::npos) end = data_.size();
    *line = data_.substr(pos_, end - pos_);
    if (!line->empty() && line->back() == '\r') line->pop_back();
    pos_ = end < data_.size() ? end + 1 : end;
    ++line_;
    return true;
  }

  void parse_format(const std::vector<std::string>& w) {
    if (w.size() != 3) fail("expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
    if (w[1] == "ascii")
      header_.format = PlyFormat::Ascii;
    else if (w[1] == "binary_little_endian")
      header_.format = PlyFormat::BinaryLittleEndian;
    else if (w[1] == "binary_big_endian")
      header_.format = PlyFormat::BinaryBigEndian;
    else
      fail("unknown format '" + w[1] + "'");
    if (w[2] != "1.0") fail("unsupported PLY version '" + w[2] + "' (expected 1.0)");
  }

  void parse_element(const std::vector<std::string>& w) {
    if (w.size() != 3) fail("expected 'element <name> <count>'");
    for (const PlyElement& e : header_.elements)
      if (e.name == w[1]) fail("element '" + w[1] + "' declared twice");
    PlyElement e;
    e.name = w[1];
    e.line = line_;
    const char* first = w[2].data();
    const char* last = first + w[2].size();
    auto [ptr, ec] = std::from_chars(first, last, e.count);
    if (ec != std::errc() || ptr != last)
      fail("element count '" + w[2] + "' is not a non-negative integer");
    header_.elements.push_back(std::move(e));
  }

  PlyType type_or_fail(const std::string& name) const {
    PlyType t;
    if (!parse_type(name, &t)) fail("unknown property type '" + name + "'");
    return t;
  }

  void parse_property(const std::vector<std::string>& w) {
    if (header_.elements.empty()) fail("'property' before any 'element'");
    PlyProperty p;
    if (w.size() >= 2 && w[1] == "list") {
      if (w.size() != 5) fail("expected 'property list <count type> <item type> <name>'");
      p.is_list = true;
      p.count_type = type_or_fail(w[2]);
      if (!is_integer(p.count_type)) fail("list count type '" + w[2] + "' is not an integer type");
      p.type = type_or_fail(w[3]);
      p.name = w[4];
    } else {
      if (w.size() != 3) fail("expected 'property <type> <name>'");
      p.type = type_or_fail(w[1]);
      p.name = w[2];
    }
    PlyElement& e = header_.elements.back();
    for (const PlyProperty& q : e.properties)
      if (q.name == p.name) fail("property '" + p.name + "' declared twice in '" + e.name + "'");
    e.properties.push_back(std::move(p));
  }

  const std::string& data_;
  const std::string& path_;
  std::size_t pos_ = 0;
  long line_ = 0;
  PlyHeader header_;
};

// Fewest bytes one element can take: lets us reject absurd counts before
// reserving memory for them.
std::uint64_t min_element_bytes(const PlyElement& e, PlyFormat format) {
  if (e.properties.empty()) return 0;
  // Ascii: each property is at least one character and a separator.
  if (format == PlyFormat::Ascii) return 2 * e.properties.size();
  std::uint64_t bytes = 0;
  for (const PlyProperty& p : e.properties) bytes += type_size(p.is_list ? p.count_type : p.type);
  return bytes;
}

void check_counts_fit(const PlyHeader& h, std::uint64_t available, const std::string& path) {
  // The last ascii line may lack its newline: one byte of slack.
  const std::uint64_t slack = h.format == PlyFormat::Ascii ? 1 : 0;
  std::uint64_t used = 0;
  for (const PlyElement& e : h.elements) {
    const std::uint64_t each = min_element_bytes(e, h.format);
    if (each == 0 || e.count == 0) continue;
    const std::uint64_t left = available + slack - used;
    if (e.count > left / each)
      throw Error("header declares " + element_count(e.name, e.count) + " (at least " +
                      std::to_string(each) + " bytes each) but only " +
                      std::to_string(left - slack) +
                      " bytes of data remain; the file is truncated or its header is corrupt",
                  path, e.line);
    used += e.count * each;
  }
}

// -------------------------------------------------------------- cursors ---

// Thrown by the cursors; the element loop turns it into a meshnbv::Error
// naming the element, since only it knows which element is being read.
struct DataError {
  bool end_of_data = false;  // ran out of bytes or lines
  std::string reason;
};

bool host_is_little_endian() {
  const std::uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

template <class T>
double load(const unsigned char* bytes) {
  T v;
  std::memcpy(&v, bytes, sizeof(T));
  return static_cast<double>(v);
}

class BinaryCursor {
 public:
  BinaryCursor(const std::string& data, std::size_t offset, bool big_endian)
      : data_(reinterpret_cast<const unsigned char*>(data.data())),
        size_(data.size()),
        pos_(offset),
        swap_(big_endian == host_is_little_endian()) {}

  long line() const { return -1; }
  void begin_element() {}
  void end_element() {}

  double value(PlyType t) {
    const std::size_t n = type_size(t);
    need(n);
    unsigned char b[8];
    for (std::size_t i = 0; i < n; ++i) b[i] = data_[pos_ + (swap_ ? n - 1 - i : i)];
    pos_ += n;
    switch (t) {
      case PlyType::Int8: return load<std::int8_t>(b);
      case PlyType::UInt8: return load<std::uint8_t>(b);
      case PlyType::Int16: return load<std::int16_t>(b);
      case PlyType::UInt16: return load<std::uint16_t>(b);
      case PlyType::Int32: return load<std::int32_t>(b);
      case PlyType::UInt32: return load<std::uint32_t>(b);
      case PlyType::Float32: return load<float>(b);
      case PlyType::Float64: return load<double>(b);
    }
    return 0.0;
  }

  void skip_values(PlyType t, std::uint64_t count) {
    const std::uint64_t size = type_size(t);
    if (count > (size_ - pos_) / size) throw DataError{true, "truncated data"};
    pos_ += static_cast<std::size_t>(count * size);
  }

 private:
  void need(std::size_t n) const {
    if (size_ - pos_ < n) throw DataError{true, "truncated data"};
  }

  const unsigned char* data_;
  std::size_t size_;
  std::size_t pos_;
  bool swap_;
};

// Ascii data: one element per line, whitespace-separated values. A line
// holding fewer or more values than the header declares is an error, which
// catches headers that disagree with their data.
class AsciiCursor {
 public:
  AsciiCursor(const std::string& data, std::size_t offset, long header_lines)
      : data_(data), pos_(offset), line_(header_lines) {}

  long line() const { return line_; }

  void begin_element() {
    tokens_.clear();
    next_ = 0;
    while (tokens_.empty()) {
      if (pos_ >= data_.size()) throw DataError{true, "unexpected end of file"};
      std::size_t end = data_.find('\n', pos_);
      if (end == std::string::npos) end = data_.size();
      ++line_;
      tokenize(pos_, end);
      pos_ = end + 1;
    }
  }

  void end_element() const {
    if (next_ < tokens_.size())
      throw DataError{false, "the line has " + std::to_string(tokens_.size() - next_) +
                                 " more value(s) than the header declares"};
  }

  double value(PlyType t) {
    const Token& tok = take();
    if (is_integer(t)) return parse_integer(tok, t);
    // Round a float property to float, so ascii and binary files holding
    // the same declared values give bit-identical meshes.
    const double v = parse_real(tok);
    return t == PlyType::Float32 ? static_cast<double>(static_cast<float>(v)) : v;
  }

  void skip_values(PlyType /*t*/, std::uint64_t count) {
    if (count > tokens_.size() - next_) throw too_few();
    next_ += static_cast<std::size_t>(count);
  }

 private:
  struct Token {
    const char* begin;
    const char* end;
  };

  void tokenize(std::size_t begin, std::size_t end) {
    const char* p = data_.data() + begin;
    const char* stop = data_.data() + end;
    while (p < stop) {
      while (p < stop && std::isspace(static_cast<unsigned char>(*p))) ++p;
      const char* start = p;
      while (p < stop && !std::isspace(static_cast<unsigned char>(*p))) ++p;
      if (p > start) tokens_.push_back({start, p});
    }
  }

  static DataError too_few() {
    return DataError{false, "the line has fewer values than the header declares"};
  }

  const Token& take() {
    if (next_ >= tokens_.size()) throw too_few();
    return tokens_[next_++];
  }

  static double parse_integer(const Token& tok, PlyType t) {
    const char* first = tok.begin;
    if (first < tok.end && *first == '+') ++first;  // from_chars rejects '+'
    long long v = 0;
    auto [ptr, ec] = std::from_chars(first, tok.end, v);
    long long lo, hi;
    integer_range(t, &lo, &hi);
    if (ec != std::errc() || ptr != tok.end || v < lo || v > hi)
      throw DataError{false, "expected an integer in [" + std::to_string(lo) + ", " +
                                 std::to_string(hi) + "], got '" + std::string(tok.begin, tok.end) +
                                 "'"};
    return static_cast<double>(v);
  }

  // Accepts nan/inf: a NaN quality (e.g. an unobserved face's PRI) is data.
  static double parse_real(const Token& tok) {
    const char* first = tok.begin;
    if (first < tok.end && *first == '+') ++first;
    double v = 0.0;
    auto [ptr, ec] = std::from_chars(first, tok.end, v);
    // from_chars leaves v unset on overflow/underflow; strtod gives inf/0.
    if (ec == std::errc::result_out_of_range && ptr == tok.end)
      return std::strtod(std::string(first, tok.end).c_str(), nullptr);
    if (ec != std::errc() || ptr != tok.end)
      throw DataError{false, "expected a number, got '" + std::string(tok.begin, tok.end) + "'"};
    return v;
  }

  const std::string& data_;
  std::size_t pos_;
  long line_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
};

template <class Cursor>
std::uint64_t list_length(Cursor& c, const PlyProperty& p) {
  const double n = c.value(p.count_type);
  if (n < 0) throw DataError{false, "negative list length for '" + p.name + "'"};
  return static_cast<std::uint64_t>(n);
}

template <class Cursor>
void skip_property(Cursor& c, const PlyProperty& p) {
  if (p.is_list)
    c.skip_values(p.type, list_length(c, p));
  else
    c.skip_values(p.type, 1);
}

// --------------------------------------------------------------- roles ---

// What each property of an element is used for; decided once per element
// so that the per-element loop is a plain switch.
enum class Role { Skip, X, Y, Z, Indices, Attribute, Red, Green, Blue };

std::vector<Role> vertex_roles(const PlyElement& e, const std::string& path) {
  std::vector<Role> roles(e.properties.size(), Role::Skip);
  const char* names[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    bool found = false;
    for (std::size_t i = 0; i < e.properties.size(); ++i) {
      if (e.properties[i].name != names[k]) continue;
      if (e.properties[i].is_list)
        throw Error(std::string("vertex property '") + names[k] + "' must be a scalar, not a list",
                    path, e.line);
      roles[i] = static_cast<Role>(static_cast<int>(Role::X) + k);
      found = true;
    }
    if (!found)
      throw Error(std::string("vertex element has no '") + names[k] + "' property", path, e.line);
  }
  return roles;
}

// How the properties of the face element are used.
struct FaceLayout {
  std::vector<Role> roles;              // per property
  std::vector<std::size_t> slot;        // per property: attribute slot (Role::Attribute)
  std::vector<std::string> attributes;  // attribute names by slot
  bool has_colors = false;
};

// Scalar float/double face properties (and `quality` of any scalar type)
// become attributes, so every attribute write_ply stores reads back.
// Integer properties (flags, tags, ids) and colour channels do not.
bool is_attribute(const PlyProperty& p) {
  if (p.is_list) return false;
  if (p.name == "red" || p.name == "green" || p.name == "blue" || p.name == "alpha") return false;
  return p.name == "quality" || !is_integer(p.type);
}

FaceLayout face_layout(const PlyElement& e, const std::string& path) {
  FaceLayout layout;
  layout.roles.assign(e.properties.size(), Role::Skip);
  layout.slot.assign(e.properties.size(), 0);
  bool have_indices = false;
  int color_count = 0;
  for (std::size_t i = 0; i < e.properties.size(); ++i) {
    const PlyProperty& p = e.properties[i];
    Role& role = layout.roles[i];
    if ((p.name == "vertex_indices" || p.name == "vertex_index") && !have_indices) {
      if (!p.is_list || !is_integer(p.type))
        throw Error("face property '" + p.name + "' must be a list of integers", path, e.line);
      role = Role::Indices;
      have_indices = true;
    } else if (is_attribute(p)) {
      role = Role::Attribute;
      layout.slot[i] = layout.attributes.size();
      layout.attributes.push_back(p.name);
    } else if (!p.is_list && p.type == PlyType::UInt8 &&
               (p.name == "red" || p.name == "green" || p.name == "blue")) {
      role = p.name == "red" ? Role::Red : p.name == "green" ? Role::Green : Role::Blue;
      ++color_count;
    }
  }
  if (!have_indices && e.count > 0)
    throw Error("face element has no 'vertex_indices' list property", path, e.line);
  // Colours are only taken when all three channels are there.
  layout.has_colors = color_count == 3;
  if (!layout.has_colors)
    for (Role& r : layout.roles)
      if (r == Role::Red || r == Role::Green || r == Role::Blue) r = Role::Skip;
  return layout;
}

// -------------------------------------------------------------- reading ---

// Binary vertices can be 3 bytes (char x y z) but take 24 in memory: cap the
// up-front reservation so a lying header cannot make us reserve many times
// the file size; past the cap, vectors grow only with data actually read.
std::size_t reserve_hint(std::uint64_t count) {
  return static_cast<std::size_t>(std::min<std::uint64_t>(count, 1u << 20));
}

struct ReadContext {
  const std::string& path;
  std::size_t vertex_count;  // from the header, so faces may precede vertices
};

std::string element_name(const std::string& name, std::uint64_t i) {
  return name + " " + std::to_string(i);
}

// Runs `read_one(i)` for every element, turning cursor errors into messages
// that name the element and, on premature end, how many were read.
template <class Cursor, class Fn>
void for_each_element(Cursor& c, const PlyElement& e, const std::string& path, Fn read_one) {
  std::uint64_t i = 0;
  try {
    for (; i < e.count; ++i) {
      c.begin_element();
      read_one(i);
      c.end_element();
    }
  } catch (const DataError& err) {
    if (err.end_of_data)
      throw Error(err.reason + " (expected " + element_count(e.name, e.count) + ", got " +
                      std::to_string(i) + ")",
                  path, c.line(), element_name(e.name, i));
    throw Error(err.reason, path, c.line(), element_name(e.name, i));
  }
}

template <class Cursor>
void read_vertices(Cursor& c, const PlyElement& e, const ReadContext& ctx, TriangleMesh* mesh) {
  const std::vector<Role> roles = vertex_roles(e, ctx.path);
  mesh->vertices.reserve(reserve_hint(e.count));
  for_each_element(c, e, ctx.path, [&](std::uint64_t i) {
    Vec3 p = Vec3::Zero();
    for (std::size_t k = 0; k < roles.size(); ++k) {
      const PlyProperty& prop = e.properties[k];
      switch (roles[k]) {
        case Role::X: p.x() = c.value(prop.type); break;
        case Role::Y: p.y() = c.value(prop.type); break;
        case Role::Z: p.z() = c.value(prop.type); break;
        default: skip_property(c, prop); break;
      }
    }
    if (!p.allFinite())
      throw Error("coordinate is not finite (NaN or inf)", ctx.path, c.line(),
                  element_name("vertex", i));
    mesh->vertices.push_back(p);
  });
}

struct FaceRecord {
  std::vector<int> polygon;
  std::vector<float> values;  // by attribute slot
  Rgb8 color{0, 0, 0};
};

template <class Cursor>
void read_polygon(Cursor& c, const PlyProperty& prop, const ReadContext& ctx, std::uint64_t i,
                  std::vector<int>* polygon) {
  const std::uint64_t n = list_length(c, prop);
  if (n < 3)
    throw Error("polygon with " + std::to_string(n) + " vertices (at least 3 needed)", ctx.path,
                c.line(), element_name("face", i));
  polygon->clear();
  for (std::uint64_t k = 0; k < n; ++k) {
    const double index = c.value(prop.type);
    if (index < 0 || index >= static_cast<double>(ctx.vertex_count))
      throw Error("vertex index " + std::to_string(static_cast<long long>(index)) +
                      " out of range (the file has " + std::to_string(ctx.vertex_count) +
                      " vertices)",
                  ctx.path, c.line(), element_name("face", i));
    polygon->push_back(static_cast<int>(index));
  }
}

// Fan triangulation (v0, vk, vk+1); per-face values go to every triangle.
void add_polygon(const FaceRecord& r, bool has_colors, TriangleMesh* mesh,
                 std::vector<std::vector<float>>* attributes) {
  for (std::size_t k = 1; k + 1 < r.polygon.size(); ++k) {
    mesh->faces.push_back({r.polygon[0], r.polygon[k], r.polygon[k + 1]});
    for (std::size_t a = 0; a < r.values.size(); ++a) (*attributes)[a].push_back(r.values[a]);
    if (has_colors) mesh->face_colors.push_back(r.color);
  }
}

template <class Cursor>
void read_faces(Cursor& c, const PlyElement& e, const ReadContext& ctx, TriangleMesh* mesh) {
  const FaceLayout layout = face_layout(e, ctx.path);
  mesh->faces.reserve(reserve_hint(e.count));
  std::vector<std::vector<float>> attributes(layout.attributes.size());
  FaceRecord r;
  r.values.assign(layout.attributes.size(), 0.0f);
  for_each_element(c, e, ctx.path, [&](std::uint64_t i) {
    for (std::size_t k = 0; k < layout.roles.size(); ++k) {
      const PlyProperty& prop = e.properties[k];
      switch (layout.roles[k]) {
        case Role::Indices: read_polygon(c, prop, ctx, i, &r.polygon); break;
        case Role::Attribute:
          r.values[layout.slot[k]] = static_cast<float>(c.value(prop.type));
          break;
        case Role::Red: r.color[0] = static_cast<std::uint8_t>(c.value(prop.type)); break;
        case Role::Green: r.color[1] = static_cast<std::uint8_t>(c.value(prop.type)); break;
        case Role::Blue: r.color[2] = static_cast<std::uint8_t>(c.value(prop.type)); break;
        default: skip_property(c, prop); break;
      }
    }
    add_polygon(r, layout.has_colors, mesh, &attributes);
  });
  for (std::size_t a = 0; a < attributes.size(); ++a)
    mesh->face_attributes[layout.attributes[a]] = std::move(attributes[a]);
}

template <class Cursor>
void skip_element(Cursor& c, const PlyElement& e, const std::string& path) {
  if (e.properties.empty()) return;  // nothing to read, however large the count
  for_each_element(c, e, path, [&](std::uint64_t) {
    for (const PlyProperty& p : e.properties) skip_property(c, p);
  });
}

template <class Cursor>
TriangleMesh read_body(Cursor& c, const PlyHeader& h, const std::string& path) {
  ReadContext ctx{path, 0};
  for (const PlyElement& e : h.elements)
    if (e.name == "vertex") {
      if (e.count > static_cast<std::uint64_t>(std::numeric_limits<int>::max()))
        throw Error("too many vertices (" + std::to_string(e.count) + ")", path, e.line);
      ctx.vertex_count = static_cast<std::size_t>(e.count);
    }
  TriangleMesh mesh;
  for (const PlyElement& e : h.elements) {
    if (e.name == "vertex")
      read_vertices(c, e, ctx, &mesh);
    else if (e.name == "face")
      read_faces(c, e, ctx, &mesh);
    else
      skip_element(c, e, path);
  }
  return mesh;
}

// -------------------------------------------------------------- writing ---

template <class T>
void put_le(std::string* out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (!host_is_little_endian())
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  out->append(bytes, sizeof(T));
}

// Shortest text that reads back to the same value (locale-independent).
template <class T>
void put_text(std::string* out, T value) {
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof(buf), value);
  out->append(buf, res.ptr);
}

void check_writable(const TriangleMesh& mesh, const std::string& path) {
  mesh.validate(path);
  for (const auto& entry : mesh.face_attributes) {
    const std::string& name = entry.first;
    bool bad = name.empty() || name == "vertex_indices";
    for (char ch : name) bad = bad || std::isspace(static_cast<unsigned char>(ch)) || ch < 32;
    if (!mesh.face_colors.empty() && (name == "red" || name == "green" || name == "blue"))
      bad = true;
    if (bad)
      throw Error("face attribute name '" + name +
                      "' cannot be a PLY property name (empty, has spaces or clashes with "
                      "vertex_indices/red/green/blue)",
                  path);
  }
}

std::string header_text(const TriangleMesh& mesh, const PlyWriteOptions& options) {
  std::string h = "ply\nformat ";
  h += options.binary ? "binary_little_endian 1.0\n" : "ascii 1.0\n";
  if (!options.comment.empty()) {
    std::string comment = options.comment;
    for (char& ch : comment)
      if (ch == '\n' || ch == '\r') ch = ' ';  // a newline would end the comment line
    h += "comment " + comment + "\n";
  }
  for (std::string comment : options.comments) {
    for (char& ch : comment)
      if (ch == '\n' || ch == '\r') ch = ' ';
    h += "comment " + comment + "\n";
  }
  const char* coord = options.double_precision ? "double" : "float";
  h += "element vertex " + std::to_string(mesh.vertices.size()) + "\n";
  for (const char* axis : {"x", "y", "z"})
    h += std::string("property ") + coord + " " + axis + "\n";
  h += "element face " + std::to_string(mesh.faces.size()) + "\n";
  h += "property list uchar int vertex_indices\n";
  for (const auto& entry : mesh.face_attributes) h += "property float " + entry.first + "\n";
  if (!mesh.face_colors.empty())
    h += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  h += "end_header\n";
  return h;
}

void put_vertex(std::string* out, const Vec3& p, const PlyWriteOptions& options) {
  for (int k = 0; k < 3; ++k) {
    if (options.binary) {
      if (options.double_precision)
        put_le(out, p[k]);
      else
        put_le(out, static_cast<float>(p[k]));
    } else {
      if (k > 0) out->push_back(' ');
      if (options.double_precision)
        put_text(out, p[k]);
      else
        put_text(out, static_cast<float>(p[k]));
    }
  }
  if (!options.binary) out->push_back('\n');
}

void put_face(std::string* out, const TriangleMesh& mesh, std::size_t f, bool binary) {
  if (binary) {
    put_le(out, static_cast<std::uint8_t>(3));
    for (int v : mesh.faces[f]) put_le(out, static_cast<std::int32_t>(v));
    for (const auto& entry : mesh.face_attributes) put_le(out, entry.second[f]);
    if (!mesh.face_colors.empty())
      for (std::uint8_t ch : mesh.face_colors[f]) put_le(out, ch);
    return;
  }
  out->push_back('3');
  for (int v : mesh.faces[f]) {
    out->push_back(' ');
    put_text(out, v);
  }
  for (const auto& entry : mesh.face_attributes) {
    out->push_back(' ');
    put_text(out, entry.second[f]);
  }
  if (!mesh.face_colors.empty())
    for (std::uint8_t ch : mesh.face_colors[f]) {
      out->push_back(' ');
      put_text(out, static_cast<int>(ch));
    }
  out->push_back('\n');
}

// Streams the body in chunks so that a large mesh needs no second copy.
void write_body(std::ostream& os, const TriangleMesh& mesh, const PlyWriteOptions& options) {
  constexpr std::size_t kChunk = 1 << 20;
  std::string buf;
  auto flush = [&](std::size_t at_least) {
    if (buf.size() < at_least) return;
    os.write(buf.data(), static_cast<std::streamsize>(buf.size()));
    buf.clear();
  };
  for (const Vec3& p : mesh.vertices) {
    put_vertex(&buf, p, options);
    flush(kChunk);
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    put_face(&buf, mesh, f, options.binary);
    flush(kChunk);
  }
  flush(0);
}

// Float coordinates would lose the mesh: a coordinate beyond float's range
// would be written as inf, and far from the origin (georeferenced meshes,
// coordinates ~1e6) rounding to float moves vertices by centimetres. Double
// when rounding would move any vertex by more than 1e-6 of the bounding-box
// diagonal.
bool needs_double(const TriangleMesh& mesh, bool exact) {
  if (mesh.vertices.empty()) return false;
  const double tolerance = exact ? 0.0 : 1e-6 * mesh.bounding_box().diagonal();
  for (const Vec3& p : mesh.vertices) {
    if (p.cwiseAbs().maxCoeff() > std::numeric_limits<float>::max()) return true;
    double moved2 = 0;
    for (int k = 0; k < 3; ++k) {
      volatile float rounded = static_cast<float>(p[k]);  // not folded away (see test_mesh_io)
      const double d = double(rounded) - p[k];
      moved2 += d * d;
    }
    if (!(std::sqrt(moved2) <= tolerance)) return true;
  }
  return false;
}

}  // namespace

TriangleMesh read_ply(const std::string& path) { return read_ply_with_info(path, nullptr); }

TriangleMesh read_ply_with_info(const std::string& path, PlyFileInfo* info) {
  const std::string data = read_file(path);
  const PlyHeader header = HeaderParser(data, path).parse();
  if (info) {
    info->comments = header.comments;
    info->coordinates = PlyCoordinateType::Float64;
    for (const PlyElement& e : header.elements) {
      if (e.name != "vertex") continue;
      for (const PlyProperty& p : e.properties) {
        if (p.is_list || (p.name != "x" && p.name != "y" && p.name != "z")) continue;
        if (is_integer(p.type))
          info->coordinates = PlyCoordinateType::Integer;
        else if (p.type == PlyType::Float32 && info->coordinates == PlyCoordinateType::Float64)
          info->coordinates = PlyCoordinateType::Float32;
      }
    }
  }
  check_counts_fit(header, data.size() - header.data_offset, path);
  TriangleMesh mesh;
  if (header.format == PlyFormat::Ascii) {
    AsciiCursor cursor(data, header.data_offset, header.lines);
    mesh = read_body(cursor, header, path);
  } else {
    BinaryCursor cursor(data, header.data_offset, header.format == PlyFormat::BinaryBigEndian);
    mesh = read_body(cursor, header, path);
  }
  mesh.validate(path);
  return mesh;
}

void write_ply(const TriangleMesh& mesh, const std::string& path, const PlyWriteOptions& requested) {
  check_can_write(path, requested.overwrite);
  check_writable(mesh, path);
  PlyWriteOptions options = requested;
  if (!options.double_precision) options.double_precision = needs_double(mesh, options.exact_coordinates);
  write_atomically(
      path,
      [&](std::ostream& os) {
        os << header_text(mesh, options);
        write_body(os, mesh, options);
      },
      options.overwrite, options.binary);
}

}  // namespace meshnbv::io
