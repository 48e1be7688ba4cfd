// Error paths of the VTK algorithms: each reports one error through
// vtkErrorMacro (seen by an ErrorEvent observer), carrying the core's
// message where the core found the problem, and leaves its outputs empty.
// Cancelling through AbortExecute leaves the output empty without an error.
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include "vtkMeshNBVNextBestViewFilter.h"
#include "vtkMeshNBVPRIFilter.h"
#include "vtkMeshNBVSceneReader.h"
#include "vtkMeshNBVTestUtilities.h"

#include "meshnbv/error.h"
#include "meshnbv/io/scene_io.h"
#include "meshnbv/pri.h"

namespace
{

// Sets AbortExecute on the first progress event.
class Canceller : public vtkCommand
{
public:
  static Canceller* New() { return new Canceller; }
  void Execute(vtkObject* caller, unsigned long, void*) override
  {
    ++this->Events;
    static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn();
  }
  int Events = 0;
};

// The views of the reader with block `index` replaced by `block`.
vtkSmartPointer<vtkMultiBlockDataSet> ReplaceBlock(
  vtkMultiBlockDataSet* views, unsigned int index, vtkDataObject* block)
{
  auto copy = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  copy->ShallowCopy(views);
  copy->SetBlock(index, block);
  return copy;
}

} // namespace

