// The next-best-view energy terms against hand-computed values (SPEC §4).
// Camera for the focus tests: 640x480, f = 500, at the origin looking
// along +z with image y down (R = I, t = 0): a point (x, y, z) projects to
// (500 x/z + 319.5, 500 y/z + 239.5).
#include <cmath>

#include "meshnbv/energy.h"
#include "meshnbv/error.h"
#include "meshnbv/synth/generators.h"
#include "test_util.h"

using namespace meshnbv;
using test::kDeg;

namespace {
PinholeCamera wide_axis_camera() { return test::centred_camera(500, 640, 480); }
}  // namespace

TEST(EnergyTerms, FocusAtCentreCornerAndOutside) {
  const PinholeCamera c = wide_axis_camera();
  EXPECT_NEAR(focus_term(c, Vec3(0, 0, 10), -10), 0.0, 1e-12);
  // Pixel (0, 0): dx = -319.5, dy = -239.5; sx = 640/3, sy = 160.
  const Vec3 corner((0 - 319.5) / 500 * 10, (0 - 239.5) / 500 * 10, 10);
  const double expected = -(319.5 * 319.5) / (2 * (640 / 3.0) * (640 / 3.0)) -
                          (239.5 * 239.5) / (2 * 160.0 * 160.0);
  EXPECT_NEAR(focus_term(c, corner, -10), expected, 1e-9);
  EXPECT_NEAR(expected, -2.25, 0.01);  // the SPEC's "-2.25 at a corner"
  EXPECT_EQ(focus_term(c, Vec3(10, 0, 10), -10), -10);   // outside the image
  EXPECT_EQ(focus_term(c, Vec3(0, 0, -10), -10), -10);   // behind the camera
}

TEST(EnergyTerms, ParallaxJustAboveAndBelowDelta) {
  EnergyOptions o;
  const Vec3 v(0, 0, 0), candidate(0, 0, 10);  // H = 10
  EXPECT_EQ(parallax_term(candidate, Vec3(3.31, 0, 10), v, o), 1.0);    // B/H = 0.331
  EXPECT_EQ(parallax_term(candidate, Vec3(3.29, 0, 10), v, o), -10.0);  // B/H = 0.329
  o.penalty = -4;
  EXPECT_EQ(parallax_term(candidate, candidate, v, o), -4.0);
}

TEST(EnergyTerms, IncidenceMaximalAt55AndSymmetric) {
  const EnergyOptions o;
  EXPECT_NEAR(o.kappa(), 1.0 / std::pow(15 * kDeg, 2), 1e-12);
  EXPECT_NEAR(o.kappa(), 14.59, 0.01);
  const double at_mu = incidence_term(55 * kDeg, o);
  EXPECT_NEAR(at_mu, 0.41, 0.01);
  for (double d : {1.0, 10.0, 30.0}) {
    EXPECT_LT(incidence_term((55 + d) * kDeg, o), at_mu);
    EXPECT_NEAR(incidence_term((55 + d) * kDeg, o), incidence_term((55 - d) * kDeg, o), 1e-12);
  }
  EXPECT_NEAR(incidence_term(145 * kDeg, o), -14.2, 0.05);  // 90 degrees from mu
  const double expected = o.kappa() - std::log(2 * M_PI * std::cyl_bessel_i(0.0, o.kappa()));
  EXPECT_NEAR(at_mu, expected, 1e-12);
}

namespace {
// A 2 x 2 m square at z = 0 (8 faces) facing +z, and a PRI that makes the
// two faces around (0.5, 0.5) the worst.
struct Square {
  TriangleMesh mesh = synth::make_ground(Vec3(-1, -1, 0), Vec3(1, 1, 0), 1.0, 0);
  std::vector<float> pri;
  Square() {
    pri.assign(mesh.num_faces(), 0.1f);
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
      const Vec3 c = mesh.face_centroid(f);
      if (c.x() > 0 && c.y() > 0) pri[f] = f % 2 ? 0.9f : 0.8f;
    }
  }
};
}  // namespace

TEST(WorstRegion, HighestPriFacesVerticesAndNormals) {
  Square s;
  const WorstRegion r = worst_region(s.mesh, s.pri, 2);
  ASSERT_EQ(r.faces.size(), 2u);
  EXPECT_GT(s.pri[r.faces[0]], s.pri[r.faces[1]] - 1e-9);
  EXPECT_EQ(r.vertices.size(), 4u);  // the unit square (0..1)^2
  for (const Vec3& n : r.normals) EXPECT_NEAR((n - Vec3::UnitZ()).norm(), 0, 1e-12);
  EXPECT_NEAR((r.centroid - Vec3(0.5, 0.5, 0)).norm(), 0, 1e-12);
  std::vector<float> none(s.mesh.num_faces(), std::numeric_limits<float>::quiet_NaN());
  MESHNBV_EXPECT_ERROR_CONTAINS(worst_region(s.mesh, none, 10), "no observed face");
}

