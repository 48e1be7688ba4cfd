// Shared by the MeshNBV VTK modules (Filters, IO; not wrapped): moves data between VTK objects and the
// core's types (docs/vtk.md describes the layouts). No algorithm lives here;
// every function either converts or throws meshnbv::Error with a message
// naming the block or cell at fault.
#ifndef vtkMeshNBVConversion_h
#define vtkMeshNBVConversion_h

#include "vtkMeshNBVFiltersModule.h" // For export macro
#include "vtkSmartPointer.h"

#include "meshnbv/image.h"
#include "meshnbv/mesh.h"
#include "meshnbv/scene.h"

#include <string>
#include <vector>

class vtkDataObject;
class vtkImageData;
class vtkPolyData;

namespace vtkMeshNBV
{

// Field-data names of a view block (vtkImageData) of a views input/output.
constexpr const char* LabelName = "Label";          // vtkStringArray, 1 value
constexpr const char* ImageSizeName = "ImageSize";  // vtkIntArray, 2 components (W, H)
constexpr const char* KName = "K";                  // vtkDoubleArray, 9 components, row-major
constexpr const char* RName = "R";                  // vtkDoubleArray, 9 components, row-major
constexpr const char* TName = "t";                  // vtkDoubleArray, 3 components
constexpr const char* DistortionName = "Distortion";  // vtkDoubleArray, 2 components (k1, k2)
// vtkDoubleArray, 9 components (model 0 = Brown-Conrady / 1 = fisheye, k1..k6, p1, p2);
// written only for a lens beyond (k1, k2), and then it wins over Distortion.
constexpr const char* LensName = "Lens";
constexpr const char* UsedName = "Used";            // vtkIntArray, 1 value (0 / 1)
constexpr const char* ImagePathName = "ImagePath";  // vtkStringArray, 1 value ("" = none)
constexpr const char* PixelsName = "Pixels";        // point scalars, unsigned char or short, 1 to 4 components
// Field data of the mesh output: where the mesh came from.
constexpr const char* MeshFileName = "MeshFileName";
// Field data of the views output: the scene file and its format.
constexpr const char* SceneFileName = "FileName";
constexpr const char* SceneFormatName = "Format";
// ... and, when the source places the scene on Earth (Scene::crs), its CRS
// (vtkStringArray) and whether the coordinates are that CRS's geocentric
// frame (vtkIntArray, 0 / 1).
constexpr const char* SceneCRSName = "CRS";
constexpr const char* SceneCRSGeocentricName = "CRSGeocentric";
// Field data of the suggestions table: the core's JSON document.
constexpr const char* SuggestionsJSONName = "SuggestionsJSON";

// vtkPolyData made only of triangles (polys) -> core mesh; cell i = face i.
// Throws for vertices, lines, strips or polygons that are not triangles.
VTKMESHNBVFILTERS_EXPORT meshnbv::TriangleMesh ToTriangleMesh(vtkPolyData* polydata);
// Core mesh -> vtkPolyData: per-face attributes become float cell arrays of
// the same name, face colours an "RGB" unsigned char cell array.
VTKMESHNBVFILTERS_EXPORT vtkSmartPointer<vtkPolyData> ToPolyData(const meshnbv::TriangleMesh& mesh);

// A view block; `pixels` (may be null) become the "Pixels" point scalars,
// rows flipped so that the block looks upright (vtkPNGReader's layout).
VTKMESHNBVFILTERS_EXPORT vtkSmartPointer<vtkImageData> ToViewBlock(const meshnbv::View& view, const meshnbv::Image* pixels);

struct ViewBlock
{
  meshnbv::View view;             // camera, label, used; image_path = the block's ImagePath
  vtkImageData* block = nullptr;  // the leaf it came from
  bool hasPixels = false;         // the block carries pixels (point scalars or "Pixels")
};
// Every leaf of a views input (a vtkMultiBlockDataSet of vtkImageData, possibly
// nested), in order. Throws when a leaf is not an image or lacks ImageSize, K,
// R, t, or when its pixels are of a type ToImage does not convert.
VTKMESHNBVFILTERS_EXPORT std::vector<ViewBlock> ExtractViews(vtkDataObject* views);
// The pixels of a block as a core image, rows flipped back to top-down:
// 1 or 2 components give grey, 3 or 4 RGB (alpha dropped, as the core's
// loader drops it); unsigned short is scaled to 8 bits as the core scales
// 16-bit files (round(v / 257)). Other scalar types are refused by
// ExtractViews with the conversion to make.
VTKMESHNBVFILTERS_EXPORT meshnbv::Image ToImage(const ViewBlock& view);
// The block's view for the core with its pixels in memory (View::pixels:
// converted once by ToImage, shared, no file; image_path cleared, since the
// pipeline's pixels are what the core is to see). Throws when the pixels'
// size differs from the camera's. A block without pixels is returned as is.
VTKMESHNBVFILTERS_EXPORT meshnbv::View ToViewWithPixels(const ViewBlock& block);

} // namespace vtkMeshNBV

#endif
// VTK-HeaderTest-Exclude: vtkMeshNBVConversion.h
