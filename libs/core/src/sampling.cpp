#include "meshnbv/sampling.h"

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "x86_simd.h"

namespace meshnbv {

namespace {

bool scalar_points(const FloatImage& plane, const double* x, const double* y, std::size_t n, float* out) {
  for (std::size_t k = 0; k < n; ++k)
    if (!plane.sample_gray(x[k], y[k], out + k)) return false;
  return true;
}

bool scalar_homogeneous(const FloatImage& plane, const double* hx, const double* hy, const double* hz,
                        std::size_t n, float* out) {
  for (std::size_t k = 0; k < n; ++k) {
    if (!(hz[k] > 0)) return false;
    const double inv = 1.0 / hz[k];
    if (!plane.sample_gray(hx[k] * inv, hy[k] * inv, out + k)) return false;
  }
  return true;
}

// Planes the vector kernels take: at least 2x2 (sample_gray's general
// case) and indexable by 32-bit integers.
bool vector_plane(const FloatImage& plane) {
  return plane.width() >= 2 && plane.height() >= 2 &&
         double(plane.width()) * double(plane.height()) < double(std::numeric_limits<std::int32_t>::max());
}

#ifdef MESHNBV_X86_SIMD

// Four bilinear samples at (x, y), sample_gray's arithmetic lane by lane;
// false when a point is outside [0, W-1] x [0, H-1] or NaN. The four cell
// corners of each lane are read as two 8-byte pairs (row iy and iy + 1),
// which this machine's loads serve faster than gathers.
__attribute__((target("avx2"))) inline bool bilinear4(const float* data, int width, int height, __m256d x,
                                                      __m256d y, float* out) {
  const __m256d zero = _mm256_setzero_pd();
  const __m256d inside =
      _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(x, zero, _CMP_GE_OQ), _mm256_cmp_pd(y, zero, _CMP_GE_OQ)),
                    _mm256_and_pd(_mm256_cmp_pd(x, _mm256_set1_pd(width - 1.0), _CMP_LE_OQ),
                                  _mm256_cmp_pd(y, _mm256_set1_pd(height - 1.0), _CMP_LE_OQ)));
  if (_mm256_movemask_pd(inside) != 0xF) return false;
  const __m128i ix = _mm_min_epi32(_mm256_cvttpd_epi32(x), _mm_set1_epi32(width - 2));
  const __m128i iy = _mm_min_epi32(_mm256_cvttpd_epi32(y), _mm_set1_epi32(height - 2));
  const __m128 wx = _mm256_cvtpd_ps(_mm256_sub_pd(x, _mm256_cvtepi32_pd(ix)));
  const __m128 wy = _mm256_cvtpd_ps(_mm256_sub_pd(y, _mm256_cvtepi32_pd(iy)));
  alignas(16) std::int32_t at[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(at),
                  _mm_add_epi32(_mm_mullo_epi32(iy, _mm_set1_epi32(width)), ix));
  auto pair = [&](std::int32_t i) {
    double v;
    std::memcpy(&v, data + i, sizeof v);
    return v;
  };
  // Lane k's (r0[0], r0[1]) and (r1[0], r1[1]).
  const __m128 t01 = _mm_castpd_ps(_mm_set_pd(pair(at[1]), pair(at[0])));
  const __m128 t23 = _mm_castpd_ps(_mm_set_pd(pair(at[3]), pair(at[2])));
  const __m128 u01 = _mm_castpd_ps(_mm_set_pd(pair(at[1] + width), pair(at[0] + width)));
  const __m128 u23 = _mm_castpd_ps(_mm_set_pd(pair(at[3] + width), pair(at[2] + width)));
  const __m128 a = _mm_shuffle_ps(t01, t23, _MM_SHUFFLE(2, 0, 2, 0)),
               b = _mm_shuffle_ps(t01, t23, _MM_SHUFFLE(3, 1, 3, 1));
  const __m128 c = _mm_shuffle_ps(u01, u23, _MM_SHUFFLE(2, 0, 2, 0)),
               d = _mm_shuffle_ps(u01, u23, _MM_SHUFFLE(3, 1, 3, 1));
  const __m128 one = _mm_set1_ps(1.0f);
  const __m128 ux = _mm_sub_ps(one, wx), uy = _mm_sub_ps(one, wy);
  // (1 - wy) * ((1 - wx) * r0[0] + wx * r0[1]) + wy * ((1 - wx) * r1[0] + wx * r1[1])
  const __m128 top = _mm_add_ps(_mm_mul_ps(ux, a), _mm_mul_ps(wx, b));
  const __m128 bottom = _mm_add_ps(_mm_mul_ps(ux, c), _mm_mul_ps(wx, d));
  _mm_storeu_ps(out, _mm_add_ps(_mm_mul_ps(uy, top), _mm_mul_ps(wy, bottom)));
  return true;
}

