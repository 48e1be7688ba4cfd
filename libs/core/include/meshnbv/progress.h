// One progress/cancel callback for the whole core. Front ends map it to a
// terminal progress bar (CLI), UpdateProgress/CheckAbort (VTK) and
// cb(percent, msg) (MeshLab).
#pragma once

#include <functional>
#include <string>

namespace meshnbv {

// `fraction` in [0, 1] of the current `stage` (e.g. "visibility", "pri").
// Return false to ask the running operation to stop: it then throws
// meshnbv::Cancelled at the next safe point.
using ProgressCallback = std::function<bool(double fraction, const std::string& stage)>;

// Calls the callback (if any) and throws Cancelled when it says stop.
void report_progress(const ProgressCallback& callback, double fraction, const std::string& stage);

}  // namespace meshnbv
