// The messages of meshnbv-mpi's ranks: written and read back exactly, and
// every truncation or wrong kind refused with an Error.
#include <gtest/gtest.h>

#include <cstring>

#include "meshnbv/error.h"
#include "meshnbv/mpi/wire.h"
#include "meshnbv/pri.h"
#include "meshnbv/synth/project.h"

using namespace meshnbv;

namespace {

Scene rendered(int views) {
  synth::SynthOptions o;
  o.cameras.count = views;
  o.cameras.width = 160;
  o.cameras.height = 120;
  synth::SynthProject p = synth::make_synthetic_project(o);
  synth::render_synthetic_views(o, &p);
  return p.scene;
}

}  // namespace

TEST(Wire, SceneRoundTripGivesTheSamePri) {
  Scene s = rendered(4);
  s.views[3].pixels.reset();
  s.views[3].image_path = "elsewhere/view.png";
  s.views[3].used = false;
  s.views[1].camera.k1 = -0.02;
  s.views[1].camera.skew = 0.5;
  s.views[3].orientation = ImageOrientation::exif;
  {  // view 2 at 16 bits
    const Image& e = *s.views[2].pixels;
    Image w(e.width(), e.height(), e.channels(), 16);
    for (int y = 0; y < e.height(); ++y)
      for (int x = 0; x < e.width(); ++x)
        for (int c = 0; c < e.channels(); ++c)
          w.pixel16(x, y)[c] = std::uint16_t(e.pixel(x, y)[c] * 257 + (x & 7));
    s.views[2].pixels = std::make_shared<const Image>(std::move(w));
  }
  const std::string bytes = mpi::write_scene(s);
  const Scene r = mpi::read_scene(bytes);
  ASSERT_EQ(r.mesh.vertices, s.mesh.vertices);
  ASSERT_EQ(r.mesh.faces, s.mesh.faces);
  ASSERT_EQ(r.views.size(), s.views.size());
  for (std::size_t i = 0; i < s.views.size(); ++i) {
    EXPECT_EQ(r.views[i].label, s.views[i].label);
    EXPECT_EQ(r.views[i].image_path, s.views[i].image_path);
    EXPECT_EQ(r.views[i].used, s.views[i].used);
    EXPECT_EQ(r.views[i].orientation, s.views[i].orientation);
    EXPECT_EQ(pri_view_key(r, i), pri_view_key(s, i)) << i;  // camera and pixels, every bit
  }
  EXPECT_EQ(mpi::write_scene(r), bytes);
  const PriResult a = compute_pri(s), b = compute_pri(r);
  EXPECT_EQ(0, std::memcmp(a.pri.data(), b.pri.data(), a.pri.size() * sizeof(float)));
}

TEST(Wire, OptionsAndFacesRoundTrip) {
  PriOptions o;
  o.measure = Measure::NCC;
  o.samples_per_side = 7;
  o.max_views_per_face = 3;
  o.color = true;
  o.check_interior_occlusion = false;
  o.edge_margin = 0.25;
  o.visibility.relative_eps = 2e-4;
  const PriOptions r = mpi::read_pri_options(mpi::write_pri_options(o));
  EXPECT_EQ(pri_options_key(r), pri_options_key(o));
  EXPECT_EQ(r.color, true);
  EXPECT_EQ(mpi::read_faces(mpi::write_faces({1, 5, 9})), (std::vector<std::uint32_t>{1, 5, 9}));
  EXPECT_THROW(mpi::read_faces(mpi::write_faces({5, 1})), Error);
  PriOptions bad;
  bad.samples_per_side = 1000;  // out of the option's range
  EXPECT_THROW(mpi::read_pri_options(mpi::write_pri_options(bad)), Error);
}

TEST(Wire, PartsRoundTrip) {
  const Scene s = rendered(3);
  PriOptions o;
  o.measure = Measure::Offset;
  const auto tiles = pri_tiles(s.mesh, 2);
  std::vector<PriPart> parts;
  for (const auto& t : tiles) parts.push_back(compute_pri_part(s, o, select_pri_views(s, o, {}, t)));
  const std::string bytes = mpi::write_pri_parts(parts);
  EXPECT_EQ(mpi::write_pri_parts(mpi::read_pri_parts(bytes)), bytes);
  const PriResult a = assemble_pri(s, o, parts), b = assemble_pri(s, o, mpi::read_pri_parts(bytes));
  EXPECT_EQ(0, std::memcmp(a.pri.data(), b.pri.data(), a.pri.size() * sizeof(float)));
}

TEST(Wire, TruncatedOrForeignMessagesAreErrors) {
  Scene s = rendered(2);
  s.mesh.faces.resize(20);
  s.mesh.vertices.resize(200);
  for (auto& f : s.mesh.faces)
    for (int& v : f) v %= 200;
  const std::string scene = mpi::write_scene(s), options = mpi::write_pri_options({});
  for (std::size_t n = 0; n < options.size(); ++n)
    EXPECT_THROW(mpi::read_pri_options(options.substr(0, n)), Error) << n;
  for (std::size_t n = 0; n < scene.size(); n += 97)
    EXPECT_THROW(mpi::read_scene(scene.substr(0, n)), Error) << n;
  EXPECT_THROW(mpi::read_scene(scene + "x"), Error);
  EXPECT_THROW(mpi::read_scene(options), Error);
  EXPECT_THROW(mpi::read_pri_options(scene), Error);
  EXPECT_THROW(mpi::read_pri_parts(options), Error);
  // A face index out of range is the mesh's validation error.
  Scene broken = s;
  broken.mesh.faces[0][0] = 100000;
  EXPECT_THROW(mpi::read_scene(mpi::write_scene(broken)), Error);
}

TEST(Wire, ScoreJobRoundTrip) {
  const Scene s = rendered(3);
  mpi::ScoreJob job;
  job.mesh_key = mpi::mesh_key(s.mesh);
  job.has_mesh = true;
  job.mesh = s.mesh;
  std::vector<float> pri(s.mesh.num_faces());
  for (std::size_t f = 0; f < pri.size(); ++f) pri[f] = float(f % 17);
  job.region = worst_region(s.mesh, pri, 10);
  job.existing = {s.views[0].camera.center(), s.views[1].camera.center()};
  job.options.weights[2] = 3.5;
  for (const View& v : s.views) job.cameras.push_back(v.camera);
  const std::string bytes = mpi::write_score_job(job);
  const mpi::ScoreJob r = mpi::read_score_job(bytes);
  EXPECT_EQ(mpi::write_score_job(r), bytes);
  EXPECT_EQ(r.mesh.vertices, s.mesh.vertices);
  EXPECT_EQ(r.region.faces, job.region.faces);
  EXPECT_EQ(r.options.weights[2], 3.5);
  EXPECT_EQ(mpi::mesh_key(r.mesh), job.mesh_key);
  TriangleMesh moved = s.mesh;
  moved.vertices[0].x() += 1e-12;
  EXPECT_NE(mpi::mesh_key(moved), job.mesh_key);
  const std::vector<EnergyTerms> e = {{1, 2, 3, 4, 10}, {-10, 0, 0, 0, -10}};
  const std::vector<EnergyTerms> back = mpi::read_energies(mpi::write_energies(e));
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].total, 10);
  EXPECT_EQ(back[1].occlusion, -10);
  EXPECT_THROW(mpi::read_energies(bytes), Error);
  for (std::size_t n = 0; n < bytes.size(); n += 1013)
    EXPECT_THROW(mpi::read_score_job(bytes.substr(0, n)), Error);
}
