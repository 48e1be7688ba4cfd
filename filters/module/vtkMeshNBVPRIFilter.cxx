#include "vtkMeshNBVPRIFilter.h"

#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkDataObjectTree.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

#include "vtkMeshNBVConversion.h"
#include "vtkMeshNBVProgress.h"

#include "meshnbv/error.h"
#include "meshnbv/options.h"
#include "meshnbv/pri.h"

#include <algorithm>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMeshNBVPRIFilter);

namespace
{
// The words of the table's `measure` option, in the order of MeasureType
// (ssd, ncc, offset): the VTK value is the word's position.
const std::vector<std::string>& MeasureWords()
{
  for (const auto& spec : meshnbv::pri_option_table())
  {
    if (spec.name == "measure")
    {
      return spec.choices;
    }
  }
  throw meshnbv::Error("the PRI option table has no measure");
}

bool KnownMeasure(int measure)
{
  return measure >= 0 && static_cast<std::size_t>(measure) < MeasureWords().size();
}

// The properties as the core's options, unchecked (PrintSelf shows what is
// set, in range or not; an unknown Measure keeps the core's default).
meshnbv::PriOptions RawOptionsOf(vtkMeshNBVPRIFilter* f)
{
  meshnbv::PriOptions o;
  if (KnownMeasure(f->GetMeasure()))
  {
    o.measure = meshnbv::parse_measure(MeasureWords()[static_cast<std::size_t>(f->GetMeasure())]);
  }
  o.samples_per_side = f->GetSamplesPerSide();
  o.max_views_per_face = f->GetMaxViewsPerFace();
  o.max_incidence_angle = f->GetMaxIncidenceAngle();
  o.max_image_reduction = f->GetMaxImageReduction();
  o.edge_margin = f->GetEdgeMargin();
  o.support_radius = f->GetSupportRadius();
  o.offset_range = f->GetOffsetRange();
  o.offset_steps = f->GetOffsetSteps();
  o.check_interior_occlusion = f->GetCheckInteriorOcclusion() != 0;
  o.color = f->GetColor() != 0;
  o.textureless_variance = f->GetTexturelessVariance();
  o.threads = f->GetThreads();
  return o;
}

// Checked: an out-of-range property is an error naming it and its range.
meshnbv::PriOptions OptionsOf(vtkMeshNBVPRIFilter* f)
{
  const int measure = f->GetMeasure();
  if (!KnownMeasure(measure))
  {
    throw meshnbv::Error("Measure must be 0 (SSD), 1 (NCC) or 2 (OFFSET), got " +
      std::to_string(measure));
  }
  meshnbv::PriOptions o = RawOptionsOf(f);
  o.check();
  return o;
}

template <class Array, class Values>
void AddCellArray(vtkPolyData* output, const std::string& name, const Values& values)
{
  vtkNew<Array> array;
  array->SetName(name.c_str());
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  output->GetCellData()->AddArray(array);
}
} // namespace

//------------------------------------------------------------------------------
vtkMeshNBVPRIFilter::vtkMeshNBVPRIFilter()
  : PRIArrayName("PRI")
  , PRIViewsArrayName("PRIViews")
  , PRIPairsArrayName("PRIPairs")
  , PRISamplesArrayName("PRISamples")
  , PRITextureArrayName("PRITexture")
{
  // The defaults are the core's, so that the three front ends agree.
  const meshnbv::PriOptions defaults;
  const std::vector<std::string>& words = MeasureWords();
  this->Measure = static_cast<int>(
    std::find(words.begin(), words.end(), meshnbv::measure_name(defaults.measure)) - words.begin());
  this->SamplesPerSide = defaults.samples_per_side;
  this->MaxViewsPerFace = defaults.max_views_per_face;
  this->MaxIncidenceAngle = defaults.max_incidence_angle;
  this->MaxImageReduction = defaults.max_image_reduction;
  this->EdgeMargin = defaults.edge_margin;
  this->SupportRadius = defaults.support_radius;
  this->OffsetRange = defaults.offset_range;
  this->OffsetSteps = defaults.offset_steps;
  this->CheckInteriorOcclusion = defaults.check_interior_occlusion;
  this->Color = defaults.color;
  this->TexturelessVariance = defaults.textureless_variance;
  this->Threads = defaults.threads;
  this->SetNumberOfInputPorts(2);
}

