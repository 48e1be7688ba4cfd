// vtkMeshNBVSuggestionWriter: the JSON document holds the table's
// suggestions (label, energy, centre); the .mlp project read back by the
// core holds the scene's views plus one raster per suggestion (nbv_1, ...)
// whose cameras have the table's centres (to 1e-6 of the scene's size).
// Existing files are kept unless Overwrite is on; a wrong extension or a
// missing input is an error.
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkTable.h"

#include "vtkMeshNBVNextBestViewFilter.h"
#include "vtkMeshNBVPRIFilter.h"
#include "vtkMeshNBVSceneReader.h"
#include "vtkMeshNBVSuggestionWriter.h"
#include "vtkMeshNBVTestUtilities.h"

#include "meshnbv/io/file_util.h"
#include "meshnbv/io/scene_io.h"

#include <nlohmann/json.hpp>

int TestSuggestionWriter(int argc, char* argv[])
{
  vtkMeshNBVTest::Arguments args;
  MESHNBV_CHECK(vtkMeshNBVTest::ParseArguments(argc, argv, &args), "bad arguments");
  vtkNew<vtkMeshNBVSceneReader> reader;
  reader->SetFileName(args.ProjectFile().c_str());
  vtkNew<vtkMeshNBVPRIFilter> pri;
  pri->SetInputConnection(reader->GetOutputPort(0));
  pri->SetViewsConnection(reader->GetViewsOutputPort());
  vtkNew<vtkMeshNBVNextBestViewFilter> nbv;
  nbv->SetInputConnection(pri->GetOutputPort());
  nbv->SetViewsConnection(reader->GetViewsOutputPort());
  nbv->SetTop(2);
  nbv->Update();
  vtkTable* table = nbv->GetSuggestionsOutput();
  MESHNBV_CHECK(table->GetNumberOfRows() == 2, table->GetNumberOfRows() << " rows");
  auto centre = [&](vtkIdType row, int c) {
    return vtkDataArray::SafeDownCast(table->GetColumnByName("centre"))->GetComponent(row, c);
  };
  auto energy = [&](vtkIdType row) {
    return vtkDataArray::SafeDownCast(table->GetColumnByName("energy"))->GetComponent(row, 0);
  };

  // JSON.
  const std::string jsonFile = args.Scratch + "/suggestions.json";
  vtkNew<vtkMeshNBVSuggestionWriter> json;
  vtkMeshNBVTest::Watch watch(json);
  json->SetInputConnection(nbv->GetSuggestionsOutputPort());
  json->SetFileName(jsonFile.c_str());
  MESHNBV_CHECK(json->Write() == 1, "JSON: " << watch.Algorithm->AllErrors());
  const nlohmann::json doc = nlohmann::json::parse(meshnbv::io::read_file(jsonFile));
  MESHNBV_CHECK(doc.at("format") == "meshnbv-suggestions" && doc.at("suggestions").size() == 2, "JSON shape");
  MESHNBV_CHECK(doc.at("scene").get<std::string>() == args.ProjectFile(), "JSON scene " << doc.at("scene"));
  for (vtkIdType row = 0; row < 2; ++row)
  {
    const auto& s = doc.at("suggestions").at(static_cast<std::size_t>(row));
    MESHNBV_CHECK(s.at("label") == "nbv_" + std::to_string(row + 1), "JSON label");
    MESHNBV_CHECK(std::abs(s.at("energy").at("total").get<double>() - energy(row)) <= 1e-9, "JSON energy");
    for (int c = 0; c < 3; ++c)
    {
      MESHNBV_CHECK(std::abs(s.at("centre").at(static_cast<std::size_t>(c)).get<double>() - centre(row, c)) <= 1e-9,
        "JSON centre");
    }
  }
  // The file exists now: kept without Overwrite, replaced with it.
  MESHNBV_CHECK(json->Write() == 0 && watch.Algorithm->HasError("exists"),
    "no overwrite: " << watch.Algorithm->AllErrors());
  watch.Algorithm->Clear();
  json->OverwriteOn();
  MESHNBV_CHECK(json->Write() == 1 && watch.Algorithm->Errors.empty(), "overwrite: " << watch.Algorithm->AllErrors());

  // MeshLab project.
  const std::string mlpFile = args.Scratch + "/with_suggestions.mlp";
  vtkNew<vtkMeshNBVSuggestionWriter> mlp;
  vtkMeshNBVTest::Watch watchMlp(mlp);
  mlp->SetInputConnection(nbv->GetSuggestionsOutputPort());
  mlp->SetViewsConnection(reader->GetViewsOutputPort());
  mlp->SetMeshConnection(pri->GetOutputPort());
  mlp->SetFileName(mlpFile.c_str());
  MESHNBV_CHECK(mlp->Write() == 1, "mlp: " << watchMlp.Algorithm->AllErrors());
  const meshnbv::Scene back = meshnbv::io::read_scene(mlpFile);
  MESHNBV_CHECK(back.views.size() == 10, back.views.size() << " views in the written project");
  MESHNBV_CHECK(back.mesh.num_faces() == static_cast<std::size_t>(pri->GetOutput()->GetNumberOfCells()),
    "mesh of the written project");
  const double scale = back.mesh.bounding_box().diagonal();
  for (vtkIdType row = 0; row < 2; ++row)
  {
    const meshnbv::View& v = back.views[static_cast<std::size_t>(8 + row)];
    MESHNBV_CHECK(v.label == "nbv_" + std::to_string(row + 1) && !v.has_image(), "raster " << v.label);
    const meshnbv::Vec3 c = v.camera.center();
    for (int k = 0; k < 3; ++k)
    {
      MESHNBV_CHECK(std::abs(c[k] - centre(row, k)) <= 1e-6 * scale,
        v.label << " centre " << c.transpose() << " vs the table's");
    }
  }

  // Errors: a wrong extension; .mlp without views.
  vtkNew<vtkMeshNBVSuggestionWriter> bad;
  vtkMeshNBVTest::Watch watchBad(bad);
  bad->SetInputConnection(nbv->GetSuggestionsOutputPort());
  bad->SetFileName((args.Scratch + "/suggestions.txt").c_str());
  MESHNBV_CHECK(bad->Write() == 0 && watchBad.Algorithm->HasError(".json or .mlp"), watchBad.Algorithm->AllErrors());
  watchBad.Algorithm->Clear();
  bad->SetFileName((args.Scratch + "/no_views.mlp").c_str());
  MESHNBV_CHECK(bad->Write() == 0 && watchBad.Algorithm->HasError("needs the views"), watchBad.Algorithm->AllErrors());
  std::cout << "JSON and .mlp written; " << back.views.size()
            << " views read back, suggestion centres within 1e-6\n";
  return EXIT_SUCCESS;
}
