#include "vtkMeshNBVSuggestionWriter.h"

#include "vtkDataArray.h"
#include "vtkDataObjectTree.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include "vtkMeshNBVConversion.h"

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/suggestions_io.h"

#include <ostream>

vtkStandardNewMacro(vtkMeshNBVSuggestionWriter);

namespace
{

std::string FieldString(vtkDataObject* object, const char* name)
{
  auto* a = object ? vtkStringArray::SafeDownCast(object->GetFieldData()->GetAbstractArray(name))
                   : nullptr;
  return a && a->GetNumberOfValues() > 0 ? a->GetValue(0) : std::string();
}

vtkDataArray* Column(vtkTable* table, const char* name, int components)
{
  auto* a = vtkDataArray::SafeDownCast(table->GetColumnByName(name));
  if (!a || a->GetNumberOfComponents() != components)
  {
    throw meshnbv::Error(std::string("the suggestions table has no column '") + name + "' with " +
      std::to_string(components) + " component(s) (use output port 1 of "
                                   "vtkMeshNBVNextBestViewFilter)");
  }
  return a;
}

// The suggestions' labels and cameras, back from the table's rows.
meshnbv::SuggestResult SuggestionsOf(vtkTable* table)
{
  auto* label = vtkStringArray::SafeDownCast(table->GetColumnByName("label"));
  if (!label)
  {
    throw meshnbv::Error("the suggestions table has no column 'label'");
  }
  vtkDataArray* rank = Column(table, "rank", 1);
  vtkDataArray* width = Column(table, "width", 1);
  vtkDataArray* height = Column(table, "height", 1);
  vtkDataArray* fx = Column(table, "fx", 1);
  vtkDataArray* fy = Column(table, "fy", 1);
  vtkDataArray* cx = Column(table, "cx", 1);
  vtkDataArray* cy = Column(table, "cy", 1);
  vtkDataArray* r = Column(table, "R", 9);
  vtkDataArray* t = Column(table, "t", 3);
  meshnbv::SuggestResult result;
  for (vtkIdType row = 0; row < table->GetNumberOfRows(); ++row)
  {
    meshnbv::Suggestion s;
    s.rank = static_cast<int>(rank->GetComponent(row, 0));
    s.label = label->GetValue(row);
    meshnbv::PinholeCamera& c = s.camera;
    c.width = static_cast<int>(width->GetComponent(row, 0));
    c.height = static_cast<int>(height->GetComponent(row, 0));
    c.fx = fx->GetComponent(row, 0);
    c.fy = fy->GetComponent(row, 0);
    c.cx = cx->GetComponent(row, 0);
    c.cy = cy->GetComponent(row, 0);
    for (int i = 0; i < 9; ++i)
    {
      c.R(i / 3, i % 3) = r->GetComponent(row, i);
    }
    for (int i = 0; i < 3; ++i)
    {
      c.t[i] = t->GetComponent(row, i);
    }
    c.check("suggestion '" + s.label + "'");
    result.suggestions.push_back(s);
  }
  return result;
}

} // namespace

//------------------------------------------------------------------------------
vtkMeshNBVSuggestionWriter::vtkMeshNBVSuggestionWriter()
  : Overwrite(0)
{
  this->SetNumberOfInputPorts(3);
}

//------------------------------------------------------------------------------
vtkMeshNBVSuggestionWriter::~vtkMeshNBVSuggestionWriter() = default;

//------------------------------------------------------------------------------
int vtkMeshNBVSuggestionWriter::FillInputPortInformation(int port, vtkInformation* info)
{
  switch (port)
  {
    case 0:
      info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkTable");
      return 1;
    case 1:
      info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObjectTree");
      info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
      return 1;
    case 2:
      info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
      info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
      return 1;
    default:
      return 0;
  }
}

//------------------------------------------------------------------------------
void vtkMeshNBVSuggestionWriter::WriteData()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  try
  {
    auto* table = vtkTable::SafeDownCast(this->GetInput(0));
    if (!table)
    {
      throw meshnbv::Error("no suggestions table on input port 0");
    }
    if (this->FileName.empty())
    {
      throw meshnbv::Error("no FileName: set a .json or .mlp file to write");
    }
    const std::string extension = meshnbv::io::extension_lower(this->FileName);
    if (extension == ".json")
    {
      const std::string json = FieldString(table, vtkMeshNBV::SuggestionsJSONName);
      if (json.empty())
      {
        throw meshnbv::Error("the table carries no SuggestionsJSON field (use output port 1 of "
                             "vtkMeshNBVNextBestViewFilter)");
      }
      meshnbv::io::write_atomically(
        this->FileName, [&](std::ostream& out) { out << json; }, this->Overwrite != 0);
    }
    else if (extension == ".mlp")
    {
      vtkDataObject* views = this->GetNumberOfInputConnections(1) ? this->GetInput(1) : nullptr;
      if (!views)
      {
        throw meshnbv::Error("writing .mlp needs the views: connect them to input port 1");
      }
      auto* mesh = vtkPolyData::SafeDownCast(
        this->GetNumberOfInputConnections(2) ? this->GetInput(2) : nullptr);
      meshnbv::Scene scene;
      for (const vtkMeshNBV::ViewBlock& block : vtkMeshNBV::ExtractViews(views))
      {
        // A project references image files: a view whose image exists only
        // as pipeline pixels cannot be written (without its image it would
        // read back as a candidate view).
        if (block.hasPixels && block.view.image_path.empty())
        {
          throw meshnbv::Error("view '" + block.view.label +
            "' has pixels but no ImagePath: a .mlp project can only reference image files "
            "(write the image, e.g. with vtkPNGWriter, and set the block's ImagePath field)");
        }
        scene.views.push_back(block.view);
      }
      if (mesh)
      {
        scene.mesh = vtkMeshNBV::ToTriangleMesh(mesh);
        scene.mesh_path = FieldString(mesh, vtkMeshNBV::MeshFileName);
      }
      else
      {
        throw meshnbv::Error("writing .mlp needs the mesh: connect it to input port 2");
      }
      meshnbv::io::write_suggestions_mlp(
        scene, SuggestionsOf(table), this->FileName, this->Overwrite != 0);
    }
    else
    {
      throw meshnbv::Error("FileName must end in .json or .mlp, got '" + this->FileName + "'");
    }
  }
  catch (const std::exception& e)
  {
    this->SetErrorCode(vtkErrorCode::UnknownError);
    vtkErrorMacro(<< e.what());
  }
}

//------------------------------------------------------------------------------
void vtkMeshNBVSuggestionWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Overwrite: " << this->Overwrite << "\n";
}
