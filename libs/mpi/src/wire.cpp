#include "meshnbv/mpi/wire.h"

#include <cmath>
#include <cstring>
#include <type_traits>

#include "meshnbv/error.h"

namespace meshnbv::mpi {

namespace {

// Each message starts with its kind, so that one kind of bytes is never
// read as another.
constexpr std::uint32_t kScene = 0x4d4e5331, kOptions = 0x4d4e4f31, kFaces = 0x4d4e4631, kParts = 0x4d4e5031,
                        kScore = 0x4d4e4a31, kEnergies = 0x4d4e4531;

class Writer {
 public:
  explicit Writer(std::uint32_t kind) { put(kind); }
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void put_string(const std::string& s) {
    put(std::uint64_t(s.size()));
    out_ += s;
  }
  template <class T>
  void put_vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(std::uint64_t(v.size()));
    if (!v.empty()) out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  Reader(const std::string& bytes, std::uint32_t kind, const char* what) : s_(bytes), what_(what) {
    if (get<std::uint32_t>() != kind) fail("not a message of this kind");
  }
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T v;
    std::memcpy(&v, s_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  double get_finite() {
    const double v = get<double>();
    if (!std::isfinite(v)) fail("a number is not finite");
    return v;
  }
  bool get_bool() {
    const std::uint8_t b = get<std::uint8_t>();
    if (b > 1) fail("a flag is neither 0 nor 1");
    return b == 1;
  }
  std::uint64_t get_count(std::size_t item_bytes) {
    const std::uint64_t n = get<std::uint64_t>();
    if (item_bytes > 0 && n > (s_.size() - at_) / item_bytes) fail("a count exceeds the bytes left");
    return n;
  }
  std::string get_string() {
    const std::uint64_t n = get_count(1);
    std::string v = s_.substr(at_, std::size_t(n));
    at_ += std::size_t(n);
    return v;
  }
  template <class T>
  std::vector<T> get_vector() {
    const std::uint64_t n = get_count(sizeof(T));
    std::vector<T> v;
    v.resize(std::size_t(n));
    if (n) std::memcpy(v.data(), s_.data() + at_, std::size_t(n) * sizeof(T));
    at_ += std::size_t(n) * sizeof(T);
    return v;
  }
  bool done() const { return at_ == s_.size(); }
  void finish() {
    if (!done()) fail("bytes left after the end");
  }
  [[noreturn]] void fail(const std::string& why) const {
    throw Error(std::string("malformed ") + what_ + " message at byte " + std::to_string(at_) + ": " + why);
  }

 private:
  void need(std::size_t n) {
    if (n > s_.size() - at_) fail("truncated");
  }
  const std::string& s_;
  const char* what_;
  std::size_t at_ = 0;
};

void put_camera(Writer& w, const PinholeCamera& c) {
  static_assert(sizeof(PinholeCamera) == 13 * 8 + 3 * 4 + 4 + 9 * 8 + 3 * 8,
                "PinholeCamera changed: update the wire format (wire.cpp)");
  for (double x : {c.fx, c.fy, c.cx, c.cy, c.k1, c.k2, c.k3, c.k4, c.k5, c.k6, c.p1, c.p2, c.skew}) w.put(x);
  w.put(std::int32_t(c.width));
  w.put(std::int32_t(c.height));
  w.put(std::int32_t(c.lens));
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) w.put(c.R(r, k));
  for (int r = 0; r < 3; ++r) w.put(c.t[r]);
}

PinholeCamera get_camera(Reader& r) {
  PinholeCamera c;
  for (double* x :
       {&c.fx, &c.fy, &c.cx, &c.cy, &c.k1, &c.k2, &c.k3, &c.k4, &c.k5, &c.k6, &c.p1, &c.p2, &c.skew})
    *x = r.get_finite();
  c.width = r.get<std::int32_t>();
  c.height = r.get<std::int32_t>();
  const std::int32_t lens = r.get<std::int32_t>();
  if (lens < 0 || lens > 1) r.fail("unknown lens model " + std::to_string(lens));
  c.lens = LensModel(lens);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) c.R(i, k) = r.get_finite();
  for (int i = 0; i < 3; ++i) c.t[i] = r.get_finite();
  return c;
}

void put_points(Writer& w, const std::vector<Vec3>& points) {
  std::vector<double> xyz;
  xyz.reserve(3 * points.size());
  for (const Vec3& p : points) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  w.put_vector(xyz);
}

std::vector<Vec3> get_points(Reader& r) {
  const std::vector<double> xyz = r.get_vector<double>();
  if (xyz.size() % 3) r.fail("coordinates are not triples");
  std::vector<Vec3> points(xyz.size() / 3);
  for (std::size_t v = 0; v < points.size(); ++v)
    points[v] = Vec3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
  return points;
}

Vec3 get_vec3(Reader& r) {
  const double x = r.get_finite(), y = r.get_finite(), z = r.get_finite();
  return Vec3(x, y, z);
}

void put_vec3(Writer& w, const Vec3& p) {
  for (int k = 0; k < 3; ++k) w.put(p[k]);
}

}  // namespace

