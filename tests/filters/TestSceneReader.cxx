// vtkMeshNBVSceneReader against the core's reader on the synthetic project:
// the mesh is the same (points, triangles), every view block carries the
// core's camera exactly (K, R, t, size, label), and its pixels are the
// image's, rows flipped: image pixel (x, y) (y down, the core's convention)
// is point (x, H-1-y) of the block. The same scene read from .mlp and from
// JSON gives the same cameras; a view without image has no pixels.
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "vtkMeshNBVConversion.h"
#include "vtkMeshNBVSceneReader.h"
#include "vtkMeshNBVTestUtilities.h"

#include "meshnbv/io/scene_io.h"

namespace
{

std::string FieldString(vtkFieldData* fd, const char* name)
{
  auto* a = vtkStringArray::SafeDownCast(fd->GetAbstractArray(name));
  return a && a->GetNumberOfValues() ? a->GetValue(0) : std::string("<missing>");
}

// Compares block `i` of `views` with the core's view; returns a failure reason.
std::string CompareView(vtkMultiBlockDataSet* views, unsigned int i, const meshnbv::View& view,
  const meshnbv::Scene& scene, bool expectPixels)
{
  auto* block = vtkImageData::SafeDownCast(views->GetBlock(i));
  if (!block)
  {
    return "block is not a vtkImageData";
  }
  const char* name = views->GetMetaData(i)->Get(vtkCompositeDataSet::NAME());
  if (!name || view.label != name)
  {
    return "block name differs from the label";
  }
  vtkFieldData* fd = block->GetFieldData();
  if (FieldString(fd, "Label") != view.label)
  {
    return "Label differs";
  }
  const meshnbv::PinholeCamera& c = view.camera;
  double size[2], k[9], r[9], t[3], d[2];
  fd->GetArray("ImageSize")->GetTuple(0, size);
  fd->GetArray("K")->GetTuple(0, k);
  fd->GetArray("R")->GetTuple(0, r);
  fd->GetArray("t")->GetTuple(0, t);
  fd->GetArray("Distortion")->GetTuple(0, d);
  if (size[0] != c.width || size[1] != c.height)
  {
    return "ImageSize differs";
  }
  const double expectedK[9] = { c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1 };
  for (int j = 0; j < 9; ++j)
  {
    if (k[j] != expectedK[j] || r[j] != c.R(j / 3, j % 3))
    {
      return "K or R differs at " + std::to_string(j);
    }
  }
  for (int j = 0; j < 3; ++j)
  {
    if (t[j] != c.t[j])
    {
      return "t differs";
    }
  }
  if (d[0] != c.k1 || d[1] != c.k2 || fd->GetArray("Used")->GetTuple1(0) != (view.used ? 1 : 0))
  {
    return "Distortion or Used differs";
  }
  auto* pixels = vtkUnsignedCharArray::SafeDownCast(block->GetPointData()->GetScalars());
  if (!expectPixels)
  {
    return pixels ? "pixels present although not expected" : "";
  }
  const auto image = scene.image(i);
  int dims[3];
  block->GetDimensions(dims);
  if (!pixels || dims[0] != image->width() || dims[1] != image->height() || dims[2] != 1 ||
    pixels->GetNumberOfComponents() != image->channels())
  {
    return "pixels missing or of the wrong shape";
  }
  const int w = image->width(), h = image->height(), ch = image->channels();
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      for (int cc = 0; cc < ch; ++cc)
      {
        const vtkIdType point = static_cast<vtkIdType>(h - 1 - y) * w + x;
        if (pixels->GetTypedComponent(point, cc) != image->pixel(x, y)[cc])
        {
          return "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") differs";
        }
      }
    }
  }
  return "";
}

} // namespace

