// Mesh readers and writer: PLY (ascii, binary both endians), OBJ, OFF.
//
// The reference shape is a square pyramid: base corners v0 (0,0,0),
// v1 (1,0,0), v2 (1,1,0), v3 (0,1,0), apex v4 (0.5,0.5,1); the base is the
// quad (0,3,2,1), fan-triangulated into (0,3,2) and (0,2,1), followed by the
// four sides (0,1,4) (1,2,4) (2,3,4) (3,0,4). The files in data/meshes hold
// it in every format, so all readers must give the same six triangles.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "meshnbv/error.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/pri_io.h"
#include "meshnbv/mesh.h"
#include "test_util.h"

using namespace meshnbv;
namespace fs = std::filesystem;

namespace {

const std::vector<Face> kPyramidFaces = {{0, 3, 2}, {0, 2, 1}, {0, 1, 4},
                                         {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};

std::string mesh_file(const std::string& name) { return test::data_dir() + "/meshes/" + name; }
std::string bad_file(const std::string& name) { return test::data_dir() + "/bad/" + name; }

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  ASSERT_TRUE(out.good()) << path;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void expect_pyramid_geometry(const TriangleMesh& m) {
  ASSERT_EQ(m.num_vertices(), 5u);
  EXPECT_EQ(m.vertices[0], Vec3(0, 0, 0));
  EXPECT_EQ(m.vertices[2], Vec3(1, 1, 0));
  EXPECT_EQ(m.vertices[4], Vec3(0.5, 0.5, 1));
  EXPECT_EQ(m.faces, kPyramidFaces);
}

// Coordinates that float cannot hold exactly (so float vs double shows),
// attributes besides `quality` (every attribute must come back), a NaN (an
// unobserved face's PRI must survive) and values that need all 9
// significant digits of a float.
TriangleMesh sample_mesh() {
  TriangleMesh m;
  m.vertices = {Vec3(0.1, 0.2, 0.3), Vec3(1.0 / 3.0, -2.5, 1e-7), Vec3(-1e5, 7.25, 2.0 / 7.0),
                Vec3(12345.678901, -0.000123, 9.87654321)};
  m.faces = {{0, 1, 2}, {0, 2, 3}, {3, 2, 1}};
  m.face_attributes["quality"] = {0.125f, 1.0f / 3.0f, 1e20f};
  m.face_attributes["pri"] = {std::numeric_limits<float>::quiet_NaN(), 2e-8f, -3.5f};
  m.face_attributes["pri_views"] = {0, 2, 7};
  m.face_colors = {Rgb8{255, 0, 7}, Rgb8{0, 128, 255}, Rgb8{1, 2, 3}};
  return m;
}

void expect_round_trip(const TriangleMesh& in, const TriangleMesh& out, bool exact) {
  ASSERT_EQ(out.num_vertices(), in.num_vertices());
  for (std::size_t v = 0; v < in.num_vertices(); ++v) {
    // Float files hold exactly the float nearest to each coordinate. The
    // rounding goes through a volatile: GCC 12.2 at -O2 drops a pair of
    // adjacent in-place double->float->double roundings (SLP vectoriser).
    Vec3 expected = in.vertices[v];
    for (int k = 0; k < 3 && !exact; ++k) {
      volatile float rounded = static_cast<float>(expected[k]);
      expected[k] = rounded;
    }
    EXPECT_EQ(out.vertices[v], expected) << "vertex " << v;
  }
  if (!exact) {
    EXPECT_NE(out.vertices[0].x(), 0.1) << "0.1 has no exact float: the file must hold floats";
  }
  EXPECT_EQ(out.faces, in.faces);
  ASSERT_EQ(out.face_attributes.size(), in.face_attributes.size());
  for (const auto& [name, values] : in.face_attributes) {
    const std::vector<float>* read = out.face_attribute(name);
    ASSERT_NE(read, nullptr) << name;
    ASSERT_EQ(read->size(), values.size());
    for (std::size_t f = 0; f < values.size(); ++f) {
      if (std::isnan(values[f]))
        EXPECT_TRUE(std::isnan((*read)[f])) << name << " face " << f;
      else
        EXPECT_EQ((*read)[f], values[f]) << name << " face " << f;  // float attributes: exact
    }
  }
  EXPECT_EQ(out.face_colors, in.face_colors);
}

void round_trip(const std::string& test_name, bool binary, bool double_precision) {
  const std::string path = test::temp_dir(test_name) + "/mesh.ply";
  const TriangleMesh in = sample_mesh();
  io::PlyWriteOptions options;
  options.binary = binary;
  options.double_precision = double_precision;
  io::write_ply(in, path, options);
  expect_round_trip(in, io::read_ply(path), double_precision);
}

// Builds binary PLY bodies of either byte order.
class Bytes {
 public:
  explicit Bytes(bool big_endian) : big_endian_(big_endian) {}
  template <class T>
  Bytes& put(T value) {
    char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    const std::uint16_t one = 1;
    const bool host_little = *reinterpret_cast<const unsigned char*>(&one) == 1;
    if (big_endian_ == host_little)
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    bytes_.append(b, sizeof(T));
    return *this;
  }
  const std::string& str() const { return bytes_; }

 private:
  bool big_endian_;
  std::string bytes_;
};

const char* kTriangleHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

}  // namespace

// ------------------------------------------------------------ PLY: writes ---

TEST(PlyIo, RoundTripBinaryFloatWithQualityAndColor) {
  round_trip("PlyIo.RoundTripBinaryFloat", true, false);
}

TEST(PlyIo, RoundTripBinaryDoubleIsExact) { round_trip("PlyIo.RoundTripBinaryDouble", true, true); }

TEST(PlyIo, RoundTripAsciiFloatWithQualityAndColor) {
  round_trip("PlyIo.RoundTripAsciiFloat", false, false);
}

TEST(PlyIo, RoundTripAsciiDoubleIsExact) { round_trip("PlyIo.RoundTripAsciiDouble", false, true); }

TEST(PlyIo, RoundTripWithoutAttributesAddsNone) {
  const std::string path = test::temp_dir("PlyIo.NoAttributes") + "/mesh.ply";
  TriangleMesh in = sample_mesh();
  in.face_attributes.clear();
  in.face_colors.clear();
  io::write_ply(in, path);
  const TriangleMesh out = io::read_ply(path);
  EXPECT_TRUE(out.face_attributes.empty());
  EXPECT_TRUE(out.face_colors.empty());
  EXPECT_EQ(out.faces, in.faces);
}

// MeshLab reads face quality only from a float property named `quality`
// and colours from uchar red/green/blue after vertex_indices.
TEST(PlyIo, WrittenHeaderIsMeshLabCompatible) {
  const std::string path = test::temp_dir("PlyIo.Header") + "/mesh.ply";
  io::PlyWriteOptions options;
  options.comment = "two\nlines";
  io::write_ply(sample_mesh(), path, options);
  const std::string text = slurp(path);
  const std::string header = text.substr(0, text.find("end_header\n") + 11);
  EXPECT_EQ(
      header,
      "ply\nformat binary_little_endian 1.0\ncomment two lines\nelement vertex 4\n"
      "property float x\nproperty float y\nproperty float z\nelement face 3\n"
      "property list uchar int vertex_indices\nproperty float pri\n"
      "property float pri_views\nproperty float quality\nproperty uchar red\nproperty uchar green\n"
      "property uchar blue\nend_header\n");
  // 4 vertices * 12 bytes + 3 faces * (1 + 12 + 3 * 4 + 3) bytes.
  EXPECT_EQ(text.size(), header.size() + 4 * 12 + 3 * 28);
}

TEST(PlyIo, AsciiWriteHasOneElementPerLine) {
  const std::string path = test::temp_dir("PlyIo.AsciiLines") + "/mesh.ply";
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1.5, 0, 0), Vec3(0, 2, 0)};
  m.faces = {{0, 1, 2}};
  m.face_attributes["quality"] = {0.5f};
  io::PlyWriteOptions options;
  options.binary = false;
  options.comment.clear();
  io::write_ply(m, path, options);
  const std::string text = slurp(path);
  EXPECT_EQ(text.substr(text.find("end_header\n") + 11), "0 0 0\n1.5 0 0\n0 2 0\n3 0 1 2 0.5\n");
}