__attribute__((target("avx2"))) bool avx2_points(const FloatImage& plane, const double* x, const double* y,
                                                 std::size_t n, float* out) {
  const float* data = plane.data();
  const int w = plane.width(), h = plane.height();
  std::size_t k = 0;
  for (; k + 4 <= n; k += 4)
    if (!bilinear4(data, w, h, _mm256_loadu_pd(x + k), _mm256_loadu_pd(y + k), out + k)) return false;
  return scalar_points(plane, x + k, y + k, n - k, out + k);
}

__attribute__((target("avx2"))) bool avx2_homogeneous(const FloatImage& plane, const double* hx,
                                                      const double* hy, const double* hz, std::size_t n,
                                                      float* out) {
  const float* data = plane.data();
  const int w = plane.width(), h = plane.height();
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  std::size_t k = 0;
  for (; k + 4 <= n; k += 4) {
    const __m256d z = _mm256_loadu_pd(hz + k);
    if (_mm256_movemask_pd(_mm256_cmp_pd(z, zero, _CMP_GT_OQ)) != 0xF) return false;
    const __m256d inv = _mm256_div_pd(one, z);
    if (!bilinear4(data, w, h, _mm256_mul_pd(_mm256_loadu_pd(hx + k), inv),
                   _mm256_mul_pd(_mm256_loadu_pd(hy + k), inv), out + k))
      return false;
  }
  return scalar_homogeneous(plane, hx + k, hy + k, hz + k, n - k, out + k);
}

#endif  // MESHNBV_X86_SIMD

SimdLevel detect() {
#ifdef MESHNBV_X86_SIMD
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2")) return SimdLevel::avx2;
#endif
  return SimdLevel::scalar;
}

SimdLevel initial_level() {
  const char* env = std::getenv("MESHNBV_SIMD");
  if (env && std::strcmp(env, "scalar") == 0) return SimdLevel::scalar;
  return simd_supported();
}

std::atomic<int>& level_in_use() {
  static std::atomic<int> level{int(initial_level())};
  return level;
}

}  // namespace

const char* simd_name(SimdLevel level) { return level == SimdLevel::avx2 ? "avx2" : "scalar"; }

SimdLevel simd_supported() {
  static const SimdLevel supported = detect();
  return supported;
}

SimdLevel simd_level() { return SimdLevel(level_in_use().load(std::memory_order_relaxed)); }

SimdLevel set_simd_level(SimdLevel level) {
  if (int(level) > int(simd_supported())) level = simd_supported();
  level_in_use().store(int(level), std::memory_order_relaxed);
  return level;
}

bool sample_gray_points(const FloatImage& plane, const double* x, const double* y, std::size_t n,
                        float* out) {
#ifdef MESHNBV_X86_SIMD
  if (simd_level() == SimdLevel::avx2 && vector_plane(plane)) return avx2_points(plane, x, y, n, out);
#endif
  return scalar_points(plane, x, y, n, out);
}

bool sample_gray_homogeneous(const FloatImage& plane, const double* hx, const double* hy, const double* hz,
                             std::size_t n, float* out) {
#ifdef MESHNBV_X86_SIMD
  if (simd_level() == SimdLevel::avx2 && vector_plane(plane))
    return avx2_homogeneous(plane, hx, hy, hz, n, out);
#endif
  return scalar_homogeneous(plane, hx, hy, hz, n, out);
}

}  // namespace meshnbv
