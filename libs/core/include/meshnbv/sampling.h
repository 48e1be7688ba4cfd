#pragma once
// Bilinear sampling of a one-channel plane at many points, by the widest
// instruction set the processor runs (chosen at run time): the inner loop
// of PRI. Every kernel computes what FloatImage::sample_gray computes, in
// the same order and precision (no fused multiply-add), so its samples are
// bitwise those of the scalar loop.
#include <cstddef>

#include "meshnbv/image.h"

namespace meshnbv {

enum class SimdLevel { scalar = 0, avx2 = 1 };

// "scalar" or "avx2".
const char* simd_name(SimdLevel level);
// The widest level this processor runs.
SimdLevel simd_supported();
// The level in use: simd_supported(), or scalar when the environment
// variable MESHNBV_SIMD is "scalar" at the first call.
SimdLevel simd_level();
// Sets the level in use (for tests and benchmarks), at most simd_supported();
// returns the level set. Not to be called while sampling runs.
SimdLevel set_simd_level(SimdLevel level);

// out[k] = plane.sample_gray(x[k], y[k]) for k < n; false (out unspecified)
// when any point lies outside the plane or is NaN.
bool sample_gray_points(const FloatImage& plane, const double* x, const double* y, std::size_t n, float* out);

// The same at the perspective points (hx[k] / hz[k], hy[k] / hz[k]), each
// as hx[k] * (1 / hz[k]); false when any hz[k] is not > 0.
bool sample_gray_homogeneous(const FloatImage& plane, const double* hx, const double* hy, const double* hz,
                             std::size_t n, float* out);

}  // namespace meshnbv
