#include "meshnbv_paraview_settings.h"

#include "vtkSMSettings.h"
#include "vtkSMTransferFunctionPresets.h"

void meshnbv_paraview_settings()
{
  // The preset: hue 120 -> 0 at full saturation (meshnbv::pri_colors) is
  // linear in RGB between green, yellow and red; grey (160/255) for NaN.
  static const char* const name = "MeshNBV PRI";
  static const char* const preset = R"({
    "Name": "MeshNBV PRI",
    "ColorSpace": "RGB",
    "RGBPoints": [0.0, 0.0, 1.0, 0.0,  0.5, 1.0, 1.0, 0.0,  1.0, 1.0, 0.0, 0.0],
    "NanColor": [0.627451, 0.627451, 0.627451]
  })";
  vtkSMTransferFunctionPresets* presets = vtkSMTransferFunctionPresets::GetInstance();
  int index = -1;
  presets->GetFirstPresetWithName(name, index);
  if (index < 0)
  {
    presets->AddPreset(name, preset);
  }
  // ParaView applies ".standard_presets.<array>" when it makes the colour
  // map of an array (vtkSMTransferFunctionManager). The lowest priority: a
  // user's own choice for "PRI" wins.
  vtkSMSettings::GetInstance()->AddCollectionFromString(
    R"({"standard_presets": {"PRI": "MeshNBV PRI"}})", 0.0);
}
