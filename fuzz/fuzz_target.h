// Shared by the fuzz targets (fuzz_*.cpp).
//
// Each target is written once with MESHNBV_FUZZ_TARGET(name) and built two
// ways:
// - with -DMESHNBV_LIBFUZZER (MESHNBV_BUILD_FUZZ=ON, clang): the body is
//   LLVMFuzzerTestOneInput and the executable is a libFuzzer fuzzer;
// - otherwise (every test build): the body is registered under `name` in
//   meshnbv_fuzz_replay, which ctest runs over the seeds and every crasher
//   found so far (fuzz/regressions/<name>/), so each stays a regression test.
//
// Contract checked by every target: a reader either returns a valid result
// or throws meshnbv::Error. Any other exception escapes (std::terminate, a
// crash to libFuzzer); crashes, leaks, UB, hangs and huge allocations are
// caught by the sanitizers and libFuzzer's limits. Round trips through the
// writers must give back what was read (FUZZ_CHECK).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "meshnbv/mesh.h"
#include "meshnbv/scene.h"

namespace meshnbv::fuzz {

using TargetFn = int (*)(const std::uint8_t*, std::size_t);
bool register_target(const char* name, TargetFn fn);
// Replay build only: the registered targets.
TargetFn find_target(const std::string& name);
std::vector<std::string> target_names();

// A private folder on tmpfs (or $TMPDIR) for this process, created on first
// use and removed at exit, holding the fixture files the scene formats may
// refer to: mesh.ply, mesh.obj, mesh.off (a pyramid), image.png (8x6),
// images/a.png, images/b.png, c.png, v0.png, v1.png.
const std::string& scratch();
// Writes `size` bytes to scratch()/name and returns the full path.
std::string write_input(const std::string& name, const std::uint8_t* data, std::size_t size);
// Splits data at the first "\n%%%%\n" (two-file formats); no separator:
// everything is the first part.
void split_two(const std::uint8_t* data, std::size_t size, std::string* first,
               std::string* second);
std::string write_text(const std::string& name, const std::string& text);

// Checks of a successfully read mesh or scene: validation, mesh statistics,
// and a round trip through the writers that must read back the same.
void exercise_mesh(const TriangleMesh& mesh);
void exercise_scene(const Scene& scene);

[[noreturn]] void check_failed(const char* what, const char* file, int line);

}  // namespace meshnbv::fuzz

#define FUZZ_CHECK(cond) \
  ((cond) ? (void)0 : ::meshnbv::fuzz::check_failed(#cond, __FILE__, __LINE__))

#ifdef MESHNBV_LIBFUZZER
#define MESHNBV_FUZZ_TARGET(name) \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
#else
#define MESHNBV_FUZZ_TARGET(name)                                                      \
  static int meshnbv_fuzz_##name(const std::uint8_t* data, std::size_t size);          \
  [[maybe_unused]] static const bool meshnbv_fuzz_registered_##name =                  \
      ::meshnbv::fuzz::register_target(#name, meshnbv_fuzz_##name);                    \
  static int meshnbv_fuzz_##name(const std::uint8_t* data, std::size_t size)
#endif