int TestSceneReader(int argc, char* argv[])
{
  vtkMeshNBVTest::Arguments args;
  MESHNBV_CHECK(vtkMeshNBVTest::ParseArguments(argc, argv, &args), "bad arguments");
  const meshnbv::Scene scene = meshnbv::io::read_scene(args.ProjectFile());

  vtkNew<vtkMeshNBVSceneReader> reader;
  vtkMeshNBVTest::Watch watch(reader);
  reader->SetFileName(args.ProjectFile().c_str());
  reader->Update();
  MESHNBV_CHECK(watch.Algorithm->Errors.empty(), watch.Algorithm->AllErrors());
  vtkPolyData* mesh = reader->GetOutput();
  MESHNBV_CHECK(mesh->GetNumberOfPoints() == static_cast<vtkIdType>(scene.mesh.num_vertices()),
    mesh->GetNumberOfPoints() << " points");
  MESHNBV_CHECK(mesh->GetNumberOfPolys() == static_cast<vtkIdType>(scene.mesh.num_faces()),
    mesh->GetNumberOfPolys() << " triangles");
  for (std::size_t v = 0; v < scene.mesh.num_vertices(); ++v)
  {
    double p[3];
    mesh->GetPoint(static_cast<vtkIdType>(v), p);
    MESHNBV_CHECK(p[0] == scene.mesh.vertices[v].x() && p[1] == scene.mesh.vertices[v].y() &&
        p[2] == scene.mesh.vertices[v].z(),
      "vertex " << v);
  }
  for (std::size_t f = 0; f < scene.mesh.num_faces(); ++f)
  {
    vtkIdType n;
    const vtkIdType* ids;
    mesh->GetCellPoints(static_cast<vtkIdType>(f), n, ids);
    const meshnbv::Face& face = scene.mesh.faces[f];
    MESHNBV_CHECK(n == 3 && ids[0] == face[0] && ids[1] == face[1] && ids[2] == face[2], "face " << f);
  }
  MESHNBV_CHECK(FieldString(mesh->GetFieldData(), "MeshFileName") == scene.mesh_path,
    "MeshFileName " << FieldString(mesh->GetFieldData(), "MeshFileName"));

  vtkMultiBlockDataSet* views = reader->GetViewsOutput();
  MESHNBV_CHECK(views->GetNumberOfBlocks() == scene.views.size(), views->GetNumberOfBlocks() << " blocks");
  MESHNBV_CHECK(FieldString(views->GetFieldData(), "Format") == "mlp", "Format");
  for (unsigned int i = 0; i < views->GetNumberOfBlocks(); ++i)
  {
    const std::string reason = CompareView(views, i, scene.views[i], scene, true);
    MESHNBV_CHECK(reason.empty(), "view " << i << ": " << reason);
  }

  // JSON scene of the same project (Format set explicitly), without pixels.
  const meshnbv::Scene jsonScene = meshnbv::io::read_scene(args.Project + "/scene.json");
  vtkNew<vtkMeshNBVSceneReader> json;
  json->SetFileName((args.Project + "/scene.json").c_str());
  json->SetFormat("json");
  json->LoadImagesOff();
  json->Update();
  vtkMultiBlockDataSet* jsonViews = json->GetViewsOutput();
  MESHNBV_CHECK(jsonViews->GetNumberOfBlocks() == jsonScene.views.size(), "JSON views");
  for (unsigned int i = 0; i < jsonViews->GetNumberOfBlocks(); ++i)
  {
    const std::string reason = CompareView(jsonViews, i, jsonScene.views[i], jsonScene, false);
    MESHNBV_CHECK(reason.empty(), "JSON view " << i << ": " << reason);
    const std::string path = FieldString(jsonViews->GetBlock(i)->GetFieldData(), "ImagePath");
    MESHNBV_CHECK(std::filesystem::exists(path), "ImagePath " << path);
  }

  // A view without image (a candidate) gets an empty ImagePath and no pixels.
  meshnbv::Scene withCandidate = scene;
  meshnbv::View candidate = scene.views[0];
  candidate.label = "candidate";
  candidate.image_path.clear();
  withCandidate.views.push_back(candidate);
  const std::string candidateFile = args.Scratch + "/with_candidate.json";
  meshnbv::io::write_scene(withCandidate, candidateFile);
  vtkNew<vtkMeshNBVSceneReader> candidates;
  candidates->SetFileName(candidateFile.c_str());
  candidates->Update();
  vtkMultiBlockDataSet* cviews = candidates->GetViewsOutput();
  MESHNBV_CHECK(cviews->GetNumberOfBlocks() == scene.views.size() + 1, "candidate scene views");
  const unsigned int last = cviews->GetNumberOfBlocks() - 1;
  const std::string reason = CompareView(cviews, last, candidate, withCandidate, false);
  MESHNBV_CHECK(reason.empty(), "candidate view: " << reason);
  MESHNBV_CHECK(FieldString(cviews->GetBlock(last)->GetFieldData(), "ImagePath").empty(), "candidate ImagePath");

  // Every lens parameter and skew survive the view block (K[0][1], "Lens").
  for (const bool fisheye : { false, true })
  {
    meshnbv::View lensView = scene.views[0];
    lensView.image_path.clear();
    meshnbv::PinholeCamera& lc = lensView.camera;
    lc.lens = fisheye ? meshnbv::LensModel::Fisheye : meshnbv::LensModel::Brown;
    lc.k1 = -0.01, lc.k2 = 0.002, lc.k3 = -0.0003, lc.k4 = 0.0001, lc.skew = 0.75;
    if (!fisheye)
    {
      lc.k5 = 0.0002, lc.k6 = -0.0001, lc.p1 = 0.0004, lc.p2 = -0.0006;
    }
    vtkNew<vtkMultiBlockDataSet> blocks;
    blocks->SetNumberOfBlocks(1);
    blocks->SetBlock(0, vtkMeshNBV::ToViewBlock(lensView, nullptr));
    const std::vector<vtkMeshNBV::ViewBlock> extracted = vtkMeshNBV::ExtractViews(blocks);
    MESHNBV_CHECK(extracted.size() == 1, "lens view block not extracted");
    const meshnbv::PinholeCamera& back = extracted[0].view.camera;
    MESHNBV_CHECK(back.lens == lc.lens && back.k1 == lc.k1 && back.k2 == lc.k2 && back.k3 == lc.k3 &&
        back.k4 == lc.k4 && back.k5 == lc.k5 && back.k6 == lc.k6 && back.p1 == lc.p1 &&
        back.p2 == lc.p2 && back.skew == lc.skew,
      "lens parameters lost in the view block (fisheye " << fisheye << ")");
  }

  std::cout << "mesh " << mesh->GetNumberOfPoints() << " points, " << mesh->GetNumberOfPolys()
            << " triangles; " << views->GetNumberOfBlocks()
            << " views with cameras and pixels equal to the core's\n";
  return EXIT_SUCCESS;
}