TEST(PlyIo, OverwriteFalseRefusesExistingFile) {
  const std::string path = test::temp_dir("PlyIo.NoOverwrite") + "/mesh.ply";
  write_file(path, "keep me");
  io::PlyWriteOptions options;
  options.overwrite = false;
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_ply(sample_mesh(), path, options), "output exists");
  EXPECT_EQ(slurp(path), "keep me");
}

TEST(PlyIo, OverwriteTrueReplacesExistingFile) {
  const std::string path = test::temp_dir("PlyIo.Overwrite") + "/mesh.ply";
  write_file(path, "old");
  io::write_ply(sample_mesh(), path);
  EXPECT_EQ(io::read_ply(path).num_faces(), 3u);
}

TEST(PlyIo, InvalidMeshIsNotWrittenAndLeavesNoFile) {
  const std::string dir = test::temp_dir("PlyIo.FailedWrite");
  const std::string path = dir + "/mesh.ply";
  TriangleMesh m = sample_mesh();
  m.face_attributes["quality"].pop_back();  // 2 values for 3 faces
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_ply(m, path), "'quality' has 2 values for 3 faces");
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(dir)) << "no temporary file may be left behind";
}

TEST(PlyIo, UnwritableLocationLeavesNoFile) {
  const std::string dir = test::temp_dir("PlyIo.Unwritable");
  write_file(dir + "/not_a_folder", "x");  // a file where a folder is needed
  const std::string path = dir + "/not_a_folder/mesh.ply";
  EXPECT_THROW(io::write_ply(sample_mesh(), path), Error);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(PlyIo, RejectsAttributeNameThatIsNotAPropertyName) {
  const std::string path = test::temp_dir("PlyIo.BadName") + "/mesh.ply";
  TriangleMesh m = sample_mesh();
  m.face_attributes["my quality"] = {1, 2, 3};
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_ply(m, path), "'my quality'");
  EXPECT_FALSE(fs::exists(path));
}