TEST(Energy, SumOfPartsOcclusionAndTerms) {
  Square s;
  TriangleMesh scene_mesh = s.mesh;
  // A blocker above the worst region, 1 m up, hiding it from straight above.
  scene_mesh.append(synth::make_box(Vec3(-0.2, -0.2, 1.0), Vec3(1.2, 1.2, 1.2), 0.5, 0));
  std::vector<float> pri = s.pri;
  pri.resize(scene_mesh.num_faces(), 0.0f);
  const RayCaster caster(scene_mesh);
  const WorstRegion region = worst_region(scene_mesh, pri, 2);
  const std::vector<Vec3> existing = {Vec3(-3, 0, 5), Vec3(0, -3, 5)};
  const EnergyOptions o;
  const EnergyEvaluator e(scene_mesh, caster, region, existing, o);

  // From (0.5 + 5 sin 55, 0.5, 5 cos 55) looking at the region: every worst
  // vertex visible, the normal at 55 degrees to the view for the centre.
  const Vec3 target(0.5, 0.5, 0);
  const Vec3 eye = target + 5.0 * Vec3(std::sin(55 * kDeg), 0, std::cos(55 * kDeg));
  const PinholeCamera good = PinholeCamera::look_at(eye, target, Vec3(0, 0, 1), 500, 500, 319.5, 239.5, 640, 480);
  const EnergyTerms t = e.evaluate(good);
  EXPECT_NEAR(t.total, t.occlusion + t.focus + t.parallax + t.incidence, 1e-12);
  EXPECT_NEAR(t.occlusion, 0.6 * 4, 1e-12);  // 4 vertices, all visible
  EXPECT_TRUE(e.sees_all_vertices(good));
  EXPECT_EQ(e.seen_faces(good).size(), 2u);
  // Hand-computed sum over the 4 vertices.
  double focus = 0, parallax = 0, incidence = 0;
  for (int v : region.vertices) {
    const Vec3& p = scene_mesh.vertices[std::size_t(v)];
    focus += focus_term(good, p, -10);
    for (const Vec3& c : existing) parallax += parallax_term(eye, c, p, o);
    incidence += incidence_term(std::acos(Vec3::UnitZ().dot((eye - p).normalized())), o);
  }
  EXPECT_NEAR(t.focus, 1.6 * focus, 1e-9);
  EXPECT_NEAR(t.parallax, 2.1 * parallax, 1e-9);
  EXPECT_NEAR(t.incidence, 0.6 * incidence, 1e-9);

  // Straight above: the blocker hides the region.
  const PinholeCamera above = PinholeCamera::look_at(target + Vec3(0, 0, 5), target, Vec3(0, 1, 0),
                                                     500, 500, 319.5, 239.5, 640, 480);
  const EnergyTerms b = e.evaluate(above);
  EXPECT_NEAR(b.occlusion, 0.6 * 4 * -10, 1e-12);
  EXPECT_FALSE(e.sees_all_vertices(above));
  EXPECT_TRUE(e.seen_faces(above).empty());
  EXPECT_GT(t.total, b.total);
}

TEST(Energy, OptionsAreChecked) {
  EnergyOptions o;
  o.weights[2] = std::nan("");
  EXPECT_THROW(o.check(), Error);
  EnergyOptions p;
  p.incidence_sigma = 0;
  EXPECT_THROW(p.check(), Error);
}

// --- The incidence term's normalisation for small sigma (issue #20) -------
// kappa = 1 / sigma^2 with sigma in radians: sigma = 2 degrees gives kappa
// = 820.7, past the ~713 where std::cyl_bessel_i(0, kappa) overflows a
// double; the term must stay finite and keep its values.

namespace {
double kappa_of(double sigma_degrees) { return 1.0 / std::pow(sigma_degrees * kDeg, 2); }
}  // namespace

TEST(IncidenceBessel, ContinuousAtTheSwitchToTheAsymptoticSeries) {
  const double k = kBesselI0AsymptoticFrom;
  const double below = log_bessel_i0_scaled(std::nextafter(k, 0.0));  // std::cyl_bessel_i branch
  const double at = log_bessel_i0_scaled(k);                           // series branch
  // One ulp of kappa moves log I0(k) - k by about 1e-16 x 1/(2k): any gap
  // beyond that is a disagreement of the two branches.
  EXPECT_NEAR(below, at, 1e-12 * std::abs(at));
  EXPECT_NEAR(below + k, at + k, 1e-12 * (at + k));  // log I0 itself
  // The series branch at the switch against std::cyl_bessel_i at the same kappa.
  EXPECT_NEAR(at, std::log(std::cyl_bessel_i(0.0, k)) - k, 1e-12 * std::abs(at));
}

