#include "vtkMeshNBVNextBestViewFilter.h"

#include <cstdint>
#include <limits>

#include "vtkCellData.h"
#include "vtkDataObjectTree.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include "vtkMeshNBVConversion.h"
#include "vtkMeshNBVProgress.h"

#include "meshnbv/error.h"
#include "meshnbv/options.h"
#include "meshnbv/results.h"
#include "meshnbv/planner.h"

#include <cmath>

vtkStandardNewMacro(vtkMeshNBVNextBestViewFilter);

namespace
{

template <typename ArrayT>
ArrayT* AddColumn(vtkTable* table, const char* name, int components = 1)
{
  vtkNew<ArrayT> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  table->AddColumn(a);
  return a;
}

// One row per suggestion: the columns of the JSON document's "suggestions".
void FillTable(vtkTable* table, const meshnbv::SuggestResult& result)
{
  auto* rank = AddColumn<vtkIntArray>(table, "rank");
  auto* label = AddColumn<vtkStringArray>(table, "label");
  auto* source = AddColumn<vtkStringArray>(table, "source");
  auto* region = AddColumn<vtkIntArray>(table, "region");
  auto* width = AddColumn<vtkIntArray>(table, "width");
  auto* height = AddColumn<vtkIntArray>(table, "height");
  auto* fx = AddColumn<vtkDoubleArray>(table, "fx");
  auto* fy = AddColumn<vtkDoubleArray>(table, "fy");
  auto* cx = AddColumn<vtkDoubleArray>(table, "cx");
  auto* cy = AddColumn<vtkDoubleArray>(table, "cy");
  auto* r = AddColumn<vtkDoubleArray>(table, "R", 9);
  auto* t = AddColumn<vtkDoubleArray>(table, "t", 3);
  auto* centre = AddColumn<vtkDoubleArray>(table, "centre", 3);
  auto* lookAt = AddColumn<vtkDoubleArray>(table, "look_at", 3);
  auto* energy = AddColumn<vtkDoubleArray>(table, "energy");
  auto* occlusion = AddColumn<vtkDoubleArray>(table, "occlusion");
  auto* focus = AddColumn<vtkDoubleArray>(table, "focus");
  auto* parallax = AddColumn<vtkDoubleArray>(table, "parallax");
  auto* incidence = AddColumn<vtkDoubleArray>(table, "incidence");
  auto* refinement = AddColumn<vtkDoubleArray>(table, "refinement");
  auto* exploration = AddColumn<vtkDoubleArray>(table, "exploration");
  auto* seen = AddColumn<vtkIntArray>(table, "seen_faces");
  for (const meshnbv::Suggestion& s : result.suggestions)
  {
    const meshnbv::PinholeCamera& c = s.camera;
    rank->InsertNextValue(s.rank);
    label->InsertNextValue(s.label);
    source->InsertNextValue(s.source);
    region->InsertNextValue(s.region);
    width->InsertNextValue(c.width);
    height->InsertNextValue(c.height);
    fx->InsertNextValue(c.fx);
    fy->InsertNextValue(c.fy);
    cx->InsertNextValue(c.cx);
    cy->InsertNextValue(c.cy);
    double rowMajor[9];
    for (int i = 0; i < 9; ++i)
    {
      rowMajor[i] = c.R(i / 3, i % 3);
    }
    r->InsertNextTuple(rowMajor);
    t->InsertNextTuple(c.t.data());
    const meshnbv::Vec3 centrePoint = c.center();
    centre->InsertNextTuple(centrePoint.data());
    lookAt->InsertNextTuple(s.look_at.data());
    energy->InsertNextValue(s.energy.total);
    occlusion->InsertNextValue(s.energy.occlusion);
    focus->InsertNextValue(s.energy.focus);
    parallax->InsertNextValue(s.energy.parallax);
    incidence->InsertNextValue(s.energy.incidence);
    refinement->InsertNextValue(s.energy.refinement);
    exploration->InsertNextValue(s.energy.exploration);
    seen->InsertNextValue(static_cast<int>(s.seen_faces.size()));
  }
}

int ToCandidates(meshnbv::CandidateMode mode)
{
  switch (mode)
  {
    case meshnbv::CandidateMode::Given:
      return vtkMeshNBVNextBestViewFilter::GIVEN;
    case meshnbv::CandidateMode::Refined:
      return vtkMeshNBVNextBestViewFilter::REFINED;
    default:
      return vtkMeshNBVNextBestViewFilter::SAMPLED;
  }
}

meshnbv::CandidateMode ToMode(int candidates)
{
  switch (candidates)
  {
    case vtkMeshNBVNextBestViewFilter::GIVEN:
      return meshnbv::CandidateMode::Given;
    case vtkMeshNBVNextBestViewFilter::REFINED:
      return meshnbv::CandidateMode::Refined;
    default:
      return meshnbv::CandidateMode::Sampled;
  }
}

std::string FieldString(vtkDataObject* object, const char* name)
{
  auto* a = object ? vtkStringArray::SafeDownCast(object->GetFieldData()->GetAbstractArray(name))
                   : nullptr;
  return a && a->GetNumberOfValues() > 0 ? a->GetValue(0) : std::string();
}

// The properties as the core's options, unchecked (PrintSelf shows what is
// set, in range or not).
meshnbv::SuggestOptions RawOptionsOf(vtkMeshNBVNextBestViewFilter* f)
{
  meshnbv::SuggestOptions o;
  const int candidates = f->GetCandidates();
  if (candidates >= 0 && candidates <= 2)
  {
    o.mode = ToMode(candidates);
  }
  o.top = f->GetTop();
  o.worst_k = f->GetWorstFaces();
  if (f->GetEnergy() == vtkMeshNBVNextBestViewFilter::RECONSTRUCTABILITY)
  {
    o.energy_kind = meshnbv::EnergyKind::Reconstructability;
  }
  o.gain.target = f->GetGainTarget();
  o.gain.exploration_weight = f->GetExplorationWeight();
  o.gain.clusters = f->GetGainClusters();
  o.gain.explore_hull = f->GetExploreHull() != 0;
  o.gain.match_angle = f->GetMatchAngle();
  o.energy.weights = { f->GetWeightOcclusion(), f->GetWeightFocus(), f->GetWeightParallax(),
    f->GetWeightIncidence() };
  o.energy.penalty = f->GetPenalty();
  o.energy.parallax_delta = f->GetParallaxDelta();
  o.energy.incidence_mu = f->GetIncidenceMu();
  o.energy.incidence_sigma = f->GetIncidenceSigma();
  o.sampling.directions = f->GetDirections();
  // Negative seeds stay visible to check_options() as out of range (as the
  // option table's setter keeps them).
  o.sampling.seed = f->GetSeed() < 0 ? std::numeric_limits<std::uint64_t>::max() : std::uint64_t(f->GetSeed());
  o.safety_distance = f->GetSafetyDistance();
  o.above_ground = f->GetAboveGround() != 0;
  o.level_views = f->GetLevelViews() != 0;
  o.refine_best = f->GetRefineBest();
  o.refine.iterations = f->GetRefineIterations();
  o.threads = f->GetThreads();
  return o;
}

// Checked: an out-of-range property is an error naming it and its range.
meshnbv::SuggestOptions OptionsOf(vtkMeshNBVNextBestViewFilter* f)
{
  const int candidates = f->GetCandidates();
  if (candidates < 0 || candidates > 2)
  {
    throw meshnbv::Error("Candidates must be 0 (GIVEN), 1 (SAMPLED) or 2 (REFINED), got " +
      std::to_string(candidates));
  }
  const int energy = f->GetEnergy();
  if (energy < 0 || energy > 1)
  {
    throw meshnbv::Error(
      "Energy must be 0 (PAPER) or 1 (RECONSTRUCTABILITY), got " + std::to_string(energy));
  }
  meshnbv::SuggestOptions o = RawOptionsOf(f);
  o.check();
  return o;
}

} // namespace

