/**
 * @class   vtkMeshNBVNextBestViewFilter
 * @brief   suggests where the next photos should be taken to refine a mesh
 *
 * vtkMeshNBVNextBestViewFilter implements the next-best-view step of
 * Morreale, Romanoni, Matteucci, "Predicting the Next Best View for 3D Mesh
 * Refinement" (2018): the K faces with the highest Photo-consistency
 * Reconstruction Index form the worst region, candidate camera poses are
 * scored by an energy of occlusion, focus, parallax and incidence terms
 * over the region's vertices, and the best poses are returned, greedily in
 * a batch of Top. The work is done by the MeshNBV core
 * (meshnbv::suggest_views, docs/nbv.md); this class only converts data.
 *
 * Input 0: the mesh with a PRI cell array (named by PRIArrayName, e.g. the
 * output of vtkMeshNBVPRIFilter). Input 1: the existing views (as
 * vtkMeshNBVSceneReader's output 1; views with pixels or an image path and
 * "Used" = 1 are the existing ones). Input 2 (optional): candidate views for
 * Candidates = Given; without it the views of input 1 that have no image or
 * are marked unused are the candidates.
 *
 * Output 0: one pyramid per suggestion (apex at the camera centre, base =
 * the image's outer corners at FrustumDepth, or at the core's default share
 * of the distance to the point looked at when FrustumDepth is 0, as `meshnbv
 * suggest --frustums` draws them), with cell arrays "rank",
 * "energy" and "RGB" (red for rank 1 to yellow). Output 1: a vtkTable with
 * one row per suggestion: rank, label, source, region, width, height, fx,
 * fy, cx, cy, R (9 components, row-major), t (3), centre (3), look_at (3),
 * energy, occlusion, focus, parallax, incidence (energy = the sum of the
 * four weighted terms), seen_faces; its field data "SuggestionsJSON" holds
 * the core's full JSON document (regions, ranking, candidate counts), which
 * vtkMeshNBVSuggestionWriter writes.
 *
 * The options carry the names and defaults of the core, the command line
 * (`meshnbv suggest`) and the JSON document, in CamelCase. Progress goes
 * through UpdateProgress; AbortExecute cancels (outputs left empty). Errors
 * are reported with vtkErrorMacro and the core's message, and the outputs
 * stay empty.
 *
 * @sa vtkMeshNBVPRIFilter vtkMeshNBVSceneReader vtkMeshNBVSuggestionWriter
 */

#ifndef vtkMeshNBVNextBestViewFilter_h
#define vtkMeshNBVNextBestViewFilter_h

#include "vtkMeshNBVFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For std::string members

class vtkTable;

