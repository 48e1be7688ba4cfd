// vtkMeshNBVPRIFilter equals the core and the CLI on the synthetic project
// (8 orbit views, 320x240): its PRI cell array matches meshnbv::compute_pri
// on the same scene and the `quality` of `meshnbv pri`'s PLY to 1e-6 (NaN
// where the core has NaN), PRIViews matches the core's view counts and
// PRIPairs, PRISamples, PRITexture its evidence exactly (and the CLI's
// pri_pairs, pri_samples, pri_texture), for the defaults and for
// non-default options, offset included (each option reaches the core).
// Pixels from the pipeline and images read by path give the same result.
// Progress is reported in [0, 1], non-decreasing, ending at 1.
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

#include "vtkMeshNBVPRIFilter.h"
#include "vtkMeshNBVSceneReader.h"
#include "vtkMeshNBVTestUtilities.h"

#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"
#include "meshnbv/options.h"
#include "meshnbv/pri.h"

#include <sstream>

namespace
{

class ProgressRecorder : public vtkCommand
{
public:
  static ProgressRecorder* New() { return new ProgressRecorder; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    this->Values.push_back(*static_cast<double*>(data));
  }
  std::vector<double> Values;
};

// Largest |filter - reference| over faces; -1 when NaN patterns differ.
double MaxDifference(vtkDataArray* pri, const std::vector<float>& reference, std::size_t* observed)
{
  if (!pri || pri->GetNumberOfTuples() != static_cast<vtkIdType>(reference.size()))
  {
    return -1;
  }
  double worst = 0;
  *observed = 0;
  for (std::size_t f = 0; f < reference.size(); ++f)
  {
    const double a = pri->GetComponent(static_cast<vtkIdType>(f), 0);
    const double b = reference[f];
    if (std::isnan(a) != std::isnan(b))
    {
      return -1;
    }
    if (!std::isnan(b))
    {
      worst = std::max(worst, std::abs(a - b));
      ++*observed;
    }
  }
  return worst;
}

struct Case
{
  const char* Name;
  bool LoadImages;
  void (*Configure)(vtkMeshNBVPRIFilter*, meshnbv::PriOptions*);
  const char* CliPly; // the CLI's output for the same options, or nullptr
};

} // namespace

