#pragma once
// MESHNBV_X86_SIMD: the compiler can build x86 vector kernels for a target
// chosen per function (__attribute__((target("avx2")))), called only when
// simd_level() (meshnbv/sampling.h) allows.
#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define MESHNBV_X86_SIMD 1
#include <immintrin.h>
#endif