TEST(PlyIo, RejectsNonFiniteVertexOnWrite) {
  const std::string path = test::temp_dir("PlyIo.NaNWrite") + "/mesh.ply";
  TriangleMesh m = sample_mesh();
  m.vertices[2].y() = std::numeric_limits<double>::infinity();
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_ply(m, path), "vertex 2");
  EXPECT_FALSE(fs::exists(path));
}

// A georeferenced mesh: a 10 m building at (1e6, 2e6, 500). Float holds
// these coordinates to 0.0625 m (x) and 0.125 m (y), far more than 1e-6 of
// the diagonal, so write_ply stores double even when float was asked for,
// and the mesh reads back exactly in both encodings.
TriangleMesh far_from_origin_mesh() {
  TriangleMesh m = sample_mesh();
  m.vertices = {Vec3(0.1, 0.2, 0.3), Vec3(1.0 / 3.0, -2.5, 1e-7), Vec3(-7.0, 7.25, 2.0 / 7.0),
                Vec3(3.123456789, -0.000123, 9.87654321)};
  for (Vec3& v : m.vertices) v += Vec3(1e6, 2e6, 500);
  return m;
}

TEST(PlyIo, FarFromOriginMeshIsWrittenInDoubleAndReadsBackExactly) {
  const std::string dir = test::temp_dir("PlyIo.FarFromOrigin");
  const TriangleMesh in = far_from_origin_mesh();
  for (bool binary : {true, false}) {
    const std::string path = dir + (binary ? "/binary.ply" : "/ascii.ply");
    io::PlyWriteOptions options;
    options.binary = binary;
    ASSERT_FALSE(options.double_precision);  // float asked for
    io::write_ply(in, path, options);
    const std::string text = slurp(path);
    EXPECT_NE(text.find("property double x\nproperty double y\nproperty double z\n"),
              std::string::npos)
        << "binary " << binary;
    io::PlyFileInfo info;
    const TriangleMesh out = io::read_ply_with_info(path, &info);
    EXPECT_EQ(info.coordinates, io::PlyCoordinateType::Float64);
    expect_round_trip(in, out, /*exact=*/true);
  }
}

