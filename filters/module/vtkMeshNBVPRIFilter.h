/**
 * @class   vtkMeshNBVPRIFilter
 * @brief   per-face Photo-consistency Reconstruction Index (PRI) of a mesh
 *
 * vtkMeshNBVPRIFilter computes, for every triangle of a reconstructed mesh,
 * how well the calibrated photos agree about it: the Photo-consistency
 * Reconstruction Index of Morreale, Romanoni, Matteucci, "Predicting the
 * Next Best View for 3D Mesh Refinement" (2018). Each face is sampled on a
 * barycentric lattice, the samples are projected into every view that sees
 * the face, and the patches of every pair of views are compared (SSD or
 * NCC), or the offset along the normal where the views agree best is
 * found (OFFSET, in scene units). Higher is worse; faces seen by fewer
 * than two views get NaN. The
 * work is done by the MeshNBV core (meshnbv::compute_pri, docs/pri.md);
 * this class only converts data.
 *
 * Input 0: the mesh (vtkPolyData of triangles only). Input 1: the views, a
 * vtkMultiBlockDataSet of vtkImageData as vtkMeshNBVSceneReader's output 1
 * makes them (camera in field data; pixels as point scalars, or else the
 * file named by "ImagePath"). Views with "Used" = 0 do not take part.
 * Pixels (unsigned char, or unsigned short scaled to 8 bits; 1 to 4
 * components) are converted once and handed to the core in memory: no file
 * is written or read for them.
 *
 * Output: the mesh with the cell arrays PRI (float, NaN where undefined),
 * PRIViews (int, the views compared per face), and what each value rests
 * on: PRIPairs (int, comparisons averaged: view pairs for SSD/NCC, views
 * against the reference for OFFSET), PRISamples (int, samples per view) and
 * PRITexture (float, mean standard deviation of the samples, intensity in
 * [0, 1]; NaN where fewer than 2 views), named by PRIArrayName,
 * PRIViewsArrayName, PRIPairsArrayName, PRISamplesArrayName and
 * PRITextureArrayName; PRI is the active cell scalars. The same values as the PLY of `meshnbv pri`
 * (quality, pri_views, pri_pairs, pri_samples, pri_texture).
 *
 * The options carry the names and defaults of the core, the command line
 * (`meshnbv pri`) and the JSON summary, in CamelCase. Progress is reported
 * through UpdateProgress; setting AbortExecute (e.g. from a ProgressEvent
 * observer) cancels the computation and leaves the output empty. Errors
 * (no views input, a view without camera data, a missing image, a mesh
 * that is not made of triangles, ...) are reported with vtkErrorMacro and
 * the core's message, and the output stays empty.
 *
 * @sa vtkMeshNBVSceneReader vtkMeshNBVNextBestViewFilter
 */

#ifndef vtkMeshNBVPRIFilter_h
#define vtkMeshNBVPRIFilter_h

#include "vtkMeshNBVFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For std::string members

