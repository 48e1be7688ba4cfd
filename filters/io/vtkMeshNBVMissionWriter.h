/**
 * @class   vtkMeshNBVMissionWriter
 * @brief   writes drone missions that take the suggested photos
 *
 * vtkMeshNBVMissionWriter does what `meshnbv mission` does, through the
 * MeshNBV core (meshnbv::mission, docs/missions.md): it georeferences the
 * scene, checks every suggestion against the altitude, keep-out,
 * mesh-distance, gimbal, GSD and battery constraints (moving and re-scoring
 * or dropping those that break one), orders them into flights from the
 * take-off point, and writes into OutputDirectory mission.kml, mission.kmz
 * (DJI WPML), litchi.csv (litchi_<k>.csv per flight when split),
 * mission.geojson, waypoints.csv, mission.json and mission.svg.
 *
 * Input 0: the suggestions table (output port 1 of
 * vtkMeshNBVNextBestViewFilter; its field data "SuggestionsJSON"). Input 1:
 * the views (vtkMeshNBVSceneReader's views: their image files for EXIF GPS,
 * the scene's CRS when the source states one). Input 2: the mesh.
 *
 * The properties are the command's flags: Georeference (--georef: a JSON
 * file, "ecef" or "enu:LAT,LON,H"; empty: the scene's CRS, else EXIF GPS),
 * Takeoff ("x,y,z") or TakeoffWGS84 ("lat,lon[,h]"), KeepOutFile
 * (--keep-out), AddKeepOutBox (--keep-out-box), and the mission options
 * under their VTK names (MinAltitude, ..., Infeasible: 0 = MOVE, 1 = DROP)
 * with the core's defaults and ranges. Nothing is written when anything
 * fails; existing files are kept unless Overwrite is on. Errors are
 * reported with vtkErrorMacro and the core's message, and Write() returns 0.
 *
 * @sa vtkMeshNBVNextBestViewFilter vtkMeshNBVSuggestionWriter vtkMeshNBVSceneReader
 */

#ifndef vtkMeshNBVMissionWriter_h
#define vtkMeshNBVMissionWriter_h

#include "vtkMeshNBVIOModule.h" // For export macro
#include "vtkWriter.h"

#include <array>  // For the keep-out boxes
#include <string> // For std::string members
#include <vector> // For the keep-out boxes

