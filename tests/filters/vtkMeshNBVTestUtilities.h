// Shared by the VTK tests: a check macro that returns EXIT_FAILURE with the
// reason, an observer that records an algorithm's errors and warnings
// (which also keeps them off the console), and the test arguments.
#ifndef vtkMeshNBVTestUtilities_h
#define vtkMeshNBVTestUtilities_h

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#define MESHNBV_CHECK(condition, message)                                                          \
  do                                                                                               \
  {                                                                                                \
    if (!(condition))                                                                              \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": FAILED " #condition ": " << message << "\n";  \
      return EXIT_FAILURE;                                                                         \
    }                                                                                              \
  } while (false)

namespace vtkMeshNBVTest
{

// Records ErrorEvent and WarningEvent messages.
class MessageObserver : public vtkCommand
{
public:
  static MessageObserver* New() { return new MessageObserver; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    const std::string text = data ? static_cast<const char*>(data) : "";
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings).push_back(text);
  }
  bool HasError(const std::string& part) const
  {
    for (const std::string& e : this->Errors)
    {
      if (e.find(part) != std::string::npos)
      {
        return true;
      }
    }
    return false;
  }
  std::string AllErrors() const
  {
    std::string all;
    for (const std::string& e : this->Errors)
    {
      all += "[" + e + "] ";
    }
    return all.empty() ? "(none)" : all;
  }
  void Clear()
  {
    this->Errors.clear();
    this->Warnings.clear();
  }
  std::vector<std::string> Errors, Warnings;
};

// Observes `algorithm`'s messages; the executive's own "returned failure"
// report goes to `executive` (it only restates that the algorithm failed).
struct Watch
{
  explicit Watch(vtkAlgorithm* algorithm)
  {
    algorithm->AddObserver(vtkCommand::ErrorEvent, this->Algorithm);
    algorithm->AddObserver(vtkCommand::WarningEvent, this->Algorithm);
    algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this->Executive);
  }
  vtkSmartPointer<MessageObserver> Algorithm = vtkSmartPointer<MessageObserver>::New();
  vtkSmartPointer<MessageObserver> Executive = vtkSmartPointer<MessageObserver>::New();
};

// Arguments of every VTK test: the synthetic project folder (made by the
// vtk/setup fixture) and a scratch folder of the test's own.
struct Arguments
{
  std::string Project;
  std::string Scratch;
  std::string ProjectFile() const { return this->Project + "/project.mlp"; }
};

inline bool ParseArguments(int argc, char* argv[], Arguments* args)
{
  if (argc < 3)
  {
    std::cerr << "usage: " << argv[0] << " <project folder> <scratch folder>\n";
    return false;
  }
  args->Project = argv[1];
  args->Scratch = argv[2];
  std::error_code ec;
  std::filesystem::remove_all(args->Scratch, ec);
  std::filesystem::create_directories(args->Scratch, ec);
  return !ec;
}

// Both NaN, or within `tolerance`.
inline bool SameValue(double a, double b, double tolerance)
{
  return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) <= tolerance;
}

} // namespace vtkMeshNBVTest

#endif