TEST(PlyIo, FloatIsKeptWhereItMovesNoVertexBeyondAMillionthOfTheDiagonal) {
  const std::string dir = test::temp_dir("PlyIo.FloatKept");
  // sample_mesh: diagonal ~1e5, float moves its vertices by < 0.001.
  io::write_ply(sample_mesh(), dir + "/near.ply");
  io::PlyFileInfo info;
  io::read_ply_with_info(dir + "/near.ply", &info);
  EXPECT_EQ(info.coordinates, io::PlyCoordinateType::Float32);
  // A 1 mm object 1 m from the origin: float's 6e-8 steps are 6e-5 of its
  // diagonal, so double.
  TriangleMesh small;
  small.vertices = {Vec3(1.0001, 1, 1), Vec3(1.0, 1.0007, 1), Vec3(1.0003, 1.0002, 1.0009)};
  small.faces = {{0, 1, 2}};
  io::write_ply(small, dir + "/small.ply");
  const TriangleMesh back = io::read_ply_with_info(dir + "/small.ply", &info);
  EXPECT_EQ(info.coordinates, io::PlyCoordinateType::Float64);
  EXPECT_EQ(back.vertices, small.vertices);
}

// read_pri_for_mesh (meshnbv suggest --pri): the PRI comes from the file,
// the mesh stays the caller's, and another mesh is refused.
TEST(PriFile, QualityIsReadForTheSameMeshAtTheFilesPrecision) {
  const std::string dir = test::temp_dir("PriFile.SameMesh");
  const TriangleMesh mesh = sample_mesh();  // not float-exact, written as float
  io::PlyWriteOptions options;
  io::write_ply(mesh, dir + "/pri.ply", options);
  const std::vector<float> pri = io::read_pri_for_mesh(dir + "/pri.ply", mesh);
  ASSERT_EQ(pri.size(), 3u);
  EXPECT_EQ(pri[0], 0.125f);
  EXPECT_EQ(pri[2], 1e20f);
  // Far from the origin the file is double, and must match to double.
  const TriangleMesh far = far_from_origin_mesh();
  io::write_ply(far, dir + "/far.ply", options);
  EXPECT_EQ(io::read_pri_for_mesh(dir + "/far.ply", far).size(), 3u);
  TriangleMesh moved = far;
  moved.vertices[3].x() += 1e-6;  // within float precision, not within double's
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_pri_for_mesh(dir + "/far.ply", moved),
                                "vertex 3 is at");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_pri_for_mesh(dir + "/far.ply", moved), "different mesh");
}

TEST(PriFile, AnotherMeshIsRefused) {
  const std::string dir = test::temp_dir("PriFile.OtherMesh");
  const TriangleMesh mesh = sample_mesh();
  io::write_ply(mesh, dir + "/pri.ply");
  TriangleMesh moved = mesh;
  moved.vertices[1].y() += 1e-3;  // beyond float precision at 2.5
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_pri_for_mesh(dir + "/pri.ply", moved),
                                "further apart than the file's float precision");
  TriangleMesh fewer = mesh;
  fewer.faces.pop_back();
  for (auto& [name, values] : fewer.face_attributes) values.pop_back();
  fewer.face_colors.pop_back();
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_pri_for_mesh(dir + "/pri.ply", fewer),
                                "the PRI mesh has 4 vertices and 3 faces, the scene's mesh 4 and 2");
  TriangleMesh flipped = mesh;
  std::swap(flipped.faces[0][1], flipped.faces[0][2]);
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_pri_for_mesh(dir + "/pri.ply", flipped), "face 0");
  TriangleMesh no_quality = mesh;
  no_quality.face_attributes.erase("quality");
  io::write_ply(no_quality, dir + "/plain.ply");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_pri_for_mesh(dir + "/plain.ply", mesh), "no per-face 'quality'");
}

// ------------------------------------------------------------- PLY: reads ---

TEST(PlyIo, ReadsAsciiWithUnknownPropertiesAndElements) {
  const TriangleMesh m = io::read_ply(mesh_file("pyramid.ply"));
  expect_pyramid_geometry(m);
  const std::vector<float> quality = {0.25f, 0.25f, 0.5f, 0.75f, 1.5f, -2.0f};
  ASSERT_NE(m.face_attribute("quality"), nullptr);
  EXPECT_EQ(*m.face_attribute("quality"), quality);
  EXPECT_EQ(m.face_attributes.size(), 1u) << "the int `tag` property is not an attribute";
  const std::vector<Rgb8> colors = {{255, 0, 0}, {255, 0, 0},  {0, 255, 0},
                                    {0, 0, 255}, {10, 20, 30}, {40, 50, 60}};
  EXPECT_EQ(m.face_colors, colors);
}