class VTKMESHNBVIO_EXPORT vtkMeshNBVMissionWriter : public vtkWriter
{
public:
  static vtkMeshNBVMissionWriter* New();
  vtkTypeMacro(vtkMeshNBVMissionWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The folder to write the mission files into. No default.
   */
  vtkSetStdStringFromCharMacro(OutputDirectory);
  vtkGetCharFromStdStringMacro(OutputDirectory);
  ///@}

  ///@{
  /**
   * The georeference (`--georef`): a JSON file {"crs", "transform"}, "ecef"
   * or "enu:LAT,LON,H". Empty (default): the scene's own CRS, else the
   * photos' EXIF GPS.
   */
  vtkSetStdStringFromCharMacro(Georeference);
  vtkGetCharFromStdStringMacro(Georeference);
  ///@}

  ///@{
  /**
   * The take-off point: "x,y,z" in scene coordinates (`--takeoff`), or
   * "lat,lon[,h]" (`--takeoff-wgs84`). Both empty (default): the ground
   * below the first photo.
   */
  vtkSetStdStringFromCharMacro(Takeoff);
  vtkGetCharFromStdStringMacro(Takeoff);
  vtkSetStdStringFromCharMacro(TakeoffWGS84);
  vtkGetCharFromStdStringMacro(TakeoffWGS84);
  ///@}

  ///@{
  /**
   * Keep-out polygons: a GeoJSON file (`--keep-out`); and boxes in scene
   * coordinates (`--keep-out-box`).
   */
  vtkSetStdStringFromCharMacro(KeepOutFile);
  vtkGetCharFromStdStringMacro(KeepOutFile);
  void AddKeepOutBox(double xmin, double ymin, double zmin, double xmax, double ymax, double zmax);
  void RemoveAllKeepOutBoxes();
  int GetNumberOfKeepOutBoxes() const { return static_cast<int>(this->KeepOutBoxes.size()); }
  ///@}

  ///@{
  /**
   * The mission options (meshnbv::mission_option_table(); names, defaults
   * and ranges as there). Out-of-range values are an error naming the
   * option when writing.
   */
  vtkSetMacro(MinAltitude, double);
  vtkGetMacro(MinAltitude, double);
  vtkSetMacro(MaxAltitude, double);
  vtkGetMacro(MaxAltitude, double);
  vtkSetMacro(MinMeshDistance, double);
  vtkGetMacro(MinMeshDistance, double);
  vtkSetMacro(GimbalPitchMin, double);
  vtkGetMacro(GimbalPitchMin, double);
  vtkSetMacro(GimbalPitchMax, double);
  vtkGetMacro(GimbalPitchMax, double);
  vtkSetMacro(TargetGsd, double);
  vtkGetMacro(TargetGsd, double);
  vtkSetMacro(MaxWaypoints, int);
  vtkGetMacro(MaxWaypoints, int);
  vtkSetMacro(Speed, double);
  vtkGetMacro(Speed, double);
  vtkSetMacro(TimePerPhoto, double);
  vtkGetMacro(TimePerPhoto, double);
  vtkSetMacro(BatteryMinutes, double);
  vtkGetMacro(BatteryMinutes, double);
  enum InfeasibleChoice
  {
    MOVE = 0,
    DROP = 1
  };
  vtkSetMacro(Infeasible, int);
  vtkGetMacro(Infeasible, int);
  ///@}

  ///@{
  /**
   * Replace existing files (`overwrite`, default off).
   */
  vtkSetMacro(Overwrite, vtkTypeBool);
  vtkGetMacro(Overwrite, vtkTypeBool);
  vtkBooleanMacro(Overwrite, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Connect the views (input port 1) and the mesh (input port 2).
   */
  void SetViewsConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetViewsData(vtkDataObject* views) { this->SetInputData(1, views); }
  void SetMeshConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(2, output); }
  void SetMeshData(vtkDataObject* mesh) { this->SetInputData(2, mesh); }
  ///@}

  ///@{
  /**
   * What the last successful Write() planned: photos flown, flights, total
   * minutes, and the georeference's source; the notes (moved, dropped,
   * detour, with the reason), one per line.
   */
  vtkGetMacro(NumberOfPhotos, int);
  vtkGetMacro(NumberOfFlights, int);
  vtkGetMacro(TotalMinutes, double);
  vtkGetCharFromStdStringMacro(GeoreferenceSource);
  vtkGetCharFromStdStringMacro(Notes);
  ///@}

protected:
  vtkMeshNBVMissionWriter();
  ~vtkMeshNBVMissionWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  std::string OutputDirectory;
  std::string Georeference;
  std::string Takeoff;
  std::string TakeoffWGS84;
  std::string KeepOutFile;
  std::vector<std::array<double, 6>> KeepOutBoxes;
  double MinAltitude;
  double MaxAltitude;
  double MinMeshDistance;
  double GimbalPitchMin;
  double GimbalPitchMax;
  double TargetGsd;
  int MaxWaypoints;
  double Speed;
  double TimePerPhoto;
  double BatteryMinutes;
  int Infeasible;
  vtkTypeBool Overwrite;

  int NumberOfPhotos = 0;
  int NumberOfFlights = 0;
  double TotalMinutes = 0.0;
  std::string GeoreferenceSource;
  std::string Notes;

private:
  vtkMeshNBVMissionWriter(const vtkMeshNBVMissionWriter&) = delete;
  void operator=(const vtkMeshNBVMissionWriter&) = delete;
};

#endif