TEST(IncidenceBessel, AgreesWithCylBesselIWhereThatIsFinite) {
  // Below the switch this is the function itself; from 50 to 700 it checks
  // the series against the library.
  int series_points = 0;
  for (double k = 1e-3; k < 710; k *= 1.07) {
    const double reference = std::log(std::cyl_bessel_i(0.0, k));
    ASSERT_TRUE(std::isfinite(reference)) << k;
    const double log_i0 = log_bessel_i0_scaled(k) + k;
    EXPECT_NEAR(log_i0, reference, 1e-12 * std::max(1.0, std::abs(reference))) << "kappa " << k;
    series_points += k >= kBesselI0AsymptoticFrom;
  }
  EXPECT_GT(series_points, 30);
  // Beyond 713 the double overflows, which is what the series avoids; a
  // long double reference still exists there.
  EXPECT_TRUE(std::isinf(std::cyl_bessel_i(0.0, kappa_of(2.0))));
  for (double sigma : {2.0, 1.0}) {
    const long double k = kappa_of(sigma);
    const long double reference = std::log(std::cyl_bessel_il(0.0L, k)) - k;
    EXPECT_NEAR(log_bessel_i0_scaled(double(k)), double(reference), 1e-12) << "sigma " << sigma;
  }
}

TEST(IncidenceBessel, FiniteEnergiesForSigmaOfAFewTenthsOfADegree) {
  Square s;
  const RayCaster caster(s.mesh);
  const WorstRegion region = worst_region(s.mesh, s.pri, 2);
  const Vec3 target(0.5, 0.5, 0);
  const Vec3 eye = target + 5.0 * Vec3(std::sin(50 * kDeg), 0, std::cos(50 * kDeg));
  const PinholeCamera cam =
      PinholeCamera::look_at(eye, target, Vec3(0, 0, 1), 500, 500, 319.5, 239.5, 640, 480);
  for (double sigma : {0.1, 0.5, 1.0, 2.0}) {
    EnergyOptions o;
    o.incidence_sigma = sigma;
    const double k = o.kappa();
    EXPECT_NEAR(k, kappa_of(sigma), 1e-9 * k);
    // At x = mu: kappa - log(2 pi I0(kappa)) = log(kappa / (2 pi)) / 2 -
    // log1p(1/(8k) + 9/(128k^2) + 225/(3072k^3) + ...), written out here
    // (the next term is below 1e-10 for these kappas).
    const double at_mu = incidence_term(55 * kDeg, o);
    const double expected = 0.5 * std::log(k / (2 * M_PI)) -
                            std::log1p(1 / (8 * k) + 9 / (128 * k * k) + 225 / (3072 * k * k * k));
    ASSERT_TRUE(std::isfinite(at_mu)) << "sigma " << sigma;
    EXPECT_NEAR(at_mu, expected, 1e-9) << "sigma " << sigma;
    // Two sigma away from mu the density has fallen by kappa (1 - cos(2 sigma)) ~ 2.
    const double two_sigma = incidence_term((55 + 2 * sigma) * kDeg, o);
    EXPECT_NEAR(at_mu - two_sigma, k * (1 - std::cos(2 * sigma * kDeg)), 1e-9) << "sigma " << sigma;
    // The whole energy, and its incidence part by hand.
    const EnergyEvaluator e(s.mesh, caster, region, {Vec3(-3, 0, 5)}, o);
    const EnergyTerms t = e.evaluate(cam);
    EXPECT_TRUE(std::isfinite(t.total) && std::isfinite(t.incidence)) << "sigma " << sigma;
    double incidence = 0;
    for (int v : region.vertices) {
      const Vec3& p = s.mesh.vertices[std::size_t(v)];
      incidence += incidence_term(std::acos(Vec3::UnitZ().dot((eye - p).normalized())), o);
    }
    EXPECT_NEAR(t.incidence, 0.6 * incidence, 1e-9 * std::max(1.0, std::abs(incidence)));
  }
}

TEST(IncidenceBessel, IncidenceIsTheVonMisesLogDensity) {
  // SPEC section 4: I(x) = kappa cos(x - mu) - log(2 pi I0(kappa)), the
  // logarithm of the von Mises density on the circle: exp(I) integrates to
  // 1 over a period, and I(x) - I(mu) = kappa (cos(x - mu) - 1). The
  // trapezoid rule on a periodic function is exact to rounding once the
  // step is well under sigma (2^17 steps: 27 per sigma at 0.1 degrees).
  for (double sigma : {0.1, 0.5, 1.0, 2.0, 15.0, 60.0, 90.0}) {
    EnergyOptions o;
    o.incidence_sigma = sigma;
    const double k = o.kappa(), mu = 55 * kDeg;
    const int n = 1 << 17;
    const double h = 2 * M_PI / n;
    double integral = 0;
    for (int i = 0; i < n; ++i) integral += std::exp(incidence_term(mu - M_PI + i * h, o)) * h;
    EXPECT_NEAR(integral, 1.0, 1e-9) << "sigma " << sigma;
    const double at_mu = incidence_term(mu, o);
    for (double d : {0.3, 1.0, 7.0, 90.0}) {
      const double x = mu + d * kDeg;
      EXPECT_NEAR(incidence_term(x, o) - at_mu, k * (std::cos(x - mu) - 1),
                  1e-12 * std::max(1.0, k)) << "sigma " << sigma << " d " << d;
    }
  }
}
