#include "vtkMeshNBVSceneReader.h"

#include "vtkCompositeDataSet.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include "vtkMeshNBVConversion.h"

#include "meshnbv/error.h"
#include "meshnbv/io/scene_io.h"

#include <filesystem>

vtkStandardNewMacro(vtkMeshNBVSceneReader);

//------------------------------------------------------------------------------
vtkMeshNBVSceneReader::vtkMeshNBVSceneReader()
  : Format("auto")
  , LoadImages(1)
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(2);
}

//------------------------------------------------------------------------------
vtkMeshNBVSceneReader::~vtkMeshNBVSceneReader() = default;

//------------------------------------------------------------------------------
vtkMultiBlockDataSet* vtkMeshNBVSceneReader::GetViewsOutput()
{
  return vtkMultiBlockDataSet::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
int vtkMeshNBVSceneReader::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkMultiBlockDataSet");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

//------------------------------------------------------------------------------
int vtkMeshNBVSceneReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* mesh = vtkPolyData::GetData(outputVector, 0);
  vtkMultiBlockDataSet* views = vtkMultiBlockDataSet::GetData(outputVector, 1);
  try
  {
    if (this->FileName.empty())
    {
      throw meshnbv::Error("no FileName: set the scene to read");
    }
    meshnbv::io::SceneReadOptions options;
    options.format = meshnbv::io::parse_scene_format(this->Format.empty() ? "auto" : this->Format);
    options.mesh_path = this->Mesh;
    options.image_dir = this->ImageDir;
    meshnbv::Scene scene = meshnbv::io::read_scene(this->FileName, options);
    for (const std::string& warning : scene.warnings)
    {
      vtkWarningMacro(<< warning);
    }

    vtkSmartPointer<vtkPolyData> polydata = vtkMeshNBV::ToPolyData(scene.mesh);
    vtkNew<vtkStringArray> meshFile;
    meshFile->SetName(vtkMeshNBV::MeshFileName);
    meshFile->InsertNextValue(scene.mesh_path);
    polydata->GetFieldData()->AddArray(meshFile);

    vtkNew<vtkMultiBlockDataSet> blocks;
    blocks->SetNumberOfBlocks(static_cast<unsigned int>(scene.views.size()));
    for (std::size_t i = 0; i < scene.views.size(); ++i)
    {
      meshnbv::View view = scene.views[i];
      if (view.has_image())
      {
        std::error_code ec;
        const auto absolute = std::filesystem::absolute(view.image_path, ec);
        if (!ec)
        {
          view.image_path = absolute.lexically_normal().string();
        }
      }
      std::shared_ptr<const meshnbv::Image> pixels;
      if (this->LoadImages && view.has_image())
      {
        pixels = scene.image(i);
      }
      const auto index = static_cast<unsigned int>(i);
      blocks->SetBlock(index, vtkMeshNBV::ToViewBlock(view, pixels.get()));
      blocks->GetMetaData(index)->Set(vtkCompositeDataSet::NAME(), view.label.c_str());
      this->UpdateProgress(double(i + 1) / double(scene.views.size()));
    }
    vtkNew<vtkStringArray> source;
    source->SetName(vtkMeshNBV::SceneFileName);
    source->InsertNextValue(scene.source);
    blocks->GetFieldData()->AddArray(source);
    vtkNew<vtkStringArray> format;
    format->SetName(vtkMeshNBV::SceneFormatName);
    format->InsertNextValue(scene.format);
    blocks->GetFieldData()->AddArray(format);
    if (!scene.crs.empty())
    {
      vtkNew<vtkStringArray> crs;
      crs->SetName(vtkMeshNBV::SceneCRSName);
      crs->InsertNextValue(scene.crs);
      blocks->GetFieldData()->AddArray(crs);
      vtkNew<vtkIntArray> geocentric;
      geocentric->SetName(vtkMeshNBV::SceneCRSGeocentricName);
      geocentric->InsertNextValue(scene.crs_geocentric ? 1 : 0);
      blocks->GetFieldData()->AddArray(geocentric);
    }

    mesh->ShallowCopy(polydata);
    views->ShallowCopy(blocks);
  }
  catch (const std::exception& e)
  {
    mesh->Initialize();
    views->Initialize();
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkMeshNBVSceneReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Format: " << this->Format << "\n";
  os << indent << "Mesh: " << this->Mesh << "\n";
  os << indent << "ImageDir: " << this->ImageDir << "\n";
  os << indent << "LoadImages: " << this->LoadImages << "\n";
}
