// vtkMeshNBVNextBestViewFilter on the synthetic project.
//
// Table: every row equals meshnbv::suggest_views on the same scene and PRI
// (label, source, centre, energy and its four terms to 1e-9), in sampled,
// given (candidates on input 2) and refined mode.
//
// Frustums, geometry stated in the core's convention (x_cam = R X + t,
// pixel centres at integers, the image covers [-0.5, W-0.5] x [-0.5, H-0.5]):
// each suggestion is 5 points and 6 triangles; one point is the camera
// centre C = -R^T t (to 1e-9 of the scene's size); the other four lie on the
// viewing rays of the image's outer corners (-0.5, -0.5), (W-0.5, -0.5),
// (W-0.5, H-0.5), (-0.5, H-0.5), one on each, in front of the camera, at
// one depth: FrustumDepth, or when 0 the core's default, between the camera
// and the point looked at.
// Cell arrays rank and energy repeat the table's values for the 6 cells.
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include "vtkMeshNBVNextBestViewFilter.h"
#include "vtkMeshNBVPRIFilter.h"
#include "vtkMeshNBVSceneReader.h"
#include "vtkMeshNBVTestUtilities.h"

#include "meshnbv/io/scene_io.h"
#include "meshnbv/planner.h"
#include "meshnbv/pri.h"

#include <array>
#include <sstream>

