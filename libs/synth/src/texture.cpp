#include "meshnbv/texture.h"

#include <algorithm>
#include <cmath>

namespace meshnbv {

std::vector<Material> default_materials() {
  return {
      {Pattern::Noise, Vec3(0.78, 0.74, 0.66), Vec3(0.5, 0.48, 0.44), 1.5, 0.35},   // plaster
      {Pattern::Bricks, Vec3(0.66, 0.33, 0.24), Vec3(0.82, 0.8, 0.74), 1.0, 0.3},  // bricks
      {Pattern::Windows, Vec3(0.8, 0.75, 0.64), Vec3(0.32, 0.38, 0.46), 3.0, 0.35},  // facade
      {Pattern::Stripes, Vec3(0.72, 0.7, 0.62), Vec3(0.52, 0.5, 0.46), 1.5, 0.35},  // stone
      {Pattern::Tiles, Vec3(0.62, 0.28, 0.2), Vec3(0.36, 0.16, 0.12), 0.4, 0.3},    // roof
      {Pattern::Tiles, Vec3(0.55, 0.56, 0.5), Vec3(0.3, 0.3, 0.27), 1.2, 0.45},    // paved ground
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

SolidTexture::SolidTexture(std::uint64_t seed, std::vector<Material> materials, double min_period)
    : seed_(seed), materials_(std::move(materials)), min_period_(min_period) {
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
    // Weight 1 for periods >= 2 min_period, fading to 0 at min_period.
    const double w = min_period_ > 0 ? std::clamp(1.0 / (freq * min_period_) - 1.0, 0.0, 1.0) : 1.0;
    if (w <= 0) break;
    sum += w * amp * value_noise(p * freq + Vec3(17.0 * octave, 31.0 * octave, 7.0 * octave));
    norm += w * amp;
    amp *= 0.5;
    freq *= 2.0;
  }
  return norm > 0 ? sum / norm : 0.5;
}

Vec3 SolidTexture::albedo(const Vec3& p, const Vec3& n, int material) const {
  const Material& m =
      materials_[material >= 0 && material < int(materials_.size()) ? material : 0];
  // Fine grain everywhere (down to the band limit), so no surface is
  // textureless.
  const double grain = fractal_noise(p, std::max(0.12 * m.scale, 2.0 * min_period_));
  const double coarse = fractal_noise(p, m.scale);
  // Averaged octaves of value noise cluster around 0.5 (std about 0.1):
  // stretch them so every surface carries visible texture, as a
  // photogrammetry subject must.
  const double mix = std::clamp(0.5 + 4.0 * (0.6 * coarse + 0.4 * grain - 0.5), 0.0, 1.0);
  const double variation = 1.0 - m.noise + 2.0 * m.noise * mix;
  double s, t;
  plane_coords(p, n, &s, &t);
  // Pattern edges are smoothed over `soft` metres (half the band limit) so
  // that they do not alias either.
  const double soft = 0.5 * min_period_;
  // 0 at distance <= -soft/2 from an edge, 1 at >= +soft/2 (hard step if soft = 0).
  auto ramp = [soft](double signed_distance) {
    if (soft <= 0) return signed_distance > 0 ? 1.0 : 0.0;
    const double x = std::clamp(signed_distance / soft + 0.5, 0.0, 1.0);
    return x * x * (3 - 2 * x);
  };
  Vec3 colour = m.base;
  switch (m.pattern) {
    case Pattern::Noise: break;
    case Pattern::Bricks:
    case Pattern::Tiles: {
      // Running bond: rows of height scale/3 (tiles: scale/2), odd rows
      // shifted by half a unit; joints centred on the cell borders.
      const double h = m.pattern == Pattern::Bricks ? m.scale / 3.0 : m.scale / 2.0;
      const double row = std::floor(t / h);
      const double shift = (long long)row % 2 ? 0.5 * m.scale : 0.0;
      const double col = std::floor((s + shift) / m.scale);
      const double fu = frac((s + shift) / m.scale) * m.scale, fv = frac(t / h) * h;
      const double to_joint = std::min({fu, m.scale - fu, fv, h - fv});
      const double half_joint = 0.5 * std::max(0.06 * m.scale, 0.5 * min_period_);
      const Vec3 unit = m.base * (0.85 + 0.3 * hash01(seed_ + std::uint64_t(material),
                                                      (long long)row, (long long)col));
      const double w = ramp(to_joint - half_joint);
      colour = (1 - w) * m.accent + w * unit;
      break;
    }
    case Pattern::Windows: {
      // A window per scale x scale cell: glass with a light frame. Signed
      // distances (metres) to the glass and frame rectangles, positive inside.
      const double fu = frac(s / m.scale) * m.scale, fv = frac(t / m.scale) * m.scale;
      auto inside = [&](double u0, double u1, double v0, double v1) {
        return std::min({fu - u0 * m.scale, u1 * m.scale - fu, fv - v0 * m.scale, v1 * m.scale - fv});
      };
      const double glass = ramp(inside(0.3, 0.7, 0.3, 0.75));
      const double frame = ramp(inside(0.27, 0.73, 0.27, 0.78));
      const Vec3 pane = m.accent * (0.7 + 0.6 * hash01(seed_, (long long)std::floor(s / m.scale),
                                                       (long long)std::floor(t / m.scale)));
      const Vec3 white(0.86, 0.86, 0.84);
      colour = (1 - frame) * m.base + frame * ((1 - glass) * white + glass * pane);
      break;
    }
    case Pattern::Stripes: {
      // Alternating bands; the distance to the nearest band border decides.
      const double ft = frac(t / m.scale) * m.scale;
      const bool odd = (long long)std::floor(t / m.scale) % 2 != 0;
      const double to_border = std::min(ft, m.scale - ft);
      const double w = 0.5 + 0.5 * (2 * ramp(to_border) - 1);  // 0.5 on the border, 1 inside
      const Vec3 own = odd ? m.accent : m.base, other = odd ? m.base : m.accent;
      colour = w * own + (1 - w) * other;
      break;
    }
  }
  return (colour * variation).cwiseMax(0.0).cwiseMin(1.0);
}

}  // namespace meshnbv