int TestErrors(int argc, char* argv[])
{
  vtkMeshNBVTest::Arguments args;
  MESHNBV_CHECK(vtkMeshNBVTest::ParseArguments(argc, argv, &args), "bad arguments");
  vtkNew<vtkMeshNBVSceneReader> reader;
  reader->SetFileName(args.ProjectFile().c_str());
  reader->Update();
  vtkMultiBlockDataSet* views = reader->GetViewsOutput();
  vtkPolyData* mesh = reader->GetOutput();
  MESHNBV_CHECK(views->GetNumberOfBlocks() == 8 && mesh->GetNumberOfCells() > 0, "project");

  // 1. The reader: a missing scene, with the core's message.
  {
    vtkNew<vtkMeshNBVSceneReader> missing;
    vtkMeshNBVTest::Watch watch(missing);
    missing->SetFileName((args.Scratch + "/nothing.mlp").c_str());
    missing->Update();
    std::string coreMessage;
    try
    {
      meshnbv::io::read_scene(args.Scratch + "/nothing.mlp");
    }
    catch (const meshnbv::Error& e)
    {
      coreMessage = e.what();
    }
    MESHNBV_CHECK(!coreMessage.empty() && watch.Algorithm->HasError(coreMessage),
      "reader: " << watch.Algorithm->AllErrors() << " vs the core's " << coreMessage);
    MESHNBV_CHECK(missing->GetOutput()->GetNumberOfPoints() == 0 &&
        missing->GetViewsOutput()->GetNumberOfBlocks() == 0,
      "reader: output not empty");
    std::cout << "reader, missing file: " << watch.Algorithm->Errors[0] << "\n";
  }

  // 2. PRI without a views input.
  {
    vtkNew<vtkMeshNBVPRIFilter> pri;
    vtkMeshNBVTest::Watch watch(pri);
    pri->SetInputData(mesh);
    pri->Update();
    MESHNBV_CHECK(watch.Algorithm->Errors.size() == 1 && watch.Algorithm->HasError("no views input"),
      "PRI without views: " << watch.Algorithm->AllErrors());
    MESHNBV_CHECK(pri->GetOutput()->GetNumberOfCells() == 0 && pri->GetOutput()->GetNumberOfPoints() == 0,
      "PRI without views: output not empty");
    std::cout << "PRI, no views input: " << watch.Algorithm->Errors[0] << "\n";
  }

  // 3. PRI with a view that carries no camera data (an image block with
  //    pixels but empty field data), and one whose K is missing.
  {
    vtkNew<vtkImageData> bare;
    bare->SetDimensions(320, 240, 1);
    bare->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
    auto noCamera = ReplaceBlock(views, 3, bare);
    vtkNew<vtkMeshNBVPRIFilter> pri;
    vtkMeshNBVTest::Watch watch(pri);
    pri->SetInputData(mesh);
    pri->SetViewsData(noCamera);
    pri->Update();
    MESHNBV_CHECK(watch.Algorithm->Errors.size() == 1 && watch.Algorithm->HasError("view 3") &&
        watch.Algorithm->HasError("no camera data"),
      "PRI, view without camera: " << watch.Algorithm->AllErrors());
    MESHNBV_CHECK(pri->GetOutput()->GetNumberOfCells() == 0, "PRI, view without camera: output");
    std::cout << "PRI, view without camera data: " << watch.Algorithm->Errors[0] << "\n";

    vtkNew<vtkImageData> noK;
    noK->DeepCopy(views->GetBlock(5));
    noK->GetFieldData()->RemoveArray("K");
    vtkNew<vtkMeshNBVPRIFilter> pri2;
    vtkMeshNBVTest::Watch watch2(pri2);
    pri2->SetInputData(mesh);
    pri2->SetViewsData(ReplaceBlock(views, 5, noK));
    pri2->Update();
    MESHNBV_CHECK(watch2.Algorithm->HasError("view 5") && watch2.Algorithm->HasError("missing or malformed: K)"),
      "PRI, view without K: " << watch2.Algorithm->AllErrors());
    MESHNBV_CHECK(pri2->GetOutput()->GetNumberOfCells() == 0, "PRI, view without K: output");
  }

  // 4. A problem only the core sees (one view with pixels is too few): the
  //    filter reports exactly the core's message.
  {
    vtkNew<vtkMultiBlockDataSet> one;
    one->SetNumberOfBlocks(1);
    one->SetBlock(0, views->GetBlock(0));
    vtkNew<vtkMeshNBVPRIFilter> pri;
    vtkMeshNBVTest::Watch watch(pri);
    pri->SetInputData(mesh);
    pri->SetViewsData(one);
    pri->Update();
    meshnbv::Scene scene = meshnbv::io::read_scene(args.ProjectFile());
    scene.views.resize(1);
    std::string coreMessage;
    try
    {
      meshnbv::compute_pri(scene);
    }
    catch (const meshnbv::Error& e)
    {
      coreMessage = e.what();
    }
    MESHNBV_CHECK(!coreMessage.empty() && watch.Algorithm->Errors.size() == 1 &&
        watch.Algorithm->HasError(coreMessage),
      "PRI, one view: " << watch.Algorithm->AllErrors() << " vs the core's " << coreMessage);
    MESHNBV_CHECK(pri->GetOutput()->GetNumberOfCells() == 0, "PRI, one view: output");
    std::cout << "PRI, one view (core's message): " << watch.Algorithm->Errors[0] << "\n";
  }

  // 5. A mesh that is not made of triangles.
  {
    vtkNew<vtkPolyData> quad;
    vtkNew<vtkPoints> points;
    points->InsertNextPoint(0, 0, 0);
    points->InsertNextPoint(1, 0, 0);
    points->InsertNextPoint(1, 1, 0);
    points->InsertNextPoint(0, 1, 0);
    vtkNew<vtkCellArray> polys;
    const vtkIdType ids[4] = { 0, 1, 2, 3 };
    polys->InsertNextCell(4, ids);
    quad->SetPoints(points);
    quad->SetPolys(polys);
    vtkNew<vtkMeshNBVPRIFilter> pri;
    vtkMeshNBVTest::Watch watch(pri);
    pri->SetInputData(quad);
    pri->SetViewsData(views);
    pri->Update();
    MESHNBV_CHECK(watch.Algorithm->HasError("vtkTriangleFilter"), "quads: " << watch.Algorithm->AllErrors());
    MESHNBV_CHECK(pri->GetOutput()->GetNumberOfCells() == 0, "quads: output");
  }

  // 6. Next best view: no views input; no PRI array; a view without camera.
  {
    vtkNew<vtkFloatArray> priArray;
    priArray->SetName("PRI");
    priArray->SetNumberOfTuples(mesh->GetNumberOfCells());
    for (vtkIdType i = 0; i < mesh->GetNumberOfCells(); ++i)
    {
      priArray->SetValue(i, static_cast<float>(i % 97));
    }
    vtkNew<vtkPolyData> withPri;
    withPri->ShallowCopy(mesh);
    withPri->GetCellData()->AddArray(priArray);

    vtkNew<vtkMeshNBVNextBestViewFilter> nbv;
    vtkMeshNBVTest::Watch watch(nbv);
    nbv->SetInputData(withPri);
    nbv->Update();
    MESHNBV_CHECK(watch.Algorithm->Errors.size() == 1 && watch.Algorithm->HasError("no views input"),
      "NBV without views: " << watch.Algorithm->AllErrors());
    MESHNBV_CHECK(nbv->GetFrustumsOutput()->GetNumberOfCells() == 0 &&
        nbv->GetSuggestionsOutput()->GetNumberOfRows() == 0,
      "NBV without views: output not empty");
    std::cout << "NBV, no views input: " << watch.Algorithm->Errors[0] << "\n";

    vtkNew<vtkMeshNBVNextBestViewFilter> noPri;
    vtkMeshNBVTest::Watch watchPri(noPri);
    noPri->SetInputData(mesh);
    noPri->SetViewsData(views);
    noPri->Update();
    MESHNBV_CHECK(watchPri.Algorithm->HasError("no cell array 'PRI'"), "NBV without PRI: " << watchPri.Algorithm->AllErrors());

    vtkNew<vtkMeshNBVNextBestViewFilter> noCamera;
    vtkMeshNBVTest::Watch watchCamera(noCamera);
    vtkNew<vtkImageData> bare;
    noCamera->SetInputData(withPri);
    noCamera->SetViewsData(ReplaceBlock(views, 0, bare));
    noCamera->Update();
    MESHNBV_CHECK(watchCamera.Algorithm->HasError("no camera data"),
      "NBV, view without camera: " << watchCamera.Algorithm->AllErrors());
    MESHNBV_CHECK(noCamera->GetFrustumsOutput()->GetNumberOfCells() == 0 &&
        noCamera->GetSuggestionsOutput()->GetNumberOfRows() == 0,
      "NBV, view without camera: output not empty");
  }

  // 7. Cancellation: AbortExecute set from a progress observer stops the
  //    core; the output is empty and no error is reported.
  {
    vtkNew<vtkMeshNBVPRIFilter> pri;
    vtkMeshNBVTest::Watch watch(pri);
    vtkNew<Canceller> cancel;
    pri->AddObserver(vtkCommand::ProgressEvent, cancel);
    pri->SetInputData(mesh);
    pri->SetViewsData(views);
    pri->Update();
    MESHNBV_CHECK(cancel->Events >= 1, "no progress event");
    MESHNBV_CHECK(watch.Algorithm->Errors.empty(), "cancel: " << watch.Algorithm->AllErrors());
    MESHNBV_CHECK(pri->GetOutput()->GetNumberOfCells() == 0, "cancel: output not empty");
    std::cout << "PRI cancelled after " << cancel->Events << " progress event(s): empty output, no error\n";
  }
  return EXIT_SUCCESS;
}
