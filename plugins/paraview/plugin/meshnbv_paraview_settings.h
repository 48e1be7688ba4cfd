// Called by ParaView when the MeshNBV plugin loads: the colour map of the
// PRI array (green, best, through yellow to red, worst; grey where no two
// views see a face), as in the report's pictures and the PLY's colours: a
// preset "MeshNBV PRI", the default of every array named PRI.
#pragma once

void meshnbv_paraview_settings();
