/**
 * @class   vtkMeshNBVSceneReader
 * @brief   reads a calibrated scene (mesh + views) for next-best-view planning
 *
 * vtkMeshNBVSceneReader reads any scene the MeshNBV core reads: a MeshLab
 * project (.mlp), a MeshNBV JSON scene, a Middlebury folder (*_par.txt), a
 * COLMAP text model folder or Bundler's bundle.out. It is the entry point of
 * the pipeline of Morreale, Romanoni, Matteucci, "Predicting the Next Best
 * View for 3D Mesh Refinement" (2018): vtkMeshNBVPRIFilter measures how
 * well the photos agree about each face, vtkMeshNBVNextBestViewFilter
 * suggests where to take the next photos.
 *
 * Output 0 is the mesh (vtkPolyData of triangles; per-face attributes of the
 * file, e.g. a PLY's `quality`, become float cell arrays; field data
 * "MeshFileName"). Output 1 holds the views: a vtkMultiBlockDataSet with one
 * vtkImageData per view, named by its label, carrying its camera in field
 * data ("Label", "ImageSize" (W, H), "K" and "R" (9 components, row-major),
 * "t" (3), "Distortion" (k1, k2), "Used", "ImagePath") and, when the view has
 * an image and LoadImages is on, its pixels as unsigned char point scalars
 * "Pixels", rows flipped the way vtkPNGReader flips them. Cameras follow
 * the core's convention (docs/conventions.md): x_cam = R X + t, pixel
 * centres at integer coordinates, y down.
 *
 * Errors of the core (missing files, malformed projects, ...) are reported
 * through vtkErrorMacro with the core's message, and both outputs stay
 * empty. The reader's warnings (e.g. skipped Bundler cameras) become
 * vtkWarningMacro.
 *
 * @sa vtkMeshNBVPRIFilter vtkMeshNBVNextBestViewFilter vtkMeshNBVSuggestionWriter
 */

#ifndef vtkMeshNBVSceneReader_h
#define vtkMeshNBVSceneReader_h

#include "vtkMeshNBVIOModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For std::string members

class vtkMultiBlockDataSet;

class VTKMESHNBVIO_EXPORT vtkMeshNBVSceneReader : public vtkPolyDataAlgorithm
{
public:
  static vtkMeshNBVSceneReader* New();
  vtkTypeMacro(vtkMeshNBVSceneReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The scene: a .mlp, a .json, a Middlebury folder or *_par.txt, a COLMAP
   * model folder, a bundle.out. No default.
   */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /**
   * The scene's format: "auto" (default: from the path), "mlp", "json",
   * "middlebury", "colmap" or "bundler". The CLI's --format.
   */
  vtkSetStdStringFromCharMacro(Format);
  vtkGetCharFromStdStringMacro(Format);
  ///@}

  ///@{
  /**
   * A mesh file (.ply, .obj, .off) to use instead of the scene's own, or for
   * formats that carry none. Empty by default. The CLI's --mesh.
   */
  vtkSetStdStringFromCharMacro(Mesh);
  vtkGetCharFromStdStringMacro(Mesh);
  ///@}

  ///@{
  /**
   * The folder of the images for formats that name them relatively (COLMAP,
   * Bundler). Empty by default. The CLI's --image-dir.
   */
  vtkSetStdStringFromCharMacro(ImageDir);
  vtkGetCharFromStdStringMacro(ImageDir);
  ///@}

  ///@{
  /**
   * Whether the view blocks carry their pixels (default on). Off keeps only
   * the cameras and image paths: the photo-consistency filter then reads the
   * images itself through the core's bounded image cache, which suits
   * projects with many large photos.
   */
  vtkSetMacro(LoadImages, vtkTypeBool);
  vtkGetMacro(LoadImages, vtkTypeBool);
  vtkBooleanMacro(LoadImages, vtkTypeBool);
  ///@}

  /**
   * The views (output port 1).
   */
  vtkMultiBlockDataSet* GetViewsOutput();
  vtkAlgorithmOutput* GetViewsOutputPort() { return this->GetOutputPort(1); }

protected:
  vtkMeshNBVSceneReader();
  ~vtkMeshNBVSceneReader() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  std::string Format;
  std::string Mesh;
  std::string ImageDir;
  vtkTypeBool LoadImages;

private:
  vtkMeshNBVSceneReader(const vtkMeshNBVSceneReader&) = delete;
  void operator=(const vtkMeshNBVSceneReader&) = delete;
};

#endif
