#include "vtkMeshNBVProgress.h"

#include "vtkAlgorithm.h"

#include <thread>

namespace vtkMeshNBV
{

meshnbv::ProgressCallback MakeProgressCallback(
  vtkAlgorithm* algorithm, std::vector<std::pair<std::string, double>> stages)
{
  const std::thread::id owner = std::this_thread::get_id();
  return [algorithm, stages = std::move(stages), owner](double fraction, const std::string& stage) {
    if (std::this_thread::get_id() == owner)
    {
      double start = 0, share = 1;
      for (const auto& [name, weight] : stages)
      {
        if (name == stage)
        {
          share = weight;
          break;
        }
        start += weight;
      }
      if (start >= 1.0)  // not a known stage
      {
        start = 0;
      }
      algorithm->SetProgressText(stage.c_str());
      algorithm->UpdateProgress(start + share * fraction);
    }
    return !algorithm->GetAbortExecute();
  };
}

} // namespace vtkMeshNBV
