#include "vtkMeshNBVMissionWriter.h"

#include "vtkDataObjectTree.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include "vtkMeshNBVConversion.h"

#include "meshnbv/error.h"
#include "meshnbv/mission/scene_mission.h"
#include "meshnbv/mission_options.h"
#include "meshnbv/options.h"

#include <ostream>
#include <sstream>

vtkStandardNewMacro(vtkMeshNBVMissionWriter);

namespace
{

std::string FieldString(vtkDataObject* object, const char* name)
{
  auto* a = object ? vtkStringArray::SafeDownCast(object->GetFieldData()->GetAbstractArray(name))
                   : nullptr;
  return a && a->GetNumberOfValues() > 0 ? a->GetValue(0) : std::string();
}

// The properties as the core's options, unchecked (PrintSelf shows what is
// set, in range or not).
meshnbv::MissionOptions RawOptionsOf(vtkMeshNBVMissionWriter* w)
{
  meshnbv::MissionOptions o;
  o.min_altitude = w->GetMinAltitude();
  o.max_altitude = w->GetMaxAltitude();
  o.min_mesh_distance = w->GetMinMeshDistance();
  o.gimbal_pitch_min = w->GetGimbalPitchMin();
  o.gimbal_pitch_max = w->GetGimbalPitchMax();
  o.target_gsd = w->GetTargetGsd();
  o.max_waypoints = w->GetMaxWaypoints();
  o.speed = w->GetSpeed();
  o.time_per_photo = w->GetTimePerPhoto();
  o.battery_minutes = w->GetBatteryMinutes();
  if (w->GetInfeasible() == vtkMeshNBVMissionWriter::DROP)
  {
    o.infeasible = "drop";
  }
  return o;
}

} // namespace

//------------------------------------------------------------------------------
vtkMeshNBVMissionWriter::vtkMeshNBVMissionWriter()
  : Overwrite(0)
{
  // The defaults are the core's option table's (options.h), so that every
  // front end agrees.
  const meshnbv::MissionOptions d;
  this->MinAltitude = d.min_altitude;
  this->MaxAltitude = d.max_altitude;
  this->MinMeshDistance = d.min_mesh_distance;
  this->GimbalPitchMin = d.gimbal_pitch_min;
  this->GimbalPitchMax = d.gimbal_pitch_max;
  this->TargetGsd = d.target_gsd;
  this->MaxWaypoints = d.max_waypoints;
  this->Speed = d.speed;
  this->TimePerPhoto = d.time_per_photo;
  this->BatteryMinutes = d.battery_minutes;
  this->Infeasible = d.infeasible == "drop" ? DROP : MOVE;
  this->SetNumberOfInputPorts(3);
}

//------------------------------------------------------------------------------
vtkMeshNBVMissionWriter::~vtkMeshNBVMissionWriter() = default;

