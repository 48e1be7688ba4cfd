// The decoding share of bench/photos/run.sh: decodes a list of photos the way
// compute_pri does (Image::load, then FloatImage::luminance_of), on a given
// number of threads, each photo once and dropped after, and prints one JSON
// object with the seconds of each part. Usage: photo_decode LIST THREADS
// (LIST: one image path per line).
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "meshnbv/error.h"
#include "meshnbv/image.h"

using namespace meshnbv;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: photo_decode LIST THREADS\n";
    return 2;
  }
  std::vector<std::string> paths;
  std::ifstream list(argv[1]);
  for (std::string line; std::getline(list, line);)
    if (!line.empty()) paths.push_back(line);
  const int threads = std::stoi(argv[2]);
  if (paths.empty() || threads < 1) {
    std::cerr << "photo_decode: no photos listed in " << argv[1] << " or bad thread count\n";
    return 2;
  }
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  using clock = std::chrono::steady_clock;
  const auto seconds = [](clock::duration d) { return std::chrono::duration<double>(d).count(); };

  // Decode only, photos in parallel (one photo per task).
  std::atomic<long long> pixels{0};
  auto t0 = clock::now();
  try {
    tbb::parallel_for(
        std::size_t(0), paths.size(),
        [&](std::size_t i) {
          const Image im = Image::load(paths[i]);
          pixels += static_cast<long long>(im.width()) * im.height();
        },
        tbb::simple_partitioner());
  } catch (const Error& e) {
    std::cerr << "photo_decode: " << e.what() << "\n";
    return 1;
  }
  const double decode = seconds(clock::now() - t0);

  // Decode and luminance planes, as compute_pri's prefetch does.
  t0 = clock::now();
  tbb::parallel_for(
      std::size_t(0), paths.size(),
      [&](std::size_t i) {
        const FloatImage plane = FloatImage::luminance_of(Image::load(paths[i]));
        if (plane.width() == 0) std::abort();
      },
      tbb::simple_partitioner());
  const double decode_and_luminance = seconds(clock::now() - t0);

  std::printf(
      "{\"photos\": %zu, \"threads\": %d, \"megapixels\": %.3f, \"decode_seconds\": %.3f, "
      "\"decode_and_luminance_seconds\": %.3f}\n",
      paths.size(), threads, double(pixels) / 1e6, decode, decode_and_luminance);
  return 0;
}