//------------------------------------------------------------------------------
vtkMeshNBVNextBestViewFilter::vtkMeshNBVNextBestViewFilter()
  : PRIArrayName("PRI")
  , FrustumDepth(0.0)
{
  // The defaults are the core's option table's (options.h), so that every
  // front end agrees.
  const meshnbv::SuggestOptions defaults;
  this->Candidates = ToCandidates(defaults.mode);
  this->Top = defaults.top;
  this->WorstFaces = defaults.worst_k;
  this->Energy = defaults.energy_kind == meshnbv::EnergyKind::Reconstructability ? RECONSTRUCTABILITY : PAPER;
  this->GainTarget = defaults.gain.target;
  this->ExplorationWeight = defaults.gain.exploration_weight;
  this->GainClusters = defaults.gain.clusters;
  this->ExploreHull = defaults.gain.explore_hull;
  this->MatchAngle = defaults.gain.match_angle;
  this->WeightOcclusion = defaults.energy.weights[0];
  this->WeightFocus = defaults.energy.weights[1];
  this->WeightParallax = defaults.energy.weights[2];
  this->WeightIncidence = defaults.energy.weights[3];
  this->Penalty = defaults.energy.penalty;
  this->ParallaxDelta = defaults.energy.parallax_delta;
  this->IncidenceMu = defaults.energy.incidence_mu;
  this->IncidenceSigma = defaults.energy.incidence_sigma;
  this->Directions = defaults.sampling.directions;
  this->SafetyDistance = defaults.safety_distance;
  this->AboveGround = defaults.above_ground;
  this->LevelViews = defaults.level_views;
  this->RefineBest = defaults.refine_best;
  this->RefineIterations = defaults.refine.iterations;
  this->Seed = vtkTypeInt64(defaults.sampling.seed);
  this->Threads = defaults.threads;
  this->SetNumberOfInputPorts(3);
  this->SetNumberOfOutputPorts(2);
}

//------------------------------------------------------------------------------
vtkMeshNBVNextBestViewFilter::~vtkMeshNBVNextBestViewFilter() = default;