// Header: vertex (double x, float y, short z), face (ushort-counted uint
// indices, double quality, rgb): every byte width swapped.
TEST(PlyIo, ReadsBigEndianBinary) {
  const std::string path = test::temp_dir("PlyIo.BigEndian") + "/mesh.ply";
  Bytes body(true);
  body.put(0.1).put(2.5f).put(std::int16_t(-300));
  body.put(1e10).put(-0.75f).put(std::int16_t(7));
  body.put(-2.0).put(1.0f).put(std::int16_t(32767));
  body.put(std::uint16_t(3)).put(std::uint32_t(2)).put(std::uint32_t(1)).put(std::uint32_t(0));
  body.put(0.375).put(std::uint8_t(9)).put(std::uint8_t(8)).put(std::uint8_t(7));
  write_file(path,
             "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\n"
             "property float32 y\nproperty int16 z\nelement face 1\n"
             "property list uint16 uint32 vertex_indices\nproperty float64 quality\n"
             "property uint8 red\nproperty uint8 green\nproperty uint8 blue\nend_header\n" +
                 body.str());
  const TriangleMesh m = io::read_ply(path);
  ASSERT_EQ(m.num_vertices(), 3u);
  EXPECT_EQ(m.vertices[0], Vec3(0.1, 2.5, -300));
  EXPECT_EQ(m.vertices[1], Vec3(1e10, -0.75, 7));
  EXPECT_EQ(m.vertices[2], Vec3(-2, 1, 32767));
  EXPECT_EQ(m.faces, (std::vector<Face>{{2, 1, 0}}));
  EXPECT_EQ(*m.face_attribute("quality"), std::vector<float>{0.375f});
  EXPECT_EQ(m.face_colors, std::vector<Rgb8>{(Rgb8{9, 8, 7})});
}

// An unknown element with list properties comes first, the vertex carries
// extra scalar and list properties, the face list is named `vertex_index`
// and is followed by a list, a non-uchar `red` and an int (all skipped) and
// a double (read as an attribute of its name).
TEST(PlyIo, ReadsBinaryWithUnknownPropertiesAndElements) {
  const std::string path = test::temp_dir("PlyIo.BinaryUnknown") + "/mesh.ply";
  Bytes b(false);
  b.put(std::uint8_t(2)).put(std::int16_t(5)).put(std::int16_t(6)).put(std::int8_t(-1));
  b.put(std::uint8_t(0)).put(std::int8_t(4));
  const double xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (int v = 0; v < 4; ++v) {
    b.put(std::uint32_t(1000 + v)).put(float(xyz[v][0])).put(float(xyz[v][1]));
    b.put(std::int32_t(v)).put(std::uint8_t(v));  // list of v shorts
    for (int k = 0; k < v; ++k) b.put(std::int16_t(k));
    b.put(float(xyz[v][2]));
  }
  b.put(std::uint8_t(4)).put(0).put(3).put(2).put(1);
  b.put(std::uint32_t(2)).put(1.5).put(2.5).put(std::uint16_t(300));
  b.put(std::int32_t(-7)).put(0.0625);
  write_file(path,
             "ply\nformat binary_little_endian 1.0\ncomment unknown things everywhere\n"
             "element camera 2\nproperty list uchar short samples\nproperty char flag\n"
             "element vertex 4\nproperty uint id\nproperty float x\nproperty float y\n"
             "property int tag\nproperty list uint8 int16 ring\nproperty float z\n"
             "element face 1\nproperty list uchar int vertex_index\n"
             "property list uint double weights\nproperty ushort red\nproperty int flags\n"
             "property double gt_error\nend_header\n" +
                 b.str());
  const TriangleMesh m = io::read_ply(path);
  ASSERT_EQ(m.num_vertices(), 4u);
  EXPECT_EQ(m.vertices[2], Vec3(1, 1, 0));
  EXPECT_EQ(m.vertices[3], Vec3(0, 1, 0));
  EXPECT_EQ(m.faces, (std::vector<Face>{{0, 3, 2}, {0, 2, 1}}));
  EXPECT_TRUE(m.face_colors.empty()) << "a ushort `red` alone is not a colour";
  EXPECT_EQ(m.face_attributes.size(), 1u) << "integer properties are not attributes";
  EXPECT_EQ(*m.face_attribute("gt_error"), (std::vector<float>{0.0625f, 0.0625f}));
}