std::string write_scene(const Scene& scene) {
  Writer w(kScene);
  put_points(w, scene.mesh.vertices);
  w.put_vector(scene.mesh.faces);
  w.put_string(scene.mesh_path);
  w.put_string(scene.source);
  w.put(std::uint64_t(scene.images ? scene.images->max_bytes() : 0));
  w.put(std::uint64_t(scene.views.size()));
  for (const View& v : scene.views) {
    w.put_string(v.label);
    put_camera(w, v.camera);
    w.put_string(v.image_path);
    w.put(std::uint8_t(v.used));
    w.put(std::uint8_t(v.orientation == ImageOrientation::exif));
    w.put(std::uint8_t(v.pixels != nullptr));
    if (v.pixels) {
      w.put(std::int32_t(v.pixels->width()));
      w.put(std::int32_t(v.pixels->height()));
      w.put(std::int32_t(v.pixels->channels()));
      w.put(std::int32_t(v.pixels->bits()));
      w.put_string(std::string(reinterpret_cast<const char*>(v.pixels->data()), v.pixels->bytes()));
    }
  }
  return w.take();
}

Scene read_scene(const std::string& bytes) {
  static_assert(sizeof(Face) == 3 * sizeof(int));
  Reader r(bytes, kScene, "scene");
  Scene s;
  s.mesh.vertices = get_points(r);
  s.mesh.faces = r.get_vector<Face>();
  s.mesh_path = r.get_string();
  s.source = r.get_string();
  const std::uint64_t cache = r.get<std::uint64_t>();
  if (cache > 0) s.images = std::make_shared<ImageCache>(std::size_t(cache));
  const std::uint64_t views = r.get_count(1);
  for (std::uint64_t i = 0; i < views; ++i) {
    View v;
    v.label = r.get_string();
    v.camera = get_camera(r);
    v.image_path = r.get_string();
    v.used = r.get_bool();
    v.orientation = r.get_bool() ? ImageOrientation::exif : ImageOrientation::stored;
    if (r.get_bool()) {
      const int width = r.get<std::int32_t>(), height = r.get<std::int32_t>(),
                channels = r.get<std::int32_t>();
      const int bits = r.get<std::int32_t>();
      if (width < 1 || height < 1 || width > 1 << 16 || height > 1 << 16 ||
          (channels != 1 && channels != 3) || (bits != 8 && bits != 16))
        r.fail("an in-memory image of " + std::to_string(width) + "x" + std::to_string(height) + "x" +
               std::to_string(channels) + " at " + std::to_string(bits) + " bits");
      const std::string data = r.get_string();
      if (data.size() !=
          std::size_t(width) * std::size_t(height) * std::size_t(channels) * std::size_t(bits / 8))
        r.fail("an in-memory image's pixels do not fill it");
      Image im(width, height, channels, bits);
      std::memcpy(im.data(), data.data(), data.size());
      v.pixels = std::make_shared<const Image>(std::move(im));
    }
    s.views.push_back(std::move(v));
  }
  r.finish();
  s.mesh.validate("the scene message");
  return s;
}

std::string write_pri_options(const PriOptions& o) {
  // A new field of PriOptions must be added here and in read_pri_options.
  static_assert(sizeof(PriOptions) == 96, "PriOptions changed: update the wire format (wire.cpp)");
  Writer w(kOptions);
  w.put(std::int32_t(o.measure));
  w.put(std::int32_t(o.samples_per_side));
  w.put(std::int32_t(o.max_views_per_face));
  w.put(std::uint8_t(o.color));
  w.put(std::int32_t(o.threads));
  w.put(o.textureless_variance);
  w.put(o.max_incidence_angle);
  w.put(std::uint8_t(o.check_interior_occlusion));
  w.put(o.edge_margin);
  w.put(o.support_radius);
  w.put(o.offset_range);
  w.put(std::int32_t(o.offset_steps));
  w.put(std::int32_t(o.max_image_reduction));
  w.put(o.visibility.relative_eps);
  w.put(o.visibility.absolute_eps_of_diagonal);
  return w.take();
}

