// Pipeline pixels reach the core in memory, never through files:
// - vtkMeshNBVPRIFilter on view blocks that carry pixels and no ImagePath,
//   after the project's image files are deleted, gives bitwise the PRI and
//   PRIViews of meshnbv::compute_pri on the same images read from files
//   (SSD grey and NCC colour); so do RGBA (4 components) pixels, and
//   16-bit ones (unsigned short, v * 257, kept at 16 bits) give bitwise the
//   core's PRI on 16-bit images of those values. Other scalar types and pixels whose size
//   differs from the camera's are clear errors.
// - vtkMeshNBVNextBestViewFilter counts such blocks as existing views (no
//   image path needed): the same suggestions as from the reader's views.
// - vtkMeshNBVSuggestionWriter refuses to write a .mlp that would lose
//   those images, and writes nothing.
// ctest runs this test with no writable temporary folder
// (tests/support/without_temp_folders.sh); it checks that TMPDIR is indeed
// unwritable when it is set.
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include "vtkMeshNBVNextBestViewFilter.h"
#include "vtkMeshNBVPRIFilter.h"
#include "vtkMeshNBVSceneReader.h"
#include "vtkMeshNBVSuggestionWriter.h"
#include "vtkMeshNBVTestUtilities.h"

#include "meshnbv/io/scene_io.h"
#include "meshnbv/pri.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>