TEST(PlyIo, TriangulatesQuadsAndPentagonsAsFans) {
  const std::string path = test::temp_dir("PlyIo.Polygons") + "/mesh.ply";
  write_file(path,
             "ply\nformat ascii 1.0\nelement vertex 6\nproperty double x\nproperty double y\n"
             "property double z\nelement face 3\nproperty list uchar int vertex_indices\n"
             "property float quality\nend_header\n"
             "0 0 0\n1 0 0\n2 1 0\n1 2 0\n0 1 0\n1 1 1\n"
             "5 0 1 2 3 4 0.5\n4 0 1 5 4 1.5\n3 1 2 5 -1\n");
  const TriangleMesh m = io::read_ply(path);
  EXPECT_EQ(m.faces,
            (std::vector<Face>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 1, 5}, {0, 5, 4}, {1, 2, 5}}));
  EXPECT_EQ(*m.face_attribute("quality"),
            (std::vector<float>{0.5f, 0.5f, 0.5f, 1.5f, 1.5f, -1.0f}));
}

TEST(PlyIo, AcceptsCrLfLineEndings) {
  const std::string path = test::temp_dir("PlyIo.CrLf") + "/mesh.ply";
  std::string text = std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  write_file(path, crlf);
  const TriangleMesh m = io::read_ply(path);
  EXPECT_EQ(m.vertices[1], Vec3(1, 0, 0));
  EXPECT_EQ(m.faces, (std::vector<Face>{{0, 1, 2}}));
}

// ------------------------------------------------------- PLY: bad input ---

TEST(PlyIo, MissingFile) {
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(test::data_dir() + "/meshes/nope.ply"),
                                "nope.ply: file not found");
}

TEST(PlyIo, TruncatedBinaryNamesCounts) {
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(bad_file("truncated_binary.ply")),
                                "face 1: truncated data (expected 2 faces, got 1)");
}

TEST(PlyIo, TruncatedAsciiNamesLineAndCounts) {
  const std::string path = test::temp_dir("PlyIo.TruncatedAscii") + "/mesh.ply";
  // Long numbers, so the size check (2 bytes per value) lets it through.
  write_file(path, std::string(kTriangleHeader) + "0.000000 0.000000 0.000000\n1.000000 0 0\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(path),
                                "vertex 2: unexpected end of file (expected 3 vertices, got 2)");
}

TEST(PlyIo, ShortAsciiFileFailsTheSizeCheck) {
  const std::string path = test::temp_dir("PlyIo.ShortAscii") + "/mesh.ply";
  write_file(path, std::string(kTriangleHeader) + "0 0 0\n1 0 0\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(
      io::read_ply(path),
      ":3: header declares 3 vertices (at least 6 bytes each) but only 12 "
      "bytes of data remain");
}

TEST(PlyIo, FaceIndexOutOfRange) {
  MESHNBV_EXPECT_ERROR_CONTAINS(
      io::read_ply(bad_file("face_index_out_of_range.ply")),
      ":14: face 1: vertex index 7 out of range (the file has 3 vertices)");
}

TEST(PlyIo, NegativeFaceIndexInBinary) {
  const std::string path = test::temp_dir("PlyIo.NegativeIndex") + "/mesh.ply";
  Bytes b(false);
  for (int k = 0; k < 9; ++k) b.put(float(k));
  b.put(std::uint8_t(3)).put(0).put(-1).put(2);
  std::string header = kTriangleHeader;
  header.replace(header.find("ascii"), 5, "binary_little_endian");
  write_file(path, header + b.str());
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(path), "face 0: vertex index -1 out of range");
}

TEST(PlyIo, NaNVertexInAscii) {
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(bad_file("nan_vertex.ply")),
                                ":12: vertex 2: coordinate is not finite");
}

TEST(PlyIo, InfVertexInBinary) {
  const std::string path = test::temp_dir("PlyIo.InfVertex") + "/mesh.ply";
  Bytes b(false);
  b.put(0.f).put(0.f).put(0.f).put(1.f).put(std::numeric_limits<float>::infinity()).put(0.f);
  b.put(0.f).put(1.f).put(0.f).put(std::uint8_t(3)).put(0).put(1).put(2);
  std::string header = kTriangleHeader;
  header.replace(header.find("ascii"), 5, "binary_little_endian");
  write_file(path, header + b.str());
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(path), "vertex 1: coordinate is not finite");
}