//------------------------------------------------------------------------------
const char* vtkMeshNBVNextBestViewFilter::GetEnergyAsString()
{
  return this->Energy == RECONSTRUCTABILITY ? "reconstructability" : "paper";
}

//------------------------------------------------------------------------------
const char* vtkMeshNBVNextBestViewFilter::GetCandidatesAsString()
{
  switch (this->Candidates)
  {
    case GIVEN:
      return "given";
    case REFINED:
      return "refined";
    default:
      return "sampled";
  }
}

//------------------------------------------------------------------------------
vtkTable* vtkMeshNBVNextBestViewFilter::GetSuggestionsOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
int vtkMeshNBVNextBestViewFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 1 || port == 2)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObjectTree");
    // Port 1 too, so that a missing views input is reported by this filter.
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  return this->Superclass::FillInputPortInformation(port, info);
}

//------------------------------------------------------------------------------
int vtkMeshNBVNextBestViewFilter::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

//------------------------------------------------------------------------------
int vtkMeshNBVNextBestViewFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkDataObject* views = vtkDataObject::GetData(inputVector[1], 0);
  vtkDataObject* candidates = vtkDataObject::GetData(inputVector[2], 0);
  vtkPolyData* frustums = vtkPolyData::GetData(outputVector, 0);
  vtkTable* table = vtkTable::GetData(outputVector, 1);
  frustums->Initialize();
  table->Initialize();
  try
  {
    if (!views)
    {
      throw meshnbv::Error("no views input: connect the existing views to input port 1 (e.g. "
                           "vtkMeshNBVSceneReader's output port 1)");
    }
    meshnbv::Scene scene;
    scene.mesh = vtkMeshNBV::ToTriangleMesh(input);
    vtkDataArray* priArray = input->GetCellData()->GetArray(this->PRIArrayName.c_str());
    if (!priArray || priArray->GetNumberOfComponents() != 1 ||
      priArray->GetNumberOfTuples() != static_cast<vtkIdType>(scene.mesh.num_faces()))
    {
      throw meshnbv::Error("the mesh has no cell array '" + this->PRIArrayName +
        "' with one component (compute it with vtkMeshNBVPRIFilter, or set PRIArrayName)");
    }
    std::vector<float> pri(scene.mesh.num_faces());
    for (std::size_t f = 0; f < pri.size(); ++f)
    {
      pri[f] = static_cast<float>(priArray->GetComponent(static_cast<vtkIdType>(f), 0));
    }
    // An existing view is one with an image: its ImagePath, or, for a block
    // that has pixels and no ImagePath, the pixels handed over in memory.
    // The planner reads neither; it takes the cameras of the views with one.
    for (const vtkMeshNBV::ViewBlock& block : vtkMeshNBV::ExtractViews(views))
    {
      const bool pixelsOnly = block.hasPixels && block.view.image_path.empty();
      scene.views.push_back(
        pixelsOnly && block.view.used ? vtkMeshNBV::ToViewWithPixels(block) : block.view);
    }
    std::vector<meshnbv::View> given;
    if (candidates)
    {
      for (const vtkMeshNBV::ViewBlock& block : vtkMeshNBV::ExtractViews(candidates))
      {
        given.push_back(block.view);
      }
      if (given.empty())
      {
        throw meshnbv::Error("the candidates input (port 2) holds no view");
      }
      if (this->Candidates != GIVEN)
      {
        throw meshnbv::Error("a candidates input (port 2) needs Candidates = GIVEN");
      }
    }

    const meshnbv::SuggestOptions options = OptionsOf(this);
    const meshnbv::SuggestResult result = meshnbv::suggest_views(
      scene, pri, options, given, vtkMeshNBV::MakeProgressCallback(this, { { "suggest", 1.0 } }));

    frustums->ShallowCopy(vtkMeshNBV::ToPolyData(meshnbv::frustum_mesh(result, this->FrustumDepth)));
    FillTable(table, result);
    meshnbv::SuggestionContext context;
    context.scene = FieldString(views, vtkMeshNBV::SceneFileName);
    context.pri_from = "cell array '" + this->PRIArrayName + "'";
    vtkNew<vtkStringArray> json;
    json->SetName(vtkMeshNBV::SuggestionsJSONName);
    json->InsertNextValue(meshnbv::suggestions_json(result, options, context));
    table->GetFieldData()->AddArray(json);
  }
  catch (const meshnbv::Cancelled&)
  {
    frustums->Initialize(); // AbortExecute was set: no result, and no error
    table->Initialize();
  }
  catch (const std::exception& e)
  {
    frustums->Initialize();
    table->Initialize();
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkMeshNBVNextBestViewFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  // Every option of the core's table, under its VTK name (options.h).
  meshnbv::SuggestOptions options = RawOptionsOf(this);
  for (const auto& spec : meshnbv::suggest_option_table())
  {
    os << indent << meshnbv::vtk_name(spec.name) << ": "
       << meshnbv::option_value_text(spec.get(options)) << "\n";
  }
  os << indent << "PRIArrayName: " << this->PRIArrayName << "\n";
  os << indent << "FrustumDepth: " << this->FrustumDepth << "\n";
}