namespace
{

namespace fs = std::filesystem;

// A copy of `views` whose blocks keep their pixels but no ImagePath;
// `pixels` (optional) replaces each block's pixel array.
vtkSmartPointer<vtkMultiBlockDataSet> PixelsOnly(vtkMultiBlockDataSet* views,
  const std::function<vtkSmartPointer<vtkDataArray>(vtkUnsignedCharArray*)>& pixels = {})
{
  auto out = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  out->SetNumberOfBlocks(views->GetNumberOfBlocks());
  for (unsigned int i = 0; i < views->GetNumberOfBlocks(); ++i)
  {
    vtkNew<vtkImageData> block;
    block->DeepCopy(views->GetBlock(i));
    block->GetFieldData()->RemoveArray("ImagePath");
    if (pixels)
    {
      auto* original = vtkUnsignedCharArray::SafeDownCast(block->GetPointData()->GetScalars());
      vtkSmartPointer<vtkDataArray> replaced = pixels(original);
      replaced->SetName("Pixels");
      block->GetPointData()->SetScalars(replaced);
    }
    out->SetBlock(i, block);
  }
  return out;
}

// PRI of the filter on `mesh` and `views`, or an empty vector (errors in `watch`).
struct FilterPri
{
  std::vector<float> Pri;
  std::vector<int> Views;
  std::string Errors;
};

FilterPri RunPri(vtkPolyData* mesh, vtkDataObject* views, bool nccColour)
{
  vtkNew<vtkMeshNBVPRIFilter> pri;
  vtkMeshNBVTest::Watch watch(pri);
  pri->SetInputData(mesh);
  pri->SetViewsData(views);
  if (nccColour)
  {
    pri->SetMeasureToNCC();
    pri->ColorOn();
  }
  pri->Update();
  FilterPri out;
  out.Errors = watch.Algorithm->Errors.empty() ? "" : watch.Algorithm->AllErrors();
  auto* values = vtkFloatArray::SafeDownCast(pri->GetOutput()->GetCellData()->GetArray("PRI"));
  auto* counts = vtkIntArray::SafeDownCast(pri->GetOutput()->GetCellData()->GetArray("PRIViews"));
  if (values && counts)
  {
    out.Pri.assign(values->GetPointer(0), values->GetPointer(0) + values->GetNumberOfTuples());
    out.Views.assign(counts->GetPointer(0), counts->GetPointer(0) + counts->GetNumberOfTuples());
  }
  return out;
}

bool SameBits(const std::vector<float>& a, const std::vector<float>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

} // namespace

int TestInMemoryImages(int argc, char* argv[])
{
  vtkMeshNBVTest::Arguments args;
  MESHNBV_CHECK(vtkMeshNBVTest::ParseArguments(argc, argv, &args), "bad arguments");
  if (const char* tmp = std::getenv("TMPDIR"))
  {
    const std::string probe = std::string(tmp) + "/meshnbv-probe";
    std::FILE* f = std::fopen(probe.c_str(), "w");
    if (f)
    {
      std::fclose(f);
      std::remove(probe.c_str());
    }
    MESHNBV_CHECK(!f, "TMPDIR (" << tmp << ") is writable: run through without_temp_folders.sh");
    std::cout << "TMPDIR " << tmp << " is not writable\n";
  }

  // A private copy of the project, whose images are deleted once read.
  const fs::path project = fs::path(args.Scratch) / "project";
  fs::copy(args.Project, project, fs::copy_options::recursive);
  const std::string projectFile = (project / "project.mlp").string();
  const meshnbv::Scene scene = meshnbv::io::read_scene(projectFile);
  meshnbv::PriOptions nccColour;
  nccColour.measure = meshnbv::Measure::NCC;
  nccColour.color = true;
  const meshnbv::PriResult ssdFiles = meshnbv::compute_pri(scene);
  const meshnbv::PriResult nccFiles = meshnbv::compute_pri(scene, nccColour);
  // The same photos at 16 bits (v * 257), in memory, built here.
  meshnbv::Scene scene16 = scene;
  for (std::size_t i = 0; i < scene16.views.size(); ++i)
  {
    const auto eight = scene.image(i);
    meshnbv::Image wide(eight->width(), eight->height(), eight->channels(), 16);
    for (int y = 0; y < wide.height(); ++y)
    {
      for (int x = 0; x < wide.width() * wide.channels(); ++x)
      {
        wide.pixel16(0, y)[x] = static_cast<std::uint16_t>(eight->pixel(0, y)[x] * 257);
      }
    }
    scene16.views[i].pixels = std::make_shared<const meshnbv::Image>(std::move(wide));
    scene16.views[i].image_path.clear();
  }
  const meshnbv::PriResult ssd16 = meshnbv::compute_pri(scene16);

  vtkNew<vtkMeshNBVSceneReader> reader;
  reader->SetFileName(projectFile.c_str());
  reader->Update();
  vtkNew<vtkPolyData> mesh;
  mesh->DeepCopy(reader->GetOutput());
  vtkNew<vtkMultiBlockDataSet> readerViews;
  readerViews->DeepCopy(reader->GetViewsOutput());
  MESHNBV_CHECK(readerViews->GetNumberOfBlocks() == 8, "8 views");
  fs::remove_all(project / "images");
  MESHNBV_CHECK(!fs::exists(scene.views[0].image_path), "images still on disk");

  // 1. Pixels only, no file anywhere: bitwise the core's PRI from files.
  auto pixels = PixelsOnly(readerViews);
  for (bool ncc : { false, true })
  {
    const meshnbv::PriResult& core = ncc ? nccFiles : ssdFiles;
    const FilterPri r = RunPri(mesh, pixels, ncc);
    const char* name = ncc ? "ncc colour" : "ssd";
    MESHNBV_CHECK(r.Errors.empty(), name << ": " << r.Errors);
    MESHNBV_CHECK(SameBits(r.Pri, core.pri), name << ": PRI differs from the core's on files");
    MESHNBV_CHECK(r.Views == core.pri_views, name << ": PRIViews differ");
    std::cout << name << ", pixels in memory, image files deleted: " << core.observed
              << " observed faces, PRI bitwise equal to the core's from files\n";
  }

  // 2. 16-bit pixels (kept at 16 bits) and RGBA (alpha dropped).
  auto sixteen = PixelsOnly(readerViews, [](vtkUnsignedCharArray* a) {
    auto b = vtkSmartPointer<vtkUnsignedShortArray>::New();
    b->SetNumberOfComponents(a->GetNumberOfComponents());
    b->SetNumberOfTuples(a->GetNumberOfTuples());
    for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
    {
      b->SetValue(i, static_cast<unsigned short>(a->GetValue(i) * 257));
    }
    return vtkSmartPointer<vtkDataArray>(b);
  });
  auto rgba = PixelsOnly(readerViews, [](vtkUnsignedCharArray* a) {
    auto b = vtkSmartPointer<vtkUnsignedCharArray>::New();
    b->SetNumberOfComponents(4);
    b->SetNumberOfTuples(a->GetNumberOfTuples());
    for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
    {
      for (int c = 0; c < 3; ++c)
      {
        b->SetTypedComponent(t, c, a->GetTypedComponent(t, c));
      }
      b->SetTypedComponent(t, 3, static_cast<unsigned char>(t * 37));  // alpha, dropped
    }
    return vtkSmartPointer<vtkDataArray>(b);
  });
  for (auto [name, views] : { std::make_pair("unsigned short", sixteen.Get()),
         std::make_pair("RGBA", rgba.Get()) })
  {
    const FilterPri r = RunPri(mesh, views, false);
    MESHNBV_CHECK(r.Errors.empty(), name << ": " << r.Errors);
    const bool wide = std::string(name) == "unsigned short";
    MESHNBV_CHECK(SameBits(r.Pri, wide ? ssd16.pri : ssdFiles.pri),
      name << ": PRI differs from the core's on the same " << (wide ? "16-bit images" : "files"));
    std::cout << name << " pixels: PRI bitwise equal\n";
  }

  // 3. Float pixels, and pixels of the wrong size: clear errors.
  auto floats = PixelsOnly(readerViews, [](vtkUnsignedCharArray* a) {
    auto b = vtkSmartPointer<vtkFloatArray>::New();
    b->DeepCopy(a);
    return vtkSmartPointer<vtkDataArray>(b);
  });
  FilterPri r = RunPri(mesh, floats, false);
  MESHNBV_CHECK(r.Pri.empty() && r.Errors.find("unsigned char or unsigned short") != std::string::npos &&
      r.Errors.find("got float with 3") != std::string::npos &&
      r.Errors.find("vtkImageShiftScale") != std::string::npos,
    "float pixels: " << r.Errors);
  std::cout << "float pixels: " << r.Errors << "\n";
  vtkNew<vtkImageData> small;
  small->DeepCopy(pixels->GetBlock(2));
  small->SetDimensions(100, 80, 1);
  vtkNew<vtkUnsignedCharArray> smallPixels;
  smallPixels->SetNumberOfComponents(3);
  smallPixels->SetNumberOfTuples(100 * 80);
  smallPixels->Fill(128);
  small->GetPointData()->SetScalars(smallPixels);
  vtkNew<vtkMultiBlockDataSet> wrongSize;
  wrongSize->ShallowCopy(pixels);
  wrongSize->SetBlock(2, small);
  r = RunPri(mesh, wrongSize, false);
  MESHNBV_CHECK(r.Pri.empty() && r.Errors.find("the pixels are 100x80 but its camera says 320x240") !=
      std::string::npos,
    "wrong size: " << r.Errors);

  // 4. Next best view: blocks with pixels and no path are existing views.
  vtkNew<vtkPolyData> withPri;
  withPri->ShallowCopy(mesh);
  vtkNew<vtkFloatArray> priArray;
  priArray->SetName("PRI");
  priArray->SetNumberOfTuples(static_cast<vtkIdType>(ssdFiles.pri.size()));
  std::copy(ssdFiles.pri.begin(), ssdFiles.pri.end(), priArray->GetPointer(0));
  withPri->GetCellData()->AddArray(priArray);
  std::vector<std::vector<double>> suggestions[2];
  vtkDataObject* nbvViews[2] = { readerViews, pixels };
  for (int k = 0; k < 2; ++k)
  {
    vtkNew<vtkMeshNBVNextBestViewFilter> nbv;
    vtkMeshNBVTest::Watch watch(nbv);
    nbv->SetInputData(withPri);
    nbv->SetViewsData(nbvViews[k]);
    nbv->SetTop(2);
    nbv->SetDirections(64);
    nbv->Update();
    MESHNBV_CHECK(watch.Algorithm->Errors.empty(), "next best view: " << watch.Algorithm->AllErrors());
    vtkTable* table = nbv->GetSuggestionsOutput();
    MESHNBV_CHECK(table->GetNumberOfRows() == 2, "next best view: " << table->GetNumberOfRows() << " rows");
    for (vtkIdType row = 0; row < 2; ++row)
    {
      auto* centre = vtkDataArray::SafeDownCast(table->GetColumnByName("centre"));
      auto* energy = vtkDataArray::SafeDownCast(table->GetColumnByName("energy"));
      suggestions[k].push_back({ centre->GetComponent(row, 0), centre->GetComponent(row, 1),
        centre->GetComponent(row, 2), energy->GetComponent(row, 0) });
    }
  }
  MESHNBV_CHECK(suggestions[0] == suggestions[1],
    "next best view: pixel-only views give other suggestions than the reader's views");
  std::cout << "next best view: the same 2 suggestions from pixel-only views\n";

  // 5. The writer cannot reference images that exist only as pixels.
  vtkNew<vtkMeshNBVNextBestViewFilter> nbv;
  nbv->SetInputData(withPri);
  nbv->SetViewsData(pixels);
  nbv->SetDirections(64);
  vtkNew<vtkMeshNBVSuggestionWriter> writer;
  vtkMeshNBVTest::Watch watch(writer);
  const std::string mlp = args.Scratch + "/suggestions.mlp";
  writer->SetInputConnection(nbv->GetSuggestionsOutputPort());
  writer->SetViewsData(pixels);
  writer->SetMeshData(mesh);
  writer->SetFileName(mlp.c_str());
  MESHNBV_CHECK(writer->Write() == 0 && watch.Algorithm->HasError("has pixels but no ImagePath"),
    "writer: " << watch.Algorithm->AllErrors());
  MESHNBV_CHECK(!fs::exists(mlp) && !fs::exists(args.Scratch + "/suggestions_mesh.ply"),
    "writer: a file was written");
  std::cout << "writer: " << watch.Algorithm->Errors[0] << "\n";
  return EXIT_SUCCESS;
}
