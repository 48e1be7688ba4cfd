// The report's 3-D viewer: three.js and libs/report/web/src bundled into one
// classic script (esbuild, at build time) and embedded here as bytes
// (libs/report/web/embed.mjs writes the definition into the build tree).
#pragma once

#include <cstddef>

namespace meshnbv::report_detail {

extern const unsigned char kViewerBundle[];
extern const std::size_t kViewerBundleSize;

}  // namespace meshnbv::report_detail