namespace
{

double Value(vtkTable* table, const char* column, vtkIdType row, int component = 0)
{
  return vtkDataArray::SafeDownCast(table->GetColumnByName(column))->GetComponent(row, component);
}

meshnbv::PinholeCamera CameraOfRow(vtkTable* table, vtkIdType row)
{
  meshnbv::PinholeCamera c;
  c.width = static_cast<int>(Value(table, "width", row));
  c.height = static_cast<int>(Value(table, "height", row));
  c.fx = Value(table, "fx", row);
  c.fy = Value(table, "fy", row);
  c.cx = Value(table, "cx", row);
  c.cy = Value(table, "cy", row);
  for (int i = 0; i < 9; ++i)
  {
    c.R(i / 3, i % 3) = Value(table, "R", row, i);
  }
  for (int i = 0; i < 3; ++i)
  {
    c.t[i] = Value(table, "t", row, i);
  }
  return c;
}

// Table rows against the core's suggestions; returns a failure reason.
std::string CompareTable(vtkTable* table, const meshnbv::SuggestResult& core)
{
  if (table->GetNumberOfRows() != static_cast<vtkIdType>(core.suggestions.size()))
  {
    return std::to_string(table->GetNumberOfRows()) + " rows, the core has " +
      std::to_string(core.suggestions.size());
  }
  auto* label = vtkStringArray::SafeDownCast(table->GetColumnByName("label"));
  auto* source = vtkStringArray::SafeDownCast(table->GetColumnByName("source"));
  for (vtkIdType row = 0; row < table->GetNumberOfRows(); ++row)
  {
    const meshnbv::Suggestion& s = core.suggestions[static_cast<std::size_t>(row)];
    const meshnbv::Vec3 c = s.camera.center();
    const double expected[] = { double(s.rank), s.energy.total, s.energy.occlusion, s.energy.focus,
      s.energy.parallax, s.energy.incidence, c.x(), c.y(), c.z(), s.look_at.x(),
      double(s.seen_faces.size()), double(s.region) };
    const double got[] = { Value(table, "rank", row), Value(table, "energy", row),
      Value(table, "occlusion", row), Value(table, "focus", row), Value(table, "parallax", row),
      Value(table, "incidence", row), Value(table, "centre", row, 0), Value(table, "centre", row, 1),
      Value(table, "centre", row, 2), Value(table, "look_at", row, 0),
      Value(table, "seen_faces", row), Value(table, "region", row) };
    for (std::size_t i = 0; i < sizeof(got) / sizeof(got[0]); ++i)
    {
      if (!vtkMeshNBVTest::SameValue(got[i], expected[i], 1e-9))
      {
        return "row " + std::to_string(row) + " value " + std::to_string(i) + ": " +
          std::to_string(got[i]) + " vs " + std::to_string(expected[i]);
      }
    }
    if (label->GetValue(row) != s.label || source->GetValue(row) != s.source)
    {
      return "row " + std::to_string(row) + ": label/source " + label->GetValue(row) + "/" +
        source->GetValue(row);
    }
    const double sum = Value(table, "occlusion", row) + Value(table, "focus", row) +
      Value(table, "parallax", row) + Value(table, "incidence", row);
    if (std::abs(sum - Value(table, "energy", row)) > 1e-9 * std::max(1.0, std::abs(sum)))
    {
      return "row " + std::to_string(row) + ": energy is not the sum of its terms";
    }
  }
  return "";
}

// Frustum geometry against the table's cameras; returns a failure reason.
std::string CheckFrustums(vtkPolyData* frustums, vtkTable* table, double frustumDepth, double scale)
{
  const vtkIdType n = table->GetNumberOfRows();
  if (frustums->GetNumberOfPoints() != 5 * n || frustums->GetNumberOfPolys() != 6 * n)
  {
    return "expected 5 points and 6 triangles per suggestion";
  }
  vtkDataArray* rank = frustums->GetCellData()->GetArray("rank");
  vtkDataArray* energy = frustums->GetCellData()->GetArray("energy");
  if (!rank || !energy || !frustums->GetCellData()->GetArray("RGB"))
  {
    return "cell arrays rank, energy, RGB missing";
  }
  for (vtkIdType row = 0; row < n; ++row)
  {
    const meshnbv::PinholeCamera cam = CameraOfRow(table, row);
    const meshnbv::Vec3 centre = cam.center();
    const meshnbv::Vec3 lookAt(
      Value(table, "look_at", row, 0), Value(table, "look_at", row, 1), Value(table, "look_at", row, 2));
    // FrustumDepth, or the core's default: a share of the depth of the point looked at.
    double depth = frustumDepth;
    if (depth == 0)
    {
      double p[3];
      frustums->GetPoint(5 * row + 1, p);
      depth = cam.depth(meshnbv::Vec3(p[0], p[1], p[2]));
      if (!(depth > 0 && depth < cam.depth(lookAt)))
      {
        return "suggestion " + std::to_string(row) + ": base depth " + std::to_string(depth) +
          " not between the camera and the point looked at";
      }
    }
    const std::array<meshnbv::Vec2, 4> corners = { meshnbv::Vec2(-0.5, -0.5),
      meshnbv::Vec2(cam.width - 0.5, -0.5), meshnbv::Vec2(cam.width - 0.5, cam.height - 0.5),
      meshnbv::Vec2(-0.5, cam.height - 0.5) };
    int apexes = 0;
    std::array<int, 4> onRay = { 0, 0, 0, 0 };
    for (vtkIdType k = 0; k < 5; ++k)
    {
      double p[3];
      frustums->GetPoint(5 * row + k, p);
      const meshnbv::Vec3 point(p[0], p[1], p[2]);
      if ((point - centre).norm() <= 1e-9 * scale)
      {
        ++apexes;
        continue;
      }
      for (std::size_t c = 0; c < 4; ++c)
      {
        const meshnbv::Ray ray = cam.viewing_ray(corners[c]);
        const meshnbv::Vec3 v = point - ray.origin;
        const double along = v.dot(ray.direction);
        const double off = (v - along * ray.direction).norm();
        if (along > 0 && off <= 1e-9 * scale && std::abs(cam.depth(point) - depth) <= 1e-9 * scale)
        {
          ++onRay[c];
        }
      }
    }
    if (apexes != 1 || onRay != std::array<int, 4>{ 1, 1, 1, 1 })
    {
      std::ostringstream s;
      s << "suggestion " << row << ": " << apexes << " apex(es), corner rays hit " << onRay[0] << onRay[1]
        << onRay[2] << onRay[3];
      return s.str();
    }
    for (vtkIdType cell = 6 * row; cell < 6 * row + 6; ++cell)
    {
      if (rank->GetComponent(cell, 0) != Value(table, "rank", row) ||
        std::abs(energy->GetComponent(cell, 0) - Value(table, "energy", row)) >
          1e-6 * std::max(1.0, std::abs(Value(table, "energy", row))))
      {
        return "cell " + std::to_string(cell) + ": rank/energy differ from the table";
      }
    }
  }
  return "";
}

} // namespace

