// Private to the MeshNBV VTK module: a fresh private folder under the
// system's temporary folder, removed with everything in it when the object
// dies. The PRI filter hands pipeline pixels to the core through it (the
// core reads images by path).
#ifndef vtkMeshNBVTemporaryFolder_h
#define vtkMeshNBVTemporaryFolder_h

#include <string>

namespace vtkMeshNBV
{

class TemporaryFolder
{
public:
  TemporaryFolder(); // throws meshnbv::Error when the folder cannot be made
  ~TemporaryFolder();
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  const std::string& Path() const { return this->Folder; }

private:
  std::string Folder;
};

} // namespace vtkMeshNBV

#endif
// VTK-HeaderTest-Exclude: vtkMeshNBVTemporaryFolder.h