class VTKMESHNBVFILTERS_EXPORT vtkMeshNBVNextBestViewFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkMeshNBVNextBestViewFilter* New();
  vtkTypeMacro(vtkMeshNBVNextBestViewFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum CandidatesType
  {
    GIVEN = 0,   // the given candidate views, all of them ranked
    SAMPLED = 1, // poses sampled on the hemisphere of the worst region
    REFINED = 2  // sampled, then the best ones refined by Nelder-Mead
  };

  ///@{
  /**
   * Where candidate poses come from (`candidates`): GIVEN, SAMPLED or
   * REFINED.
   */
  vtkSetMacro(Candidates, int);
  vtkGetMacro(Candidates, int);
  void SetCandidatesToGiven() { this->SetCandidates(GIVEN); }
  void SetCandidatesToSampled() { this->SetCandidates(SAMPLED); }
  void SetCandidatesToRefined() { this->SetCandidates(REFINED); }
  const char* GetCandidatesAsString();
  ///@}

  ///@{
  /**
   * Number of suggestions, chosen greedily (`top`).
   */
  vtkSetMacro(Top, int);
  vtkGetMacro(Top, int);
  ///@}

  ///@{
  /**
   * Faces in the worst region (`worst_faces`, the paper's K).
   */
  vtkSetMacro(WorstFaces, int);
  vtkGetMacro(WorstFaces, int);
  ///@}

  enum EnergyType
  {
    PAPER = 0,             // the SPEC's energy over the worst region
    RECONSTRUCTABILITY = 1 // the whole-mesh reconstructability gain (docs/nbv.md)
  };

  ///@{
  /**
   * What a candidate is scored by (`energy`): PAPER or RECONSTRUCTABILITY.
   */
  vtkSetMacro(Energy, int);
  vtkGetMacro(Energy, int);
  void SetEnergyToPaper() { this->SetEnergy(PAPER); }
  void SetEnergyToReconstructability() { this->SetEnergy(RECONSTRUCTABILITY); }
  const char* GetEnergyAsString();
  ///@}

  ///@{
  /**
   * RECONSTRUCTABILITY: the target a face needs (`gain_target`), the weight
   * of unobserved and boundary faces (`exploration_weight`) and the number
   * of face clusters scored (`gain_clusters`, 0 = every face).
   */
  vtkSetMacro(GainTarget, double);
  vtkGetMacro(GainTarget, double);
  vtkSetMacro(ExplorationWeight, double);
  vtkGetMacro(ExplorationWeight, double);
  vtkSetMacro(GainClusters, int);
  vtkGetMacro(GainClusters, int);
  ///@}

  ///@{
  /**
   * RECONSTRUCTABILITY: the part of the mesh's convex hull that no view
   * sees, away from the mesh, stands for surface not yet reconstructed and
   * weighs as exploration (`explore_hull`).
   */
  vtkSetMacro(ExploreHull, vtkTypeBool);
  vtkGetMacro(ExploreHull, vtkTypeBool);
  vtkBooleanMacro(ExploreHull, vtkTypeBool);
  ///@}

  ///@{
  /**
   * RECONSTRUCTABILITY: a candidate improves surface that existing views
   * see only where its ray is within this many degrees of one of theirs
   * (`match_angle`, in (0, 180]; 180 = every pair counts).
   */
  vtkSetMacro(MatchAngle, double);
  vtkGetMacro(MatchAngle, double);
  ///@}

  ///@{
  /**
   * Energy weights m1..m4 of the occlusion, focus, parallax and incidence
   * terms (`weight_occlusion`, `weight_focus`, `weight_parallax`,
   * `weight_incidence`).
   */
  vtkSetMacro(WeightOcclusion, double);
  vtkGetMacro(WeightOcclusion, double);
  vtkSetMacro(WeightFocus, double);
  vtkGetMacro(WeightFocus, double);
  vtkSetMacro(WeightParallax, double);
  vtkGetMacro(WeightParallax, double);
  vtkSetMacro(WeightIncidence, double);
  vtkGetMacro(WeightIncidence, double);
  ///@}

  ///@{
  /**
   * Kp, the value of a failed term (`penalty`).
   */
  vtkSetMacro(Penalty, double);
  vtkGetMacro(Penalty, double);
  ///@}

  ///@{
  /**
   * Baseline-to-distance threshold of the parallax term (`parallax_delta`,
   * default 0.33).
   */
  vtkSetMacro(ParallaxDelta, double);
  vtkGetMacro(ParallaxDelta, double);
  ///@}

  ///@{
  /**
   * Preferred incidence angle and its spread, in degrees (`incidence_mu`,
   * default 55; `incidence_sigma`).
   */
  vtkSetMacro(IncidenceMu, double);
  vtkGetMacro(IncidenceMu, double);
  vtkSetMacro(IncidenceSigma, double);
  vtkGetMacro(IncidenceSigma, double);
  ///@}

  ///@{
  /**
   * Directions sampled on the hemisphere (`directions`).
   */
  vtkSetMacro(Directions, int);
  vtkGetMacro(Directions, int);
  ///@}

  ///@{
  /**
   * Minimum distance of a candidate to the surface, as a share of the
   * bounding-box diagonal (`safety_distance`).
   */
  vtkSetMacro(SafetyDistance, double);
  vtkGetMacro(SafetyDistance, double);
  ///@}

  ///@{
  /**
   * Sampled, refined: no pose below the mesh's lowest point along the
   * existing views' level up, plus the safety distance, or below the
   * lowest existing view where that is lower (`above_ground`, on).
   */
  vtkSetMacro(AboveGround, vtkTypeBool);
  vtkGetMacro(AboveGround, vtkTypeBool);
  vtkBooleanMacro(AboveGround, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Sampled, refined: poses without roll, image up towards the existing
   * views' level up, as a gimbal takes them (`level_views`, on).
   */
  vtkSetMacro(LevelViews, vtkTypeBool);
  vtkGetMacro(LevelViews, vtkTypeBool);
  vtkBooleanMacro(LevelViews, vtkTypeBool);
  ///@}

  ///@{
  /**
   * REFINED: sampled poses refined per pick (`refine_best`) and
   * optimiser iterations (`refine_iterations`).
   */
  vtkSetMacro(RefineBest, int);
  vtkGetMacro(RefineBest, int);
  vtkSetMacro(RefineIterations, int);
  vtkGetMacro(RefineIterations, int);
  ///@}

  ///@{
  /**
   * Seed of the sampling (`seed`). Signed, so that ParaView's wrapping
   * can set it and a negative value is reported as out of range.
   */
  vtkSetMacro(Seed, vtkTypeInt64);
  vtkGetMacro(Seed, vtkTypeInt64);
  ///@}

  ///@{
  /**
   * Worker threads (`threads`); 0 (default) = all cores.
   */
  vtkSetMacro(Threads, int);
  vtkGetMacro(Threads, int);
  ///@}

  ///@{
  /**
   * The cell array of input 0 holding the PRI.
   */
  vtkSetStdStringFromCharMacro(PRIArrayName);
  vtkGetCharFromStdStringMacro(PRIArrayName);
  ///@}

  ///@{
  /**
   * Depth of the frustums' base (camera z) in scene units; 0 (default) =
   * the core's default, a share of the distance to the point the suggestion
   * looks at (docs/nbv.md).
   */
  vtkSetClampMacro(FrustumDepth, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(FrustumDepth, double);
  ///@}

  ///@{
  /**
   * Connect the existing views (input port 1) and the candidate views
   * (input port 2, optional).
   */
  void SetViewsConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetViewsData(vtkDataObject* views) { this->SetInputData(1, views); }
  void SetCandidatesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(2, output); }
  void SetCandidatesData(vtkDataObject* views) { this->SetInputData(2, views); }
  ///@}

  ///@{
  /**
   * The frustums (output port 0) and the suggestions table (output port 1).
   */
  vtkPolyData* GetFrustumsOutput() { return this->GetOutput(0); }
  vtkTable* GetSuggestionsOutput();
  vtkAlgorithmOutput* GetSuggestionsOutputPort() { return this->GetOutputPort(1); }
  ///@}

protected:
  vtkMeshNBVNextBestViewFilter();
  ~vtkMeshNBVNextBestViewFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Candidates;
  int Top;
  int WorstFaces;
  int Energy;
  double GainTarget;
  double ExplorationWeight;
  int GainClusters;
  vtkTypeBool ExploreHull;
  double MatchAngle;
  double WeightOcclusion;
  double WeightFocus;
  double WeightParallax;
  double WeightIncidence;
  double Penalty;
  double ParallaxDelta;
  double IncidenceMu;
  double IncidenceSigma;
  int Directions;
  double SafetyDistance;
  vtkTypeBool AboveGround;
  vtkTypeBool LevelViews;
  int RefineBest;
  int RefineIterations;
  vtkTypeInt64 Seed;
  int Threads;
  std::string PRIArrayName;
  double FrustumDepth;

private:
  vtkMeshNBVNextBestViewFilter(const vtkMeshNBVNextBestViewFilter&) = delete;
  void operator=(const vtkMeshNBVNextBestViewFilter&) = delete;
};

#endif