class VTKMESHNBVFILTERS_EXPORT vtkMeshNBVPRIFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkMeshNBVPRIFilter* New();
  vtkTypeMacro(vtkMeshNBVPRIFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // The positions of the words in the core's option table (`measure`:
  // ssd, ncc, offset), checked by the tests.
  enum MeasureType
  {
    SSD = 0,   // mean squared difference (the paper's choice)
    NCC = 1,   // (1 - normalised cross-correlation) / 2
    OFFSET = 2 // distance along the normal to where the views agree best (scene units)
  };

  ///@{
  /**
   * What PRI measures (`measure`): SSD, NCC or OFFSET.
   * GetMeasureAsString gives the table's word ("ssd", "ncc", "offset").
   */
  vtkSetMacro(Measure, int);
  vtkGetMacro(Measure, int);
  void SetMeasureToSSD() { this->SetMeasure(SSD); }
  void SetMeasureToNCC() { this->SetMeasure(NCC); }
  void SetMeasureToOffset() { this->SetMeasure(OFFSET); }
  const char* GetMeasureAsString();
  ///@}

  ///@{
  /**
   * Lattice subdivisions per face side (`samples_per_side`); 0 =
   * automatic: the largest projected edge in pixels, clamped to [2, 32].
   */
  vtkSetMacro(SamplesPerSide, int);
  vtkGetMacro(SamplesPerSide, int);
  ///@}

  ///@{
  /**
   * Views compared per face (`max_views_per_face`), smallest incidence angle
   * first; 0 = all of them.
   */
  vtkSetMacro(MaxViewsPerFace, int);
  vtkGetMacro(MaxViewsPerFace, int);
  ///@}

  ///@{
  /**
   * Views seeing a face at a larger angle to its normal, in degrees, do not
   * count as seeing it (`max_incidence_angle`; 90 = plain
   * back-face rule).
   */
  vtkSetMacro(MaxIncidenceAngle, double);
  vtkGetMacro(MaxIncidenceAngle, double);
  ///@}

  ///@{
  /**
   * A JPEG photo read from its file may be decoded 2, 4 or 8 times smaller
   * (the largest power of two up to this) when every face that may use it
   * has its lattice at least that many pixels apart there: faster, but PRI
   * finds error less well (`max_image_reduction`, in [1, 8]; 1 = always
   * full resolution, the default).
   */
  vtkSetMacro(MaxImageReduction, int);
  vtkGetMacro(MaxImageReduction, int);
  ///@}

  ///@{
  /**
   * Keep the sampling lattice this many pixels inside each face in every
   * view (`edge_margin`; 0 = the whole face).
   */
  vtkSetMacro(EdgeMargin, double);
  vtkGetMacro(EdgeMargin, double);
  ///@}

  ///@{
  /**
   * OFFSET: each face's signed offset is averaged over the connected faces
   * within 2 sigma, Gaussian-weighted with sigma this many pixels of its
   * reference view (`support_radius`).
   */
  vtkSetMacro(SupportRadius, double);
  vtkGetMacro(SupportRadius, double);
  ///@}

  ///@{
  /**
   * OFFSET: offsets along the normal are swept up to this disparity in
   * pixels, on both sides of the face (`offset_range`).
   */
  vtkSetMacro(OffsetRange, double);
  vtkGetMacro(OffsetRange, double);
  ///@}

  ///@{
  /**
   * OFFSET: hypotheses on each side of the face (`offset_steps`; the step
   * is OffsetRange / OffsetSteps).
   */
  vtkSetMacro(OffsetSteps, int);
  vtkGetMacro(OffsetSteps, int);
  ///@}

  ///@{
  /**
   * Also require a face's centroid and edge midpoints to be unoccluded
   * (`check_interior_occlusion`).
   */
  vtkSetMacro(CheckInteriorOcclusion, vtkTypeBool);
  vtkGetMacro(CheckInteriorOcclusion, vtkTypeBool);
  vtkBooleanMacro(CheckInteriorOcclusion, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Compare R, G, B instead of luminance (`color`).
   */
  vtkSetMacro(Color, vtkTypeBool);
  vtkGetMacro(Color, vtkTypeBool);
  vtkBooleanMacro(Color, vtkTypeBool);
  ///@}

  ///@{
  /**
   * NCC: patches with a lower variance are textureless
   * (`textureless_variance`).
   */
  vtkSetMacro(TexturelessVariance, double);
  vtkGetMacro(TexturelessVariance, double);
  ///@}

  ///@{
  /**
   * Worker threads (`threads`); 0 = all cores. The result does not
   * depend on it.
   */
  vtkSetMacro(Threads, int);
  vtkGetMacro(Threads, int);
  ///@}

  ///@{
  /**
   * Names of the output cell arrays: PRI (default "PRI") and the number of
   * views compared per face (default "PRIViews").
   */
  vtkSetStdStringFromCharMacro(PRIArrayName);
  vtkGetCharFromStdStringMacro(PRIArrayName);
  vtkSetStdStringFromCharMacro(PRIViewsArrayName);
  vtkGetCharFromStdStringMacro(PRIViewsArrayName);
  ///@}

  ///@{
  /**
   * Names of the evidence cell arrays (defaults "PRIPairs", "PRISamples",
   * "PRITexture").
   */
  vtkSetStdStringFromCharMacro(PRIPairsArrayName);
  vtkGetCharFromStdStringMacro(PRIPairsArrayName);
  vtkSetStdStringFromCharMacro(PRISamplesArrayName);
  vtkGetCharFromStdStringMacro(PRISamplesArrayName);
  vtkSetStdStringFromCharMacro(PRITextureArrayName);
  vtkGetCharFromStdStringMacro(PRITextureArrayName);
  ///@}

  /**
   * Connect the views (input port 1).
   */
  void SetViewsConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetViewsData(vtkDataObject* views) { this->SetInputData(1, views); }

protected:
  vtkMeshNBVPRIFilter();
  ~vtkMeshNBVPRIFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Measure;
  int SamplesPerSide;
  int MaxViewsPerFace;
  double MaxIncidenceAngle;
  int MaxImageReduction;
  double EdgeMargin;
  double SupportRadius;
  double OffsetRange;
  int OffsetSteps;
  vtkTypeBool CheckInteriorOcclusion;
  vtkTypeBool Color;
  double TexturelessVariance;
  int Threads;
  std::string PRIArrayName;
  std::string PRIViewsArrayName;
  std::string PRIPairsArrayName;
  std::string PRISamplesArrayName;
  std::string PRITextureArrayName;

private:
  vtkMeshNBVPRIFilter(const vtkMeshNBVPRIFilter&) = delete;
  void operator=(const vtkMeshNBVPRIFilter&) = delete;
};

#endif