//------------------------------------------------------------------------------
vtkMeshNBVPRIFilter::~vtkMeshNBVPRIFilter() = default;

//------------------------------------------------------------------------------
const char* vtkMeshNBVPRIFilter::GetMeasureAsString()
{
  return KnownMeasure(this->Measure) ? MeasureWords()[static_cast<std::size_t>(this->Measure)].c_str()
                                      : "unknown";
}

//------------------------------------------------------------------------------
int vtkMeshNBVPRIFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObjectTree");
    // Optional for the pipeline so that a missing views input is reported
    // by this filter, with a message saying what to connect.
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  return this->Superclass::FillInputPortInformation(port, info);
}

//------------------------------------------------------------------------------
int vtkMeshNBVPRIFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkDataObject* views = vtkDataObject::GetData(inputVector[1], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->Initialize();
  try
  {
    if (!views)
    {
      throw meshnbv::Error("no views input: connect the views to input port 1 (e.g. "
                           "vtkMeshNBVSceneReader's output port 1)");
    }
    meshnbv::Scene scene;
    scene.mesh = vtkMeshNBV::ToTriangleMesh(input);
    // Pixels carried by the pipeline are what is compared: each block's
    // pixels are converted once and handed to the core in memory (no file).
    // Blocks without pixels are read from their ImagePath through the core's
    // bounded cache. Views kept aside (Used = 0) are not read: not converted.
    for (const vtkMeshNBV::ViewBlock& block : vtkMeshNBV::ExtractViews(views))
    {
      scene.views.push_back(
        block.hasPixels && block.view.used ? vtkMeshNBV::ToViewWithPixels(block) : block.view);
    }

    const meshnbv::PriOptions options = OptionsOf(this);
    const meshnbv::PriResult result = meshnbv::compute_pri(scene, options,
      vtkMeshNBV::MakeProgressCallback(this, { { "visibility", 0.15 }, { "view selection", 0.1 }, { "pri", 0.75 } }));

    output->ShallowCopy(input);
    AddCellArray<vtkFloatArray>(output, this->PRIArrayName, result.pri);
    AddCellArray<vtkIntArray>(output, this->PRIViewsArrayName, result.pri_views);
    AddCellArray<vtkIntArray>(output, this->PRIPairsArrayName, result.pri_pairs);
    AddCellArray<vtkIntArray>(output, this->PRISamplesArrayName, result.pri_samples);
    AddCellArray<vtkFloatArray>(output, this->PRITextureArrayName, result.pri_texture);
    // The active cell scalars: what a mapper (or ParaView, on Apply)
    // colours by.
    output->GetCellData()->SetActiveScalars(this->PRIArrayName.c_str());
  }
  catch (const meshnbv::Cancelled&)
  {
    output->Initialize(); // AbortExecute was set: no result, and no error
  }
  catch (const std::exception& e)
  {
    output->Initialize();
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkMeshNBVPRIFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  // Every option of the core's table, under its VTK name (options.h).
  const meshnbv::PriOptions options = RawOptionsOf(this);
  for (const auto& spec : meshnbv::pri_option_table())
  {
    os << indent << meshnbv::vtk_name(spec.name) << ": "
       << meshnbv::option_value_text(spec.get(options)) << "\n";
  }
  os << indent << "PRIArrayName: " << this->PRIArrayName << "\n";
  os << indent << "PRIViewsArrayName: " << this->PRIViewsArrayName << "\n";
  os << indent << "PRIPairsArrayName: " << this->PRIPairsArrayName << "\n";
  os << indent << "PRISamplesArrayName: " << this->PRISamplesArrayName << "\n";
  os << indent << "PRITextureArrayName: " << this->PRITextureArrayName << "\n";
}
