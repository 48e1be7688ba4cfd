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

vtkStandardNewMacro(vtkMeshNBVPRIFilter);

namespace
{
// The properties as the core's options, unchecked (PrintSelf shows what is
// set, in range or not).
meshnbv::PriOptions RawOptionsOf(vtkMeshNBVPRIFilter* f)
{
  meshnbv::PriOptions o;
  o.measure = f->GetMeasure() == vtkMeshNBVPRIFilter::NCC ? meshnbv::Measure::NCC
                                                          : meshnbv::Measure::SSD;
  o.samples_per_side = f->GetSamplesPerSide();
  o.max_views_per_face = f->GetMaxViewsPerFace();
  o.max_incidence_angle = f->GetMaxIncidenceAngle();
  o.edge_margin = f->GetEdgeMargin();
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
  if (measure != vtkMeshNBVPRIFilter::SSD && measure != vtkMeshNBVPRIFilter::NCC)
  {
    throw meshnbv::Error(
      "Measure must be 0 (SSD) or 1 (NCC), got " + std::to_string(measure));
  }
  meshnbv::PriOptions o = RawOptionsOf(f);
  o.check();
  return o;
}
} // namespace

//------------------------------------------------------------------------------
vtkMeshNBVPRIFilter::vtkMeshNBVPRIFilter()
  : PRIArrayName("PRI")
  , PRIViewsArrayName("PRIViews")
{
  // The defaults are the core's, so that the three front ends agree.
  const meshnbv::PriOptions defaults;
  this->Measure = defaults.measure == meshnbv::Measure::NCC ? NCC : SSD;
  this->SamplesPerSide = defaults.samples_per_side;
  this->MaxViewsPerFace = defaults.max_views_per_face;
  this->MaxIncidenceAngle = defaults.max_incidence_angle;
  this->EdgeMargin = defaults.edge_margin;
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
  return this->Measure == NCC ? "ncc" : "ssd";
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
      vtkMeshNBV::MakeProgressCallback(this, { { "visibility", 0.2 }, { "pri", 0.8 } }));

    vtkNew<vtkFloatArray> pri;
    pri->SetName(this->PRIArrayName.c_str());
    pri->SetNumberOfTuples(static_cast<vtkIdType>(result.pri.size()));
    std::copy(result.pri.begin(), result.pri.end(), pri->GetPointer(0));
    vtkNew<vtkIntArray> count;
    count->SetName(this->PRIViewsArrayName.c_str());
    count->SetNumberOfTuples(static_cast<vtkIdType>(result.pri_views.size()));
    std::copy(result.pri_views.begin(), result.pri_views.end(), count->GetPointer(0));
    output->ShallowCopy(input);
    output->GetCellData()->AddArray(pri);
    output->GetCellData()->AddArray(count);
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
}