int TestPRIFilter(int argc, char* argv[])
{
  vtkMeshNBVTest::Arguments args;
  MESHNBV_CHECK(vtkMeshNBVTest::ParseArguments(argc, argv, &args), "bad arguments");
  const meshnbv::Scene scene = meshnbv::io::read_scene(args.ProjectFile());

  const Case cases[] = {
    { "defaults (ssd)", true, [](vtkMeshNBVPRIFilter*, meshnbv::PriOptions*) {}, "pri_ssd.ply" },
    { "ncc, samples 4, max views 3", true,
      [](vtkMeshNBVPRIFilter* f, meshnbv::PriOptions* o) {
        f->SetMeasureToNCC();
        f->SetSamplesPerSide(4);
        f->SetMaxViewsPerFace(3);
        o->measure = meshnbv::Measure::NCC;
        o->samples_per_side = 4;
        o->max_views_per_face = 3;
      },
      "pri_ncc.ply" },
    { "color, no interior check, 90 degrees, 1 thread, images by path", false,
      [](vtkMeshNBVPRIFilter* f, meshnbv::PriOptions* o) {
        f->ColorOn();
        f->CheckInteriorOcclusionOff();
        f->SetMaxIncidenceAngle(90);
        f->SetThreads(1);
        o->color = true;
        o->check_interior_occlusion = false;
        o->max_incidence_angle = 90;
        o->threads = 1;
      },
      nullptr },
    { "offset, support 3, range 3, steps 3", true,
      [](vtkMeshNBVPRIFilter* f, meshnbv::PriOptions* o) {
        f->SetMeasureToOffset();
        f->SetSupportRadius(3);
        f->SetOffsetRange(3);
        f->SetOffsetSteps(3);
        o->measure = meshnbv::Measure::Offset;
        o->support_radius = 3;
        o->offset_range = 3;
        o->offset_steps = 3;
      },
      "pri_offset.ply" },
    { "ncc, textureless variance 3e-4", true,
      [](vtkMeshNBVPRIFilter* f, meshnbv::PriOptions* o) {
        f->SetMeasure(vtkMeshNBVPRIFilter::NCC);
        f->SetTexturelessVariance(3e-4);
        o->measure = meshnbv::Measure::NCC;
        o->textureless_variance = 3e-4;
      },
      nullptr },
  };

  std::vector<float> first;
  for (const Case& c : cases)
  {
    vtkNew<vtkMeshNBVSceneReader> reader;
    reader->SetFileName(args.ProjectFile().c_str());
    reader->SetLoadImages(c.LoadImages);
    vtkNew<vtkMeshNBVPRIFilter> pri;
    vtkMeshNBVTest::Watch watch(pri);
    vtkNew<ProgressRecorder> progress;
    pri->AddObserver(vtkCommand::ProgressEvent, progress);
    pri->SetInputConnection(reader->GetOutputPort(0));
    pri->SetViewsConnection(reader->GetViewsOutputPort());
    meshnbv::PriOptions options;
    c.Configure(pri, &options);
    pri->Update();
    MESHNBV_CHECK(watch.Algorithm->Errors.empty(), c.Name << ": " << watch.Algorithm->AllErrors());

    const meshnbv::PriResult core = meshnbv::compute_pri(scene, options);
    vtkPolyData* out = pri->GetOutput();
    MESHNBV_CHECK(out->GetNumberOfCells() == static_cast<vtkIdType>(scene.mesh.num_faces()),
      c.Name << ": " << out->GetNumberOfCells() << " cells");
    std::size_t observed = 0;
    const double diff = MaxDifference(out->GetCellData()->GetArray("PRI"), core.pri, &observed);
    MESHNBV_CHECK(diff >= 0 && diff <= 1e-6, c.Name << ": PRI differs from the core by " << diff);
    MESHNBV_CHECK(observed == core.observed && observed > 1000, c.Name << ": " << observed << " observed");
    vtkDataArray* views = out->GetCellData()->GetArray("PRIViews");
    MESHNBV_CHECK(views && views->GetNumberOfTuples() == out->GetNumberOfCells(), c.Name << ": PRIViews");
    for (std::size_t f = 0; f < core.pri_views.size(); ++f)
    {
      MESHNBV_CHECK(views->GetComponent(static_cast<vtkIdType>(f), 0) == core.pri_views[f],
        c.Name << ": PRIViews of face " << f);
    }
    // The evidence arrays are the core's, exactly (texture: NaN where the core's is).
    const std::pair<const char*, std::vector<float>> evidence[] = {
      { "PRIPairs", std::vector<float>(core.pri_pairs.begin(), core.pri_pairs.end()) },
      { "PRISamples", std::vector<float>(core.pri_samples.begin(), core.pri_samples.end()) },
      { "PRITexture", core.pri_texture },
    };
    for (const auto& [name, values] : evidence)
    {
      std::size_t defined = 0;
      const double d = MaxDifference(out->GetCellData()->GetArray(name), values, &defined);
      MESHNBV_CHECK(d == 0, c.Name << ": " << name << " differs from the core (" << d << ")");
    }
    std::cout << c.Name << ": " << observed << " observed faces, max |PRI - core| = " << diff;
    if (c.CliPly)
    {
      const meshnbv::TriangleMesh cli = meshnbv::io::read_ply(args.Project + "/" + c.CliPly);
      const std::vector<float>* quality = cli.face_attribute("quality");
      MESHNBV_CHECK(quality, c.CliPly << " has no quality");
      const double cliDiff = MaxDifference(out->GetCellData()->GetArray("PRI"), *quality, &observed);
      MESHNBV_CHECK(cliDiff >= 0 && cliDiff <= 1e-6, c.Name << ": PRI differs from the CLI by " << cliDiff);
      std::cout << ", max |PRI - CLI| = " << cliDiff;
      for (const auto& [array, property] : { std::make_pair("PRIPairs", "pri_pairs"),
             std::make_pair("PRISamples", "pri_samples"), std::make_pair("PRITexture", "pri_texture") })
      {
        const std::vector<float>* values = cli.face_attribute(property);
        MESHNBV_CHECK(values, c.CliPly << " has no " << property);
        std::size_t defined = 0;
        const double d = MaxDifference(out->GetCellData()->GetArray(array), *values, &defined);
        MESHNBV_CHECK(d == 0, c.Name << ": " << array << " differs from the CLI's " << property << " (" << d << ")");
      }
    }
    std::cout << "\n";

    MESHNBV_CHECK(!progress->Values.empty() && progress->Values.back() == 1.0,
      c.Name << ": progress did not end at 1");
    for (std::size_t i = 0; i < progress->Values.size(); ++i)
    {
      MESHNBV_CHECK(progress->Values[i] >= 0 && progress->Values[i] <= 1 &&
          (i == 0 || progress->Values[i] >= progress->Values[i - 1]),
        c.Name << ": progress value " << progress->Values[i]);
    }
    if (first.empty())
    {
      first = core.pri;
    }
    else
    {
      MESHNBV_CHECK(MaxDifference(out->GetCellData()->GetArray("PRI"), first, &observed) != 0,
        c.Name << ": same PRI as the defaults: the options did not reach the core");
    }
  }

  // PrintSelf states the options.
  vtkNew<vtkMeshNBVPRIFilter> defaults;
  std::ostringstream printed;
  defaults->Print(printed);
  MESHNBV_CHECK(printed.str().find("Measure: ssd") != std::string::npos &&
      printed.str().find("MaxIncidenceAngle: 80") != std::string::npos,
    "PrintSelf: " << printed.str());

  // The Measure values are the positions of the table's words.
  for (const auto& spec : meshnbv::pri_option_table())
  {
    if (spec.name != "measure")
    {
      continue;
    }
    MESHNBV_CHECK(spec.choices.size() == 3, "measure has " << spec.choices.size() << " words");
    const int values[] = { vtkMeshNBVPRIFilter::SSD, vtkMeshNBVPRIFilter::NCC, vtkMeshNBVPRIFilter::OFFSET };
    const meshnbv::Measure measures[] = { meshnbv::Measure::SSD, meshnbv::Measure::NCC, meshnbv::Measure::Offset };
    for (std::size_t i = 0; i < 3; ++i)
    {
      defaults->SetMeasure(values[i]);
      MESHNBV_CHECK(values[i] == static_cast<int>(i) && spec.choices[i] == defaults->GetMeasureAsString() &&
          meshnbv::parse_measure(spec.choices[i]) == measures[i],
        "Measure " << values[i] << " is " << defaults->GetMeasureAsString() << ", table " << spec.choices[i]);
    }
  }
  defaults->SetMeasure(3);
  MESHNBV_CHECK(std::string(defaults->GetMeasureAsString()) == "unknown", "Measure 3");

  // Array names are properties.
  vtkNew<vtkMeshNBVSceneReader> reader;
  reader->SetFileName(args.ProjectFile().c_str());
  vtkNew<vtkMeshNBVPRIFilter> named;
  named->SetInputConnection(reader->GetOutputPort(0));
  named->SetViewsConnection(reader->GetViewsOutputPort());
  named->SetPRIArrayName("quality");
  named->SetPRIViewsArrayName("views");
  named->SetPRIPairsArrayName("pri_pairs");
  named->SetPRISamplesArrayName("pri_samples");
  named->SetPRITextureArrayName("pri_texture");
  named->Update();
  vtkCellData* cells = named->GetOutput()->GetCellData();
  MESHNBV_CHECK(cells->GetArray("quality") && cells->GetArray("views") && !cells->GetArray("PRI") &&
      cells->GetArray("pri_pairs") && cells->GetArray("pri_samples") && cells->GetArray("pri_texture") &&
      !cells->GetArray("PRIPairs") && !cells->GetArray("PRISamples") && !cells->GetArray("PRITexture"),
    "array names");
  return EXIT_SUCCESS;
}
