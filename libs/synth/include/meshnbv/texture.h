// Deterministic procedural solid textures for synthetic scenes: the colour
// is a function of the 3-D surface point only (view-independent), so a
// correct reconstruction is photo-consistent across views.
#pragma once

#include <cstdint>
#include <vector>

#include "meshnbv/types.h"

namespace meshnbv {

enum class Pattern { Noise, Bricks, Windows, Stripes, Tiles };

struct Material {
  Pattern pattern = Pattern::Noise;
  Vec3 base = Vec3(0.6, 0.55, 0.5);    // RGB in [0, 1]
  Vec3 accent = Vec3(0.3, 0.25, 0.2);  // mortar, window glass, second stripe
  double scale = 1.0;                  // pattern period in metres
  double noise = 0.25;                 // amplitude of the multi-octave noise
};

// Materials the generators use, by id: 0 plaster (noise), 1 bricks,
// 2 facade with windows, 3 stone stripes, 4 roof tiles, 5 paved ground.
std::vector<Material> default_materials();

class SolidTexture {
 public:
  // `min_period` (metres) band-limits the texture: noise octaves and
  // pattern lines finer than it are faded out, so that images rendered with
  // a pixel footprint of about min_period / 2 do not alias (aliasing would
  // make a correct surface look photo-inconsistent). 0 = no limit.
  explicit SolidTexture(std::uint64_t seed = 1, std::vector<Material> materials = default_materials(),
                        double min_period = 0.0);

  // Albedo in [0, 1]^3 at surface point p of a face with unit normal n.
  // Unknown material ids fall back to material 0.
  Vec3 albedo(const Vec3& p, const Vec3& n, int material) const;
  // Multi-octave value noise in [0, 1] (5 octaves, base frequency 1/scale;
  // octaves finer than min_period fade out).
  double fractal_noise(const Vec3& p, double scale) const;

 private:
  double lattice(long long x, long long y, long long z) const;
  double value_noise(const Vec3& p) const;

  std::uint64_t seed_;
  std::vector<Material> materials_;
  double min_period_ = 0.0;
};

}  // namespace meshnbv