PriOptions read_pri_options(const std::string& bytes) {
  Reader r(bytes, kOptions, "PRI options");
  PriOptions o;
  const std::int32_t measure = r.get<std::int32_t>();
  if (measure < 0 || measure > 2) r.fail("unknown measure " + std::to_string(measure));
  o.measure = Measure(measure);
  o.samples_per_side = r.get<std::int32_t>();
  o.max_views_per_face = r.get<std::int32_t>();
  o.color = r.get_bool();
  o.threads = r.get<std::int32_t>();
  o.textureless_variance = r.get_finite();
  o.max_incidence_angle = r.get_finite();
  o.check_interior_occlusion = r.get_bool();
  o.edge_margin = r.get_finite();
  o.support_radius = r.get_finite();
  o.offset_range = r.get_finite();
  o.offset_steps = r.get<std::int32_t>();
  o.max_image_reduction = r.get<std::int32_t>();
  o.visibility.relative_eps = r.get_finite();
  o.visibility.absolute_eps_of_diagonal = r.get_finite();
  r.finish();
  o.check();
  return o;
}

std::string write_faces(const std::vector<std::uint32_t>& faces) {
  Writer w(kFaces);
  w.put_vector(faces);
  return w.take();
}

std::vector<std::uint32_t> read_faces(const std::string& bytes) {
  Reader r(bytes, kFaces, "faces");
  std::vector<std::uint32_t> faces = r.get_vector<std::uint32_t>();
  r.finish();
  for (std::size_t j = 1; j < faces.size(); ++j)
    if (faces[j] <= faces[j - 1]) r.fail("the faces are not ascending");
  return faces;
}

std::string write_pri_parts(const std::vector<PriPart>& parts) {
  Writer w(kParts);
  w.put(std::uint64_t(parts.size()));
  for (const PriPart& p : parts) {
    const PriResult& v = p.values;
    w.put_vector(p.faces);
    w.put_vector(v.pri);
    w.put_vector(v.pri_views);
    w.put_vector(v.status);
    w.put_vector(v.pri_pairs);
    w.put_vector(v.pri_samples);
    w.put_vector(v.pri_texture);
    w.put_vector(v.evidence_key);
    w.put_vector(v.offset_signed);
    w.put_vector(v.offset_precision);
    w.put_vector(v.offset_pixel);
    w.put_vector(v.offset_steady);
    w.put(std::uint64_t(v.views_used));
    w.put(std::uint64_t(v.recomputed));
    w.put(std::uint64_t(v.images_decoded));
    w.put(std::uint64_t(v.views_reduced));
  }
  return w.take();
}

std::vector<PriPart> read_pri_parts(const std::string& bytes) {
  Reader r(bytes, kParts, "PRI parts");
  std::vector<PriPart> parts;
  const std::uint64_t n = r.get_count(8);
  for (std::uint64_t i = 0; i < n; ++i) {
    PriPart p;
    PriResult& v = p.values;
    p.faces = r.get_vector<std::uint32_t>();
    v.pri = r.get_vector<float>();
    v.pri_views = r.get_vector<int>();
    v.status = r.get_vector<FaceStatus>();
    v.pri_pairs = r.get_vector<int>();
    v.pri_samples = r.get_vector<int>();
    v.pri_texture = r.get_vector<float>();
    v.evidence_key = r.get_vector<std::uint64_t>();
    v.offset_signed = r.get_vector<float>();
    v.offset_precision = r.get_vector<float>();
    v.offset_pixel = r.get_vector<float>();
    v.offset_steady = r.get_vector<float>();
    v.views_used = std::size_t(r.get<std::uint64_t>());
    v.recomputed = std::size_t(r.get<std::uint64_t>());
    v.images_decoded = std::size_t(r.get<std::uint64_t>());
    v.views_reduced = std::size_t(r.get<std::uint64_t>());
    const std::size_t m = p.faces.size();
    for (std::size_t size : {v.pri.size(), v.pri_views.size(), v.status.size(), v.pri_pairs.size(),
                             v.pri_samples.size(), v.pri_texture.size(), v.evidence_key.size()})
      if (size != m) r.fail("a part's arrays differ in length from its faces");
    for (std::size_t size : {v.offset_signed.size(), v.offset_precision.size(), v.offset_pixel.size(),
                              v.offset_steady.size()})
      if (size != 0 && size != m) r.fail("a part's offset arrays differ in length from its faces");
    for (FaceStatus st : v.status)
      if (std::uint8_t(st) > 2) r.fail("unknown face status");
    parts.push_back(std::move(p));
  }
  r.finish();
  return parts;
}

