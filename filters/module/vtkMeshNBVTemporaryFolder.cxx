#include "vtkMeshNBVTemporaryFolder.h"

#include "meshnbv/error.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace vtkMeshNBV
{

TemporaryFolder::TemporaryFolder()
{
  std::error_code ec;
  std::string pattern = (std::filesystem::temp_directory_path(ec) / "meshnbv-vtk-XXXXXX").string();
  if (ec || !::mkdtemp(pattern.data()))
  {
    throw meshnbv::Error("cannot create a temporary folder (" + pattern + ")");
  }
  this->Folder = pattern;
}

TemporaryFolder::~TemporaryFolder()
{
  std::error_code ec;
  std::filesystem::remove_all(this->Folder, ec);
}

} // namespace vtkMeshNBV
