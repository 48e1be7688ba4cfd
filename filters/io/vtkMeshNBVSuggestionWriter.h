/**
 * @class   vtkMeshNBVSuggestionWriter
 * @brief   writes next-best-view suggestions as JSON or as a MeshLab project
 *
 * vtkMeshNBVSuggestionWriter writes the suggestions of
 * vtkMeshNBVNextBestViewFilter (Morreale, Romanoni, Matteucci, "Predicting
 * the Next Best View for 3D Mesh Refinement", 2018) the way `meshnbv
 * suggest` does, through the MeshNBV core:
 *
 * - FileName ending in .json: the core's suggestions document (schema in
 *   docs/formats.md), taken from the table's field data "SuggestionsJSON".
 *   Only input 0 is needed.
 * - FileName ending in .mlp: the scene as a MeshLab project with one raster
 *   without image per suggestion (labels nbv_1, ...). Needs the views
 *   (input 1), whose images it references by "ImagePath" (a view with
 *   pixels but no ImagePath is an error: a project references image files);
 *   the mesh is referenced where it is on disk (the mesh's field
 *   data "MeshFileName", as vtkMeshNBVSceneReader sets it), else written
 *   beside the project from input 2.
 *
 * Input 0: the suggestions table (output port 1 of
 * vtkMeshNBVNextBestViewFilter). Input 1 (optional): the views. Input 2
 * (optional): the mesh. Existing files are kept unless Overwrite is on (the
 * CLI's --overwrite). Writes are atomic. Errors are reported with
 * vtkErrorMacro and the core's message, and Write() returns 0.
 *
 * @sa vtkMeshNBVNextBestViewFilter vtkMeshNBVSceneReader
 */

#ifndef vtkMeshNBVSuggestionWriter_h
#define vtkMeshNBVSuggestionWriter_h

#include "vtkMeshNBVIOModule.h" // For export macro
#include "vtkWriter.h"

#include <string> // For std::string members

class VTKMESHNBVIO_EXPORT vtkMeshNBVSuggestionWriter : public vtkWriter
{
public:
  static vtkMeshNBVSuggestionWriter* New();
  vtkTypeMacro(vtkMeshNBVSuggestionWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The file to write: *.json or *.mlp. No default.
   */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /**
   * Replace existing files (`overwrite`, default off).
   */
  vtkSetMacro(Overwrite, vtkTypeBool);
  vtkGetMacro(Overwrite, vtkTypeBool);
  vtkBooleanMacro(Overwrite, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Connect the views (input port 1) and the mesh (input port 2), needed
   * for .mlp.
   */
  void SetViewsConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetViewsData(vtkDataObject* views) { this->SetInputData(1, views); }
  void SetMeshConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(2, output); }
  void SetMeshData(vtkDataObject* mesh) { this->SetInputData(2, mesh); }
  ///@}

protected:
  vtkMeshNBVSuggestionWriter();
  ~vtkMeshNBVSuggestionWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  std::string FileName;
  vtkTypeBool Overwrite;

private:
  vtkMeshNBVSuggestionWriter(const vtkMeshNBVSuggestionWriter&) = delete;
  void operator=(const vtkMeshNBVSuggestionWriter&) = delete;
};

#endif