std::uint64_t mesh_key(const TriangleMesh& mesh) {
  std::uint64_t h = 0x6d6573686b6579ull ^ (std::uint64_t(mesh.vertices.size()) << 32) ^ mesh.faces.size();
  auto mix = [](std::uint64_t x) {
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdull;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ull;
    return x ^ (x >> 33);
  };
  for (const Vec3& p : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      std::uint64_t bits;
      const double x = p[k];
      std::memcpy(&bits, &x, 8);
      h = mix(h ^ bits) + 0x9e3779b97f4a7c15ull;
    }
  for (const Face& f : mesh.faces)
    h = mix(h ^ (std::uint64_t(std::uint32_t(f[0])) | std::uint64_t(std::uint32_t(f[1])) << 32)) ^
        std::uint32_t(f[2]);
  return h;
}

std::string write_score_job(const ScoreJob& job) {
  static_assert(sizeof(EnergyOptions) == 4 * 8 + 4 * 8 + 2 * 8, "EnergyOptions changed: update wire.cpp");
  Writer w(kScore);
  w.put(job.mesh_key);
  w.put(std::uint8_t(job.has_mesh));
  if (job.has_mesh) {
    put_points(w, job.mesh.vertices);
    w.put_vector(job.mesh.faces);
  }
  w.put_vector(job.region.faces);
  w.put_vector(job.region.vertices);
  put_points(w, job.region.normals);
  put_vec3(w, job.region.centroid);
  put_vec3(w, job.region.mean_normal);
  put_points(w, job.existing);
  const EnergyOptions& o = job.options;
  for (double x : o.weights) w.put(x);
  for (double x : {o.penalty, o.parallax_delta, o.incidence_mu, o.incidence_sigma, o.visibility.relative_eps,
                   o.visibility.absolute_eps_of_diagonal})
    w.put(x);
  w.put(std::uint64_t(job.cameras.size()));
  for (const PinholeCamera& c : job.cameras) put_camera(w, c);
  return w.take();
}

ScoreJob read_score_job(const std::string& bytes) {
  Reader r(bytes, kScore, "candidate scoring");
  ScoreJob job;
  job.mesh_key = r.get<std::uint64_t>();
  job.has_mesh = r.get_bool();
  if (job.has_mesh) {
    job.mesh.vertices = get_points(r);
    job.mesh.faces = r.get_vector<Face>();
    job.mesh.validate("the candidate scoring message");
    if (job.mesh.empty()) r.fail("the mesh has no faces");
  }
  job.region.faces = r.get_vector<int>();
  job.region.vertices = r.get_vector<int>();
  job.region.normals = get_points(r);
  job.region.centroid = get_vec3(r);
  job.region.mean_normal = get_vec3(r);
  if (job.region.normals.size() != job.region.vertices.size())
    r.fail("a region's normals are not one per vertex");
  job.existing = get_points(r);
  EnergyOptions& o = job.options;
  for (double& x : o.weights) x = r.get_finite();
  for (double* x : {&o.penalty, &o.parallax_delta, &o.incidence_mu, &o.incidence_sigma,
                    &o.visibility.relative_eps, &o.visibility.absolute_eps_of_diagonal})
    *x = r.get_finite();
  o.check();
  const std::uint64_t n = r.get_count(200);
  for (std::uint64_t i = 0; i < n; ++i) {
    job.cameras.push_back(get_camera(r));
    job.cameras.back().check("candidate " + std::to_string(i));
  }
  r.finish();
  return job;
}

std::string write_energies(const std::vector<EnergyTerms>& energies) {
  Writer w(kEnergies);
  w.put(std::uint64_t(energies.size()));
  for (const EnergyTerms& e : energies)
    for (double x : {e.occlusion, e.focus, e.parallax, e.incidence, e.refinement, e.exploration, e.total,
                     e.whole_mesh ? 1.0 : 0.0})
      w.put(x);
  return w.take();
}

std::vector<EnergyTerms> read_energies(const std::string& bytes) {
  Reader r(bytes, kEnergies, "energies");
  std::vector<EnergyTerms> out(std::size_t(r.get_count(64)));
  for (EnergyTerms& e : out) {
    for (double* x : {&e.occlusion, &e.focus, &e.parallax, &e.incidence, &e.refinement, &e.exploration, &e.total})
      *x = r.get<double>();
    e.whole_mesh = r.get<double>() != 0;
  }
  r.finish();
  return out;
}

}  // namespace meshnbv::mpi