// 10^12 vertices would need 12 TB; the reader must refuse before reserving.
TEST(PlyIo, HugeDeclaredVertexCountIsRejectedBeforeAllocating) {
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(bad_file("huge_vertex_count.ply")),
                                ":4: header declares 1000000000000 vertices (at least 12 bytes "
                                "each) but only 0 bytes");
}

TEST(PlyIo, HugeDeclaredFaceCountInAscii) {
  const std::string path = test::temp_dir("PlyIo.HugeFaces") + "/mesh.ply";
  std::string text = std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  text.replace(text.find("face 1"), 6, "face 4000000000");
  write_file(path, text);
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(path),
                                ":7: header declares 4000000000 faces (at least 2 bytes each)");
}

TEST(PlyIo, MalformedHeaderUnknownType) {
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(bad_file("malformed_header.ply")),
                                ":6: malformed PLY header: unknown property type 'quaternion'");
}

TEST(PlyIo, MalformedHeaderPropertyBeforeElement) {
  const std::string path = test::temp_dir("PlyIo.PropertyFirst") + "/mesh.ply";
  write_file(path, "ply\nformat ascii 1.0\nproperty float x\nend_header\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(path), ":3: malformed PLY header: 'property' before");
}

TEST(PlyIo, MalformedHeaderMissingEndHeader) {
  const std::string path = test::temp_dir("PlyIo.NoEnd") + "/mesh.ply";
  write_file(path, "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(path), "no 'end_header'");
}

TEST(PlyIo, MalformedHeaderMissingCoordinate) {
  const std::string path = test::temp_dir("PlyIo.NoZ") + "/mesh.ply";
  std::string text = std::string(kTriangleHeader) + "0 0\n1 0\n0 1\n3 0 1 2\n";
  text.erase(text.find("property float z\n"), 17);
  write_file(path, text);
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(path), ":3: vertex element has no 'z' property");
}

TEST(PlyIo, WrongMagic) {
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(bad_file("wrong_magic.ply")),
                                ":1: not a PLY file: the first line must be 'ply'");
}

TEST(PlyIo, FaceWithTwoVertices) {
  const std::string path = test::temp_dir("PlyIo.TwoVertexFace") + "/mesh.ply";
  write_file(path, std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(path),
                                ":13: face 0: polygon with 2 vertices (at least 3 needed)");
}

TEST(PlyIo, AsciiLineWithTooFewValues) {
  const std::string path = test::temp_dir("PlyIo.ShortLine") + "/mesh.ply";
  write_file(path, std::string(kTriangleHeader) + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(path), ":11: vertex 1: the line has fewer values");
}

TEST(PlyIo, AsciiLineWithTooManyValues) {
  const std::string path = test::temp_dir("PlyIo.LongLine") + "/mesh.ply";
  write_file(path, std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 9\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(path), ":13: face 0: the line has 1 more value");
}

TEST(PlyIo, AsciiValueNotANumber) {
  const std::string path = test::temp_dir("PlyIo.NotANumber") + "/mesh.ply";
  write_file(path, std::string(kTriangleHeader) + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_ply(path), ":11: vertex 1: expected a number, got 'zero'");
}

// ------------------------------------------------------------------- OBJ ---

TEST(ObjIo, ReadsQuadsAndMultipleObjects) {
  const TriangleMesh m = io::read_obj(mesh_file("pyramid.obj"));
  expect_pyramid_geometry(m);
  EXPECT_TRUE(m.face_attributes.empty());
  EXPECT_TRUE(m.face_colors.empty());
}

TEST(ObjIo, TriangulatesPentagonAsFan) {
  const std::string path = test::temp_dir("ObjIo.Pentagon") + "/mesh.obj";
  write_file(path, "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 1 2 3 4 5\n");
  EXPECT_EQ(io::read_obj(path).faces, (std::vector<Face>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}));
}

TEST(ObjIo, MissingFile) {
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_obj(test::data_dir() + "/meshes/nope.obj"),
                                "nope.obj: file not found");
}

TEST(ObjIo, FaceIndexOutOfRange) {
  const std::string path = test::temp_dir("ObjIo.OutOfRange") + "/mesh.obj";
  write_file(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_obj(path),
                                "face 1: vertex index 9 (1-based) out of range (the file has 3");
}

