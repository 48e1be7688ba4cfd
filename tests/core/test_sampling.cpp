// The vectorised bilinear kernels (meshnbv/sampling.h) against
// FloatImage::sample_gray, bit for bit, and PRI with either kernel.
#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <random>

#include "meshnbv/image.h"
#include "meshnbv/pri.h"
#include "meshnbv/sampling.h"
#include "meshnbv/synth/project.h"
#include "test_util.h"

using namespace meshnbv;

namespace {

FloatImage random_plane(int w, int h, unsigned seed) {
  Image img(w, h, 1);
  std::mt19937 rng(seed);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.pixel(x, y)[0] = std::uint8_t(rng() % 256);
  return FloatImage::luminance_of(img);
}

// Restores the level in use when a test ends.
struct LevelGuard {
  SimdLevel saved = simd_level();
  ~LevelGuard() { set_simd_level(saved); }
};

std::vector<SimdLevel> levels() {
  std::vector<SimdLevel> out = {SimdLevel::scalar};
  if (simd_supported() != SimdLevel::scalar)
    out.push_back(simd_supported());
  else
    std::cout << "[ note ] this processor runs no vector kernel: the scalar one only\n";
  return out;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST(Sampling, LevelIsAtMostSupported) {
  LevelGuard guard;
  EXPECT_EQ(set_simd_level(SimdLevel::scalar), SimdLevel::scalar);
  EXPECT_EQ(simd_level(), SimdLevel::scalar);
  EXPECT_EQ(set_simd_level(SimdLevel::avx2), simd_supported());
  EXPECT_STREQ(simd_name(SimdLevel::scalar), "scalar");
  EXPECT_STREQ(simd_name(SimdLevel::avx2), "avx2");
}

// Random points, the plane's corners and edges, integer coordinates and
// the last row and column (clamped cell, weight 1), every count from 1 to
// 70 (every tail): each kernel's samples are sample_gray's bits.
TEST(Sampling, KernelsAreSampleGrayBitForBit) {
  LevelGuard guard;
  const FloatImage plane = random_plane(37, 23, 3);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ux(0.0, 36.0), uy(0.0, 22.0);
  std::vector<double> x, y;
  for (double px : {0.0, 36.0, 35.0, 17.0, 35.999999}) x.push_back(px), y.push_back(22.0 - px * 0.5);
  x.push_back(36.0), y.push_back(22.0);
  x.push_back(0.0), y.push_back(0.0);
  while (x.size() < 70) x.push_back(ux(rng)), y.push_back(uy(rng));
  std::vector<float> expect(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) ASSERT_TRUE(plane.sample_gray(x[k], y[k], &expect[k]));
  for (SimdLevel level : levels()) {
    set_simd_level(level);
    for (std::size_t n = 1; n <= x.size(); ++n) {
      std::vector<float> out(n, -1.0f);
      ASSERT_TRUE(sample_gray_points(plane, x.data(), y.data(), n, out.data()))
          << simd_name(level) << " " << n;
      for (std::size_t k = 0; k < n; ++k)
        EXPECT_TRUE(same_bits(out[k], expect[k])) << simd_name(level) << " n " << n << " k " << k;
    }
  }
}

TEST(Sampling, HomogeneousPointsAreDividedAsTheLatticeDivides) {
  LevelGuard guard;
  const FloatImage plane = random_plane(64, 48, 4);
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> ux(0.0, 63.0), uy(0.0, 47.0), uz(0.3, 3.0);
  const std::size_t n = 67;
  std::vector<double> hx(n), hy(n), hz(n);
  std::vector<float> expect(n);
  for (std::size_t k = 0; k < n; ++k) {
    hz[k] = uz(rng);
    hx[k] = ux(rng) * hz[k], hy[k] = uy(rng) * hz[k];
    const double inv = 1.0 / hz[k];
    if (!plane.sample_gray(hx[k] * inv, hy[k] * inv, &expect[k])) {  // rounding past the edge
      hx[k] = 10 * hz[k], hy[k] = 10 * hz[k];
      ASSERT_TRUE(plane.sample_gray(hx[k] * inv, hy[k] * inv, &expect[k]));
    }
  }
  for (SimdLevel level : levels()) {
    set_simd_level(level);
    std::vector<float> out(n);
    ASSERT_TRUE(sample_gray_homogeneous(plane, hx.data(), hy.data(), hz.data(), n, out.data()));
    for (std::size_t k = 0; k < n; ++k)
      EXPECT_TRUE(same_bits(out[k], expect[k])) << simd_name(level) << " " << k;
  }
}

// One bad point at any position of a call (each lane of a vector, each
// place of the scalar tail) makes the call false.
TEST(Sampling, AnyPointOffThePlaneOrBehindTheCameraIsFalse) {
  LevelGuard guard;
  const FloatImage plane = random_plane(20, 10, 7);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<double, double>> bad = {{-1e-9, 5.0},      {5.0, -1e-9}, {19.0 + 1e-9, 5.0},
                                                      {5.0, 9.0 + 1e-9}, {nan, 5.0},   {5.0, nan},
                                                      {-100.0, -100.0}};
  const std::size_t n = 11;
  for (SimdLevel level : levels()) {
    set_simd_level(level);
    for (const auto& p : bad)
      for (std::size_t at = 0; at < n; ++at) {
        std::vector<double> x(n, 3.5), y(n, 2.5), z(n, 1.0);
        x[at] = p.first, y[at] = p.second;
        std::vector<float> out(n);
        EXPECT_FALSE(sample_gray_points(plane, x.data(), y.data(), n, out.data()))
            << simd_name(level) << " (" << p.first << ", " << p.second << ") at " << at;
        EXPECT_FALSE(sample_gray_homogeneous(plane, x.data(), y.data(), z.data(), n, out.data()));
      }
    for (double z_bad : {0.0, -1.0, -0.0, nan})
      for (std::size_t at = 0; at < n; ++at) {
        std::vector<double> x(n, 3.5), y(n, 2.5), z(n, 1.0);
        z[at] = z_bad, x[at] = 3.5 * z_bad, y[at] = 2.5 * z_bad;
        std::vector<float> out(n);
        EXPECT_FALSE(sample_gray_homogeneous(plane, x.data(), y.data(), z.data(), n, out.data()))
            << simd_name(level) << " z " << z_bad << " at " << at;
      }
    // No points: nothing to refuse.
    float none = 0;
    EXPECT_TRUE(sample_gray_points(plane, nullptr, nullptr, 0, &none));
  }
}

// Planes of one row or column: sample_gray's own rule (the vector kernels
// leave them to it).
TEST(Sampling, ThinPlanesAreSampledAsSampleGraySamplesThem) {
  LevelGuard guard;
  for (const auto& size : {std::pair<int, int>(1, 9), std::pair<int, int>(9, 1), std::pair<int, int>(1, 1)}) {
    const FloatImage plane = random_plane(size.first, size.second, 8);
    std::vector<double> x(9), y(9);
    for (int k = 0; k < 9; ++k)
      x[k] = size.first > 1 ? k * 0.9 : 0.0, y[k] = size.second > 1 ? k * 0.85 : 0.0;
    std::vector<float> expect(9);
    for (int k = 0; k < 9; ++k) ASSERT_TRUE(plane.sample_gray(x[k], y[k], &expect[k]));
    for (SimdLevel level : levels()) {
      set_simd_level(level);
      std::vector<float> out(9);
      ASSERT_TRUE(sample_gray_points(plane, x.data(), y.data(), 9, out.data()));
      for (int k = 0; k < 9; ++k) EXPECT_TRUE(same_bits(out[k], expect[k])) << simd_name(level);
    }
  }
}

// PRI of a rendered city (r from the faces' projected size, and
// fixed at 13: 105 points, two kernel calls per lattice) is the
// same bits with the scalar and the vector kernels, SSD and NCC.
TEST(Sampling, PriIsTheSameBitsWithEitherKernel) {
  LevelGuard guard;
  synth::SynthOptions o;
  o.scene = "city";
  o.generator.edge_length = 2.0;
  o.cameras.count = 6;
  o.cameras.width = 160;
  o.cameras.height = 120;
  o.overwrite = true;
  const synth::SynthProject project = synth::write_synthetic_project(o, test::temp_dir("sampling_pri"));
  for (const Measure measure : {Measure::SSD, Measure::NCC})
    for (int spp : {0, 13}) {
      PriOptions po;
      po.measure = measure;
      po.samples_per_side = spp;
      std::vector<PriResult> results;
      for (SimdLevel level : levels()) {
        set_simd_level(level);
        results.push_back(compute_pri(project.scene, po));
      }
      ASSERT_GT(results[0].observed, 100u);
      for (std::size_t i = 1; i < results.size(); ++i) {
        ASSERT_EQ(results[i].pri.size(), results[0].pri.size());
        EXPECT_EQ(
            std::memcmp(results[i].pri.data(), results[0].pri.data(), results[0].pri.size() * sizeof(float)),
            0)
            << measure_name(measure) << " spp " << spp;
        EXPECT_EQ(results[i].pri_views, results[0].pri_views);
        EXPECT_EQ(results[i].observed, results[0].observed);
      }
    }
}

// SSD's accumulator update (the default measure's inner loop) is the same
// bits with either kernel, for every patch size from 1 to 70 (every tail).
TEST(Sampling, SsdAccumulatorIsTheSameBitsWithEitherKernel) {
  LevelGuard guard;
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (std::size_t n = 1; n <= 70; ++n) {
    std::vector<std::vector<float>> patches(7, std::vector<float>(n));
    for (auto& p : patches)
      for (float& x : p) x = u(rng);
    std::vector<std::vector<double>> accs;
    for (SimdLevel level : levels()) {
      set_simd_level(level);
      std::vector<double> acc(pair_accumulator_size(n), 0.0);
      for (const auto& p : patches) pair_accumulate(acc.data(), p.data(), n, Measure::SSD, 1e-4);
      accs.push_back(acc);
    }
    for (std::size_t i = 1; i < accs.size(); ++i)
      EXPECT_EQ(std::memcmp(accs[i].data(), accs[0].data(), accs[0].size() * sizeof(double)), 0) << "n " << n;
    // And the sums are the pairwise SSD's (SPEC: mean over pairs).
    double pairwise = 0;
    for (std::size_t a = 0; a < patches.size(); ++a)
      for (std::size_t b = a + 1; b < patches.size(); ++b)
        pairwise += ssd_error(patches[a].data(), patches[b].data(), n);
    const PairSum sum = pair_accumulated_sum(accs.back().data(), n, Measure::SSD);
    EXPECT_NEAR(sum.sum, pairwise, 1e-12 * pairwise) << "n " << n;
    EXPECT_EQ(sum.pairs, 21u);
  }
}