int TestNextBestView(int argc, char* argv[])
{
  vtkMeshNBVTest::Arguments args;
  MESHNBV_CHECK(vtkMeshNBVTest::ParseArguments(argc, argv, &args), "bad arguments");
  const meshnbv::Scene scene = meshnbv::io::read_scene(args.ProjectFile());
  const std::vector<float> pri = meshnbv::compute_pri(scene).pri;
  const double scale = scene.mesh.bounding_box().diagonal() * 10;

  vtkNew<vtkMeshNBVSceneReader> reader;
  reader->SetFileName(args.ProjectFile().c_str());
  vtkNew<vtkMeshNBVPRIFilter> priFilter;
  priFilter->SetInputConnection(reader->GetOutputPort(0));
  priFilter->SetViewsConnection(reader->GetViewsOutputPort());

  struct Mode
  {
    const char* Name;
    int Candidates;
    int Top;
    double FrustumDepth;
  };
  const Mode modes[] = {
    { "sampled", vtkMeshNBVNextBestViewFilter::SAMPLED, 3, 0.0 },
    { "given", vtkMeshNBVNextBestViewFilter::GIVEN, 2, 2.5 },
    { "refined", vtkMeshNBVNextBestViewFilter::REFINED, 1, 0.0 },
  };
  for (const Mode& mode : modes)
  {
    vtkNew<vtkMeshNBVNextBestViewFilter> nbv;
    vtkMeshNBVTest::Watch watch(nbv);
    nbv->SetInputConnection(priFilter->GetOutputPort());
    nbv->SetViewsConnection(reader->GetViewsOutputPort());
    nbv->SetCandidates(mode.Candidates);
    nbv->SetTop(mode.Top);
    nbv->SetFrustumDepth(mode.FrustumDepth);
    meshnbv::SuggestOptions options;
    options.mode = meshnbv::parse_candidate_mode(nbv->GetCandidatesAsString());
    options.top = mode.Top;
    std::vector<meshnbv::View> given;
    if (mode.Candidates == vtkMeshNBVNextBestViewFilter::GIVEN)
    {
      nbv->SetCandidatesConnection(reader->GetViewsOutputPort()); // the views themselves
      given = scene.views;
    }
    if (mode.Candidates == vtkMeshNBVNextBestViewFilter::REFINED)
    {
      nbv->SetRefineBest(2);
      nbv->SetRefineIterations(40);
      nbv->SetDirections(128);
      nbv->SetSeed(7);
      options.refine_best = 2;
      options.refine.iterations = 40;
      options.sampling.directions = 128;
      options.sampling.seed = 7;
    }
    nbv->Update();
    MESHNBV_CHECK(watch.Algorithm->Errors.empty(), mode.Name << ": " << watch.Algorithm->AllErrors());
    const meshnbv::SuggestResult core = meshnbv::suggest_views(scene, pri, options, given);
    vtkTable* table = nbv->GetSuggestionsOutput();
    const std::string tableReason = CompareTable(table, core);
    MESHNBV_CHECK(tableReason.empty(), mode.Name << ": " << tableReason);
    const std::string frustumReason =
      CheckFrustums(nbv->GetFrustumsOutput(), table, mode.FrustumDepth, scale);
    MESHNBV_CHECK(frustumReason.empty(), mode.Name << ": " << frustumReason);
    MESHNBV_CHECK(table->GetFieldData()->GetAbstractArray("SuggestionsJSON"), "SuggestionsJSON");
    std::cout << mode.Name << ": " << table->GetNumberOfRows()
              << " suggestions equal to the core's; best energy "
              << Value(table, "energy", 0) << "; frustum apexes and corner rays within 1e-9\n";
  }
  return EXIT_SUCCESS;
}
