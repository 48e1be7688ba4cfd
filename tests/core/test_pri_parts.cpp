// PRI in parts: tiles computed separately and assembled, and incremental
// PRI, each equal bit for bit to one whole computation (docs/scale.md).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

#include "meshnbv/error.h"
#include "meshnbv/pri.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/renderer.h"
#include "meshnbv/synth/generators.h"
#include "meshnbv/synth/project.h"
#include "meshnbv/visibility.h"
#include "test_util.h"

using namespace meshnbv;

namespace {

// The synthetic building (degraded, so that PRI varies) seen by `views`
// orbit cameras, images rendered in memory.
Scene building(int views, int width = 320) {
  synth::SynthOptions o;
  o.scene = "building";
  o.cameras.count = views;
  o.cameras.layout = synth::CameraLayout::Orbit;
  o.cameras.width = width;
  o.cameras.height = width * 3 / 4;
  synth::SynthProject p = synth::make_synthetic_project(o);
  synth::render_synthetic_views(o, &p);
  return p.scene;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every per-face array equal, floats bit for bit (NaN included).
void expect_identical(const PriResult& a, const PriResult& b) {
  ASSERT_EQ(a.pri.size(), b.pri.size());
  std::size_t differ = 0;
  for (std::size_t f = 0; f < a.pri.size(); ++f) {
    const bool same = same_bits(a.pri[f], b.pri[f]) && a.pri_views[f] == b.pri_views[f] &&
                      a.status[f] == b.status[f] && a.pri_pairs[f] == b.pri_pairs[f] &&
                      a.pri_samples[f] == b.pri_samples[f] && same_bits(a.pri_texture[f], b.pri_texture[f]) &&
                      a.evidence_key[f] == b.evidence_key[f];
    if (!same && differ++ < 5) ADD_FAILURE() << "face " << f << ": " << a.pri[f] << " vs " << b.pri[f];
  }
  EXPECT_EQ(differ, 0u);
  ASSERT_EQ(a.offset_signed.size(), b.offset_signed.size());
  for (std::size_t f = 0; f < a.offset_signed.size(); ++f) {
    EXPECT_TRUE(same_bits(a.offset_signed[f], b.offset_signed[f])) << f;
    EXPECT_TRUE(same_bits(a.offset_precision[f], b.offset_precision[f])) << f;
    EXPECT_TRUE(same_bits(a.offset_steady[f], b.offset_steady[f])) << f;
  }
  EXPECT_EQ(a.observed, b.observed);
  EXPECT_EQ(a.unobserved, b.unobserved);
  EXPECT_EQ(a.textureless, b.textureless);
}

PriResult by_tiles(const Scene& scene, const PriOptions& o, std::size_t tiles) {
  const RayCaster caster(scene.mesh);
  std::vector<PriPart> parts;
  for (const auto& tile : pri_tiles(scene.mesh, tiles))
    parts.push_back(compute_pri_part(scene, o, select_pri_views(scene, o, {}, tile, &caster)));
  return assemble_pri(scene, o, parts);
}

// Moves the vertices within `radius` of `centre` by `offset` along z.
TriangleMesh edited(const TriangleMesh& mesh, const Vec3& centre, double radius, double offset) {
  TriangleMesh out = mesh;
  for (Vec3& v : out.vertices)
    if ((v - centre).norm() < radius) v.z() += offset;
  return out;
}

}  // namespace

TEST(PriTiles, EveryFaceOnceCompactAndAscending) {
  const Scene s = building(2);
  const std::size_t F = s.mesh.num_faces();
  const auto tiles = pri_tiles(s.mesh, 7);
  ASSERT_EQ(tiles.size(), 7u);
  std::vector<int> seen(F, 0);
  double tile_extent = 0;
  for (const auto& t : tiles) {
    EXPECT_TRUE(std::is_sorted(t.begin(), t.end()));
    EXPECT_LE(std::max(t.size(), F / 7) - std::min(t.size(), F / 7), 1u);
    BoundingBox box;
    for (std::uint32_t f : t) {
      ++seen[f];
      box.extend(s.mesh.face_centroid(f));
    }
    tile_extent += box.diagonal() / double(tiles.size());
  }
  for (std::size_t f = 0; f < F; ++f) EXPECT_EQ(seen[f], 1) << f;
  // Compact: a tile spans much less than the mesh (a Morton run of 1/7 of
  // the faces; a random seventh would span the whole mesh).
  EXPECT_LT(tile_extent, 0.8 * s.mesh.bounding_box().diagonal());
  // A subset is tiled alone; more tiles than faces gives one face each.
  EXPECT_EQ(pri_tiles(s.mesh, 10, {3, 5, 9}).size(), 3u);
  EXPECT_TRUE(pri_tiles(s.mesh, 0).empty());
}

TEST(PriTiles, SubsetVisibilityEqualsTheWholeMesh) {
  const Scene s = building(4);
  std::vector<PinholeCamera> cams;
  for (const View& v : s.views) cams.push_back(v.camera);
  const RayCaster caster(s.mesh);
  const VertexVisibility all(s.mesh, caster, cams);
  std::vector<std::uint32_t> some;
  for (std::uint32_t v = 0; v < s.mesh.num_vertices(); v += 3) some.push_back(v);
  const VertexVisibility part(s.mesh, caster, cams, {}, {}, some);
  std::size_t visible = 0;
  for (std::uint32_t v = 0; v < s.mesh.num_vertices(); ++v)
    for (std::size_t i = 0; i < cams.size(); ++i) {
      if (v % 3 == 0) {
        EXPECT_EQ(part.visible(v, i), all.visible(v, i)) << v << " " << i;
        visible += all.visible(v, i);
      } else {
        EXPECT_FALSE(part.visible(v, i));
      }
    }
  EXPECT_GT(visible, 0u);
  EXPECT_THROW(VertexVisibility(s.mesh, caster, cams, {}, {}, {std::uint32_t(s.mesh.num_vertices())}), Error);
}

TEST(PriParts, TilesAssembleToTheWholeResultForEveryMeasure) {
  const Scene s = building(6);
  for (const char* m : {"ssd", "ncc", "offset"}) {
    SCOPED_TRACE(m);
    PriOptions o;
    o.measure = parse_measure(m);
    const PriResult whole = compute_pri(s, o);
    ASSERT_GT(whole.observed, s.mesh.num_faces() / 4);
    const PriResult tiled = by_tiles(s, o, 5);
    expect_identical(whole, tiled);
    EXPECT_EQ(tiled.recomputed, s.mesh.num_faces());
  }
}

TEST(PriParts, AssembleRefusesMissingOrRepeatedFaces) {
  const Scene s = building(3);
  const PriOptions o;
  const auto tiles = pri_tiles(s.mesh, 2);
  const PriPart a = compute_pri_part(s, o, select_pri_views(s, o, {}, tiles[0]));
  EXPECT_THROW(assemble_pri(s, o, {a}), Error);     // tile 1 missing
  EXPECT_THROW(assemble_pri(s, o, {a, a}), Error);  // tile 0 twice
  EXPECT_THROW(select_pri_views(s, o, {}, {5, 3}), Error);  // not ascending
}

TEST(PriIncremental, NothingChangedRecomputesNothing) {
  const Scene s = building(5);
  const PriOptions o;
  const PriResult full = compute_pri(s, o);
  const PriPrevious previous{s.mesh, full};
  const PriResult again = compute_pri(s, o, {}, &previous);
  expect_identical(full, again);
  EXPECT_EQ(again.recomputed, 0u);
  EXPECT_EQ(again.images_decoded, 0u);
  // Other options change every key: everything again.
  PriOptions other = o;
  other.samples_per_side = 5;
  const PriResult changed = compute_pri(s, other, {}, &previous);
  EXPECT_EQ(changed.recomputed, s.mesh.num_faces());
  expect_identical(compute_pri(s, other), changed);
  // The thread count changes no value: nothing recomputed.
  PriOptions threads = o;
  threads.threads = 1;
  EXPECT_EQ(compute_pri(s, threads, {}, &previous).recomputed, 0u);
}

TEST(PriIncremental, LocalEditEqualsAFullComputationOnAFifthOfTheFaces) {
  const Scene before = building(6);
  for (const char* m : {"ssd", "offset"}) {
    SCOPED_TRACE(m);
    PriOptions o;
    o.measure = parse_measure(m);
    const PriResult old = compute_pri(before, o);
    Scene after = before;
    const BoundingBox box = before.mesh.bounding_box();
    // A dent a few faces wide, inside the bounding box (which then stays
    // the same): around the surface point nearest to a point above the centre.
    const Vec3 aim = box.center() + Vec3(0, 0, 0.2 * box.extent().z());
    Vec3 centre = before.mesh.vertices[0];
    for (const Vec3& v : before.mesh.vertices)
      if ((v - aim).norm() < (centre - aim).norm()) centre = v;
    after.mesh = edited(before.mesh, centre, 0.06 * box.diagonal(), -0.005 * box.diagonal());
    ASSERT_EQ(after.mesh.bounding_box().max, box.max);
    ASSERT_EQ(after.mesh.bounding_box().min, box.min);
    ASSERT_NE(after.mesh.vertices, before.mesh.vertices);
    const PriPrevious previous{before.mesh, old};
    const PriResult incremental = compute_pri(after, o, {}, &previous);
    expect_identical(compute_pri(after, o), incremental);
    EXPECT_GT(incremental.recomputed, 0u);
    EXPECT_LE(double(incremental.recomputed), 0.2 * double(after.mesh.num_faces()));
    EXPECT_GE(plan_incremental_pri(after, o, previous).selected, incremental.recomputed);
  }
}

TEST(PriIncremental, AddingAViewRecomputesTheFacesItSees) {
  const Scene all = building(7);
  Scene fewer = all;
  fewer.views.pop_back();
  const PriOptions o;
  const PriPrevious previous{fewer.mesh, compute_pri(fewer, o)};
  const PriResult incremental = compute_pri(all, o, {}, &previous);
  expect_identical(compute_pri(all, o), incremental);
  // Exactly the faces whose selected views include the new one.
  const PriViewSelection sel = select_pri_views(all, o);
  const int added = int(sel.cameras.size()) - 1;
  std::size_t seeing = 0;
  for (const PriFaceViews& fv : sel.faces)
    seeing += std::find(fv.views.begin(), fv.views.end(), added) != fv.views.end();
  EXPECT_EQ(incremental.recomputed, seeing);
  EXPECT_GT(seeing, 0u);
  // A view removed: every face's views selected again, still exact.
  const PriPrevious all_before{all.mesh, compute_pri(all, o)};
  const PriReuse plan = plan_incremental_pri(fewer, o, all_before);
  EXPECT_EQ(plan.selected, all.mesh.num_faces());
  expect_identical(compute_pri(fewer, o), compute_pri(fewer, o, {}, &all_before));
  EXPECT_LT(seeing, all.mesh.num_faces());
}

TEST(PriIncremental, ChangedImageOrCameraRecomputesItsFaces) {
  const Scene s = building(5);
  const PriOptions o;
  const PriPrevious previous{s.mesh, compute_pri(s, o)};
  Scene moved = s;
  moved.views[2].camera.t.x() += 1e-3;
  const PriResult a = compute_pri(moved, o, {}, &previous);
  expect_identical(compute_pri(moved, o), a);
  EXPECT_GT(a.recomputed, 0u);
  Scene repainted = s;
  Image im = *s.views[1].pixels;
  im.data()[0] ^= 1;
  repainted.views[1].pixels = std::make_shared<const Image>(std::move(im));
  EXPECT_GT(compute_pri(repainted, o, {}, &previous).recomputed, 0u);
}

TEST(PriIncremental, InconsistentPreviousIsAnError) {
  const Scene s = building(3);
  PriOptions o;
  PriPrevious previous{s.mesh, compute_pri(s, o)};
  previous.result.evidence_key.pop_back();
  EXPECT_THROW(compute_pri(s, o, {}, &previous), Error);
  PriPrevious ssd{s.mesh, compute_pri(s, o)};
  o.measure = Measure::Offset;
  EXPECT_THROW(compute_pri(s, o, {}, &ssd), Error);  // no offset values to reuse
}

// A long strip of ground, each camera looking down at its own part (the
// last one behind the strip's end, looking away from it).
Scene strip() {
  const TriangleMesh ground = synth::make_ground(Vec3(-20, -2, 0), Vec3(20, 2, 0), 0.25, 0);
  Scene s;
  s.mesh = ground;
  s.mesh.face_attributes.clear();
  const RayCaster caster(ground);
  const SolidTexture texture(3, {{Pattern::Noise, Vec3(0.7, 0.6, 0.5), Vec3(0.3, 0.3, 0.3), 0.5, 0.45}}, 0.1);
  for (int i = 0; i < 9; ++i) {
    View v;
    v.label = "v" + std::to_string(i);
    const Vec3 eye(-16 + 4 * i, -1.0 + 0.3 * (i % 3), 5), target(-16 + 4 * i + 0.5 * (i % 2), 0, 0);
    v.camera = PinholeCamera::look_at(eye, target, Vec3(0, 1, 0.3), 180, 180, 99.5, 74.5, 200, 150);
    v.pixels = std::make_shared<const Image>(
        render({&ground, &caster, &texture, ground.face_attribute(synth::kMaterialAttribute)}, v.camera));
    s.views.push_back(v);
  }
  // One camera behind the strip's end, looking away from it.
  s.views[8].camera = PinholeCamera::look_at(Vec3(25, 0, 5), Vec3(40, 0, 0), Vec3(0, 0, 1), 180, 180, 99.5, 74.5,
                                            200, 150);
  return s;
}

// Most views of a tile of the strip are culled by its bounding box
// (may_see_box), and the tiles still give the whole result.
TEST(PriParts, TilesOfAWideSceneCullTheirViewsAndAgree) {
  const Scene s = strip();
  for (const char* m : {"ssd", "offset"}) {
    SCOPED_TRACE(m);
    PriOptions o;
    o.measure = parse_measure(m);
    const PriResult whole = compute_pri(s, o);
    ASSERT_GT(whole.observed, 100u);
    expect_identical(whole, by_tiles(s, o, 12));
  }
}

// On the strip, an edit seen by two cameras: views are selected again only
// for the faces those cameras see near it, and the result is exact.
TEST(PriIncremental, LocalEditSelectsViewsOnlyWhereItMayReach) {
  const Scene before = strip();
  const PriOptions o;
  const PriPrevious previous{before.mesh, compute_pri(before, o)};
  Scene after = before;
  // Vertices under camera 2 moved along the strip: the geometry changes,
  // its bounding box does not.
  for (Vec3& v : after.mesh.vertices)
    if ((v - Vec3(-8, 0, 0)).norm() < 1.2) v.x() += 0.05;
  ASSERT_EQ(after.mesh.bounding_box().min, before.mesh.bounding_box().min);
  ASSERT_EQ(after.mesh.bounding_box().max, before.mesh.bounding_box().max);
  const PriReuse plan = plan_incremental_pri(after, o, previous);
  const PriResult incremental = compute_pri(after, o, {}, &previous);
  expect_identical(compute_pri(after, o), incremental);
  EXPECT_GT(incremental.recomputed, 0u);
  EXPECT_GE(plan.selected, incremental.recomputed);
  // Bound: the faces of the strip that a camera seeing the edit sees.
  std::size_t seen_with_edit = 0;
  for (std::size_t f = 0; f < after.mesh.num_faces(); ++f) {
    bool near = false;
    for (const View& v : after.views) {
      Vec2 p, q;
      const bool sees_edit = v.camera.project(Vec3(-8, 0, 0), &p) && v.camera.in_image(p);
      if (sees_edit && v.camera.project(after.mesh.face_centroid(f), &q) && v.camera.in_image(q)) near = true;
    }
    seen_with_edit += near;
  }
  // ... plus the two tiles (of 256 faces, plan_incremental_pri) cut by
  // the ends of that footprint along the strip.
  EXPECT_LE(plan.selected, seen_with_edit + 2 * 256);
  EXPECT_LT(plan.selected, after.mesh.num_faces() / 4);
}

// On the strip, one view added: views are selected again only for the faces
// that lie wholly inside the new view's image, and the result is exact.
TEST(PriIncremental, AddedViewSelectsViewsOnlyForTheFacesInItsImage) {
  const Scene all = strip();
  Scene fewer = all;
  fewer.views.erase(fewer.views.begin() + 3);
  const PriOptions o;
  const PriPrevious previous{fewer.mesh, compute_pri(fewer, o)};
  const PriReuse plan = plan_incremental_pri(all, o, previous);
  const PriResult incremental = compute_pri(all, o, {}, &previous);
  expect_identical(compute_pri(all, o), incremental);
  EXPECT_GT(incremental.recomputed, 0u);
  EXPECT_GE(plan.selected, incremental.recomputed);
  const PinholeCamera& added = all.views[3].camera;
  std::size_t inside = 0;
  for (const Face& f : all.mesh.faces) {
    bool in = true;
    for (int k = 0; k < 3; ++k) {
      Vec2 p;
      in = in && added.project(all.mesh.vertices[std::size_t(f[k])], &p) && added.in_image(p);
    }
    inside += in;
  }
  ASSERT_GT(inside, 0u);
  EXPECT_LE(plan.selected, inside);
  EXPECT_LT(plan.selected, all.mesh.num_faces() / 4);
}

// The same faces in another order (an exporter that sorts them): each is
// found by its geometry, nothing is recomputed, and the result equals a
// full computation on the reordered mesh.
TEST(PriIncremental, ReorderedFacesAreFoundByTheirGeometry) {
  const Scene before = building(5);
  const PriOptions o;
  const PriPrevious previous{before.mesh, compute_pri(before, o)};
  Scene after = before;
  std::reverse(after.mesh.faces.begin(), after.mesh.faces.end());
  const PriResult incremental = compute_pri(after, o, {}, &previous);
  EXPECT_EQ(incremental.recomputed, 0u);
  EXPECT_EQ(plan_incremental_pri(after, o, previous).selected, 0u);
  expect_identical(compute_pri(after, o), incremental);
}