TEST(ObjIo, NegativeIndexBeforeFirstVertex) {
  const std::string path = test::temp_dir("ObjIo.Negative") + "/mesh.obj";
  write_file(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_obj(path), "face 0: a relative (negative) vertex index");
}

TEST(ObjIo, ZeroIndexNamesTheLine) {
  const std::string path = test::temp_dir("ObjIo.Zero") + "/mesh.obj";
  write_file(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  try {
    io::read_obj(path);
    ADD_FAILURE() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.line(), 4);
    EXPECT_NE(std::string(e.what()).find("invalid OBJ"), std::string::npos) << e.what();
  }
}

TEST(ObjIo, FaceWithTwoVerticesNamesTheLine) {
  const std::string path = test::temp_dir("ObjIo.TwoVertices") + "/mesh.obj";
  write_file(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n# comment\nf 1 2\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_obj(path), ":6: face with fewer than 3 vertices");
}

// ------------------------------------------------------------------- OFF ---

TEST(OffIo, ReadsOffWithCommentsAndQuad) {
  expect_pyramid_geometry(io::read_off(mesh_file("pyramid.off")));
}

TEST(OffIo, ReadsCoffWithColourColumnsAndCountsOnKeywordLine) {
  const std::string path = test::temp_dir("OffIo.Coff") + "/mesh.off";
  write_file(path,
             "COFF 4 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n"
             "0 1 0 9 9 9 255\n3 0 1 2 0.5 0.5 0.5 1\n3 0 2 3\n");
  const TriangleMesh m = io::read_off(path);
  ASSERT_EQ(m.num_vertices(), 4u);
  EXPECT_EQ(m.vertices[3], Vec3(0, 1, 0));
  EXPECT_EQ(m.faces, (std::vector<Face>{{0, 1, 2}, {0, 2, 3}}));
}

TEST(OffIo, HugeDeclaredCountIsRejectedBeforeAllocating) {
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_off(bad_file("huge_count.off")),
                                ":2: header declares 1000000000000 vertices");
}

TEST(OffIo, FaceIndexOutOfRange) {
  const std::string path = test::temp_dir("OffIo.OutOfRange") + "/mesh.off";
  write_file(path, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(
      io::read_off(path), ":6: face 0: vertex index 3 out of range (the file has 3 vertices)");
}

TEST(OffIo, MissingFaceLines) {
  const std::string path = test::temp_dir("OffIo.Truncated") + "/mesh.off";
  write_file(path, "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_off(path),
                                "unexpected end of file: expected face 1 (the header declares 2");
}

TEST(OffIo, NaNVertex) {
  const std::string path = test::temp_dir("OffIo.NaN") + "/mesh.off";
  write_file(path, "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_off(path),
                                ":4: vertex 1 coordinate is not a finite number");
}

TEST(OffIo, WrongMagic) {
  const std::string path = test::temp_dir("OffIo.Magic") + "/mesh.off";
  write_file(path, "ply\n3 1 0\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_off(path), ":1: not an OFF file");
}

TEST(OffIo, FaceWithTwoVertices) {
  const std::string path = test::temp_dir("OffIo.TwoVertices") + "/mesh.off";
  write_file(path, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_off(path), ":6: face 0: polygon with 2 vertices");
}

// -------------------------------------------------------------- dispatch ---

// The same pyramid in three formats gives the same triangles, whatever the
// case of the extension.
TEST(MeshIo, DispatchesByExtensionCaseInsensitive) {
  const std::string dir = test::temp_dir("MeshIo.Dispatch");
  const std::vector<std::pair<std::string, std::string>> files = {
      {"pyramid.ply", "a.PLY"}, {"pyramid.obj", "b.Obj"}, {"pyramid.off", "c.off"}};
  for (const auto& [source, target] : files) {
    fs::copy_file(mesh_file(source), dir + "/" + target);
    expect_pyramid_geometry(io::read_mesh(dir + "/" + target));
  }
}

TEST(MeshIo, UnsupportedExtension) {
  MESHNBV_EXPECT_ERROR_CONTAINS(
      io::read_mesh("scan.stl"),
      "scan.stl: unsupported mesh format '.stl' (expected .ply, .obj or .off)");
}

TEST(MeshIo, NoExtension) {
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_mesh("scan"), "unsupported mesh format '(no extension)'");
}