//------------------------------------------------------------------------------
void vtkMeshNBVMissionWriter::AddKeepOutBox(
  double xmin, double ymin, double zmin, double xmax, double ymax, double zmax)
{
  this->KeepOutBoxes.push_back({ xmin, ymin, zmin, xmax, ymax, zmax });
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkMeshNBVMissionWriter::RemoveAllKeepOutBoxes()
{
  if (!this->KeepOutBoxes.empty())
  {
    this->KeepOutBoxes.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkMeshNBVMissionWriter::FillInputPortInformation(int port, vtkInformation* info)
{
  switch (port)
  {
    case 0:
      info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkTable");
      return 1;
    case 1:
      info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObjectTree");
      return 1;
    case 2:
      info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
      return 1;
    default:
      return 0;
  }
}

//------------------------------------------------------------------------------
void vtkMeshNBVMissionWriter::WriteData()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  this->NumberOfPhotos = this->NumberOfFlights = 0;
  this->TotalMinutes = 0.0;
  this->GeoreferenceSource.clear();
  this->Notes.clear();
  try
  {
    if (this->Infeasible != MOVE && this->Infeasible != DROP)
    {
      throw meshnbv::Error(
        "Infeasible must be 0 (MOVE) or 1 (DROP), got " + std::to_string(this->Infeasible));
    }
    meshnbv::mission::MissionRequest request;
    request.options = RawOptionsOf(this);
    request.options.check();
    auto* table = vtkTable::SafeDownCast(this->GetInput(0));
    if (!table)
    {
      throw meshnbv::Error("no suggestions table on input port 0");
    }
    if (this->OutputDirectory.empty())
    {
      throw meshnbv::Error("no OutputDirectory: set the folder to write the mission into");
    }
    meshnbv::mission::check_mission_outputs(this->OutputDirectory, this->Overwrite != 0);
    const std::string json = FieldString(table, vtkMeshNBV::SuggestionsJSONName);
    if (json.empty())
    {
      throw meshnbv::Error("the table carries no SuggestionsJSON field (use output port 1 of "
                           "vtkMeshNBVNextBestViewFilter)");
    }
    vtkDataObject* views = this->GetNumberOfInputConnections(1) ? this->GetInput(1) : nullptr;
    auto* mesh =
      vtkPolyData::SafeDownCast(this->GetNumberOfInputConnections(2) ? this->GetInput(2) : nullptr);
    if (!views)
    {
      throw meshnbv::Error("a mission needs the views: connect them to input port 1");
    }
    if (!mesh)
    {
      throw meshnbv::Error("a mission needs the mesh: connect it to input port 2");
    }
    meshnbv::Scene scene;
    for (const vtkMeshNBV::ViewBlock& block : vtkMeshNBV::ExtractViews(views))
    {
      scene.views.push_back(vtkMeshNBV::ToViewWithPixels(block));
    }
    scene.crs = FieldString(views, vtkMeshNBV::SceneCRSName);
    if (auto* g = vtkIntArray::SafeDownCast(
          views->GetFieldData()->GetAbstractArray(vtkMeshNBV::SceneCRSGeocentricName)))
    {
      scene.crs_geocentric = g->GetNumberOfValues() > 0 && g->GetValue(0) != 0;
    }
    scene.source = FieldString(views, vtkMeshNBV::SceneFileName);
    scene.mesh = vtkMeshNBV::ToTriangleMesh(mesh);
    request.georef = this->Georeference;
    meshnbv::mission::set_takeoff(this->Takeoff, this->TakeoffWGS84, &request);
    if (!this->KeepOutFile.empty())
    {
      request.keep_outs = meshnbv::mission::read_keep_out_geojson(this->KeepOutFile);
    }
    for (std::size_t i = 0; i < this->KeepOutBoxes.size(); ++i)
    {
      const auto& b = this->KeepOutBoxes[i];
      std::ostringstream text;
      text.precision(17);
      text << b[0] << "," << b[1] << "," << b[2] << "," << b[3] << "," << b[4] << "," << b[5];
      request.keep_outs.boxes.push_back(meshnbv::mission::parse_keep_out_box(text.str()));
    }
    const meshnbv::mission::SceneMission m = meshnbv::mission::plan_scene_mission(
      scene, meshnbv::mission::parse_suggestions_json(json, "SuggestionsJSON"), request);
    meshnbv::mission::write_mission_files(m, this->OutputDirectory, this->Overwrite != 0);
    this->NumberOfPhotos = static_cast<int>(m.plan.waypoints.size());
    this->NumberOfFlights = static_cast<int>(m.plan.flights.size());
    this->TotalMinutes = m.plan.total_minutes();
    this->GeoreferenceSource = m.frame->georef().source;
    for (const meshnbv::mission::Note& n : m.plan.notes)
    {
      this->Notes += n.label + ": " + n.action + " (" + n.reason + ")\n";
    }
  }
  catch (const std::exception& e)
  {
    this->SetErrorCode(vtkErrorCode::UnknownError);
    vtkErrorMacro(<< e.what());
  }
}

//------------------------------------------------------------------------------
void vtkMeshNBVMissionWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OutputDirectory: " << this->OutputDirectory << "\n";
  os << indent << "Georeference: " << this->Georeference << "\n";
  os << indent << "Takeoff: " << this->Takeoff << "\n";
  os << indent << "TakeoffWGS84: " << this->TakeoffWGS84 << "\n";
  os << indent << "KeepOutFile: " << this->KeepOutFile << "\n";
  os << indent << "KeepOutBoxes: " << this->KeepOutBoxes.size() << "\n";
  // Every option of the core's table, under its VTK name (options.h).
  const meshnbv::MissionOptions options = RawOptionsOf(this);
  for (const auto& spec : meshnbv::mission_option_table())
  {
    os << indent << meshnbv::vtk_name(spec.name) << ": "
       << meshnbv::option_value_text(spec.get(options)) << "\n";
  }
  os << indent << "Overwrite: " << this->Overwrite << "\n";
}
