#include "meshnbv/texture.h"

#include <algorithm>
#include <cmath>

namespace meshnbv {

std::vector<Material> default_materials() {
  return {
      {Pattern::Noise, Vec3(0.78, 0.74, 0.66), Vec3(0.5, 0.48, 0.44), 1.5, 0.35},   // plaster
      {Pattern::Bricks, Vec3(0.66, 0.33, 0.24), Vec3(0.82, 0.8, 0.74), 0.5, 0.3},  // bricks
      {Pattern::Windows, Vec3(0.85, 0.8, 0.68), Vec3(0.18, 0.24, 0.32), 3.0, 0.3},  // facade
      {Pattern::Stripes, Vec3(0.72, 0.7, 0.62), Vec3(0.52, 0.5, 0.46), 0.8, 0.35},  // stone
      {Pattern::Tiles, Vec3(0.62, 0.28, 0.2), Vec3(0.36, 0.16, 0.12), 0.4, 0.3},    // roof
      {Pattern::Noise, Vec3(0.45, 0.52, 0.36), Vec3(0.35, 0.33, 0.3), 4.0, 0.45},   // ground
  };
}

namespace {
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
double frac(double x) { return x - std::floor(x); }
double hash01(std::uint64_t seed, long long a, long long b) {
  return double(splitmix64(seed ^ splitmix64(std::uint64_t(a) * 0x9E3779B1ull + std::uint64_t(b))) >>
                11) *
         0x1.0p-53;
}

// Two in-plane coordinates (s horizontal, t vertical for walls) by the
// dominant axis of the normal: a planar projection for each face.
void plane_coords(const Vec3& p, const Vec3& n, double* s, double* t) {
  const Vec3 a = n.cwiseAbs();
  if (a.z() >= a.x() && a.z() >= a.y()) {
    *s = p.x();
    *t = p.y();
  } else if (a.x() >= a.y()) {
    *s = p.y();
    *t = p.z();
  } else {
    *s = p.x();
    *t = p.z();
  }
}
}  // namespace

SolidTexture::SolidTexture(std::uint64_t seed, std::vector<Material> materials)
    : seed_(seed), materials_(std::move(materials)) {
  if (materials_.empty()) materials_ = default_materials();
}

double SolidTexture::lattice(long long x, long long y, long long z) const {
  std::uint64_t h = splitmix64(seed_ ^ splitmix64(std::uint64_t(x) * 0x8DA6B343ull ^
                                                  std::uint64_t(y) * 0xD8163841ull ^
                                                  std::uint64_t(z) * 0xCB1AB31Full));
  return double(h >> 11) * 0x1.0p-53;
}

double SolidTexture::value_noise(const Vec3& p) const {
  const double fx = std::floor(p.x()), fy = std::floor(p.y()), fz = std::floor(p.z());
  const long long x = (long long)fx, y = (long long)fy, z = (long long)fz;
  const double u = fade(p.x() - fx), v = fade(p.y() - fy), w = fade(p.z() - fz);
  double c[2][2][2];
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) c[i][j][k] = lattice(x + i, y + j, z + k);
  auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
  const double x00 = lerp(c[0][0][0], c[1][0][0], u), x10 = lerp(c[0][1][0], c[1][1][0], u);
  const double x01 = lerp(c[0][0][1], c[1][0][1], u), x11 = lerp(c[0][1][1], c[1][1][1], u);
  return lerp(lerp(x00, x10, v), lerp(x01, x11, v), w);
}

double SolidTexture::fractal_noise(const Vec3& p, double scale) const {
  double sum = 0, norm = 0, amp = 1, freq = 1.0 / scale;
  for (int octave = 0; octave < 5; ++octave) {
    sum += amp * value_noise(p * freq + Vec3(17.0 * octave, 31.0 * octave, 7.0 * octave));
    norm += amp;
    amp *= 0.5;
    freq *= 2.0;
  }
  return sum / norm;
}

Vec3 SolidTexture::albedo(const Vec3& p, const Vec3& n, int material) const {
  const Material& m =
      materials_[material >= 0 && material < int(materials_.size()) ? material : 0];
  // Fine grain everywhere, so no surface is textureless at close range.
  const double grain = fractal_noise(p, 0.12 * m.scale);
  const double coarse = fractal_noise(p, m.scale);
  const double variation = 1.0 - m.noise + 2.0 * m.noise * (0.6 * coarse + 0.4 * grain);
  double s, t;
  plane_coords(p, n, &s, &t);
  Vec3 colour = m.base;
  switch (m.pattern) {
    case Pattern::Noise: break;
    case Pattern::Bricks:
    case Pattern::Tiles: {
      // Running bond: rows of height scale/3 (tiles: scale/2), odd rows shifted.
      const double h = m.pattern == Pattern::Bricks ? m.scale / 3.0 : m.scale / 2.0;
      const double row = std::floor(t / h);
      const double shift = (long long)row % 2 ? 0.5 * m.scale : 0.0;
      const double col = std::floor((s + shift) / m.scale);
      const double fu = frac((s + shift) / m.scale), fv = frac(t / h);
      const double mortar = 0.06;
      if (fu < mortar || fv < mortar * 3.0) {
        colour = m.accent;
      } else {
        colour = m.base * (0.75 + 0.5 * hash01(seed_ + std::uint64_t(material), (long long)row,
                                               (long long)col));
      }
      break;
    }
    case Pattern::Windows: {
      // A window per scale x scale cell, glass with a light frame.
      const double fu = frac(s / m.scale), fv = frac(t / m.scale);
      const bool in_window = fu > 0.3 && fu < 0.7 && fv > 0.3 && fv < 0.75;
      const bool in_frame = fu > 0.27 && fu < 0.73 && fv > 0.27 && fv < 0.78;
      if (in_window)
        colour = m.accent * (0.7 + 0.6 * hash01(seed_, (long long)std::floor(s / m.scale),
                                                (long long)std::floor(t / m.scale)));
      else if (in_frame)
        colour = Vec3(0.92, 0.92, 0.9);
      break;
    }
    case Pattern::Stripes: {
      const double band = std::floor(t / m.scale);
      colour = (long long)band % 2 ? m.accent : m.base;
      break;
    }
  }
  return (colour * variation).cwiseMax(0.0).cwiseMin(1.0);
}

}  // namespace meshnbv
