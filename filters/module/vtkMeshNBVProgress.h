// Private to the MeshNBV VTK module: the core's one progress/cancel callback
// mapped to a VTK algorithm. Each core stage ("visibility", "view selection", "pri",
// "suggest") gets a share of the algorithm's progress; the callback reports
// through UpdateProgress (on the thread that runs RequestData only: VTK
// observers, Python ones included, are not thread-safe) and asks the core
// to stop when the algorithm's AbortExecute flag is set.
#ifndef vtkMeshNBVProgress_h
#define vtkMeshNBVProgress_h

#include "meshnbv/progress.h"

#include <string>
#include <utility>
#include <vector>

class vtkAlgorithm;

namespace vtkMeshNBV
{

// `stages`: (name, share of the whole) in the order the core runs them;
// shares should sum to 1. Unknown stages report their fraction unchanged.
meshnbv::ProgressCallback MakeProgressCallback(
  vtkAlgorithm* algorithm, std::vector<std::pair<std::string, double>> stages);

} // namespace vtkMeshNBV

#endif
// VTK-HeaderTest-Exclude: vtkMeshNBVProgress.h
