#include "vtkMeshNBVConversion.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataObjectTree.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include "meshnbv/error.h"

#include <algorithm>
#include <cstring>
#include <memory>

namespace vtkMeshNBV
{
namespace
{

using meshnbv::Error;

void AddString(vtkFieldData* fd, const char* name, const std::string& value)
{
  vtkNew<vtkStringArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

void AddDoubles(vtkFieldData* fd, const char* name, const double* values, int n)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(n);
  a->InsertNextTuple(values);
  fd->AddArray(a);
}

void AddInts(vtkFieldData* fd, const char* name, const int* values, int n)
{
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(n);
  a->SetNumberOfTuples(1);
  for (int i = 0; i < n; ++i)
  {
    a->SetTypedComponent(0, i, values[i]);
  }
  fd->AddArray(a);
}

// The first tuple of a numeric field array with `n` components, or false.
bool GetTuple(vtkFieldData* fd, const char* name, int n, double* out)
{
  vtkDataArray* a = fd ? fd->GetArray(name) : nullptr;
  if (!a || a->GetNumberOfComponents() != n || a->GetNumberOfTuples() < 1)
  {
    return false;
  }
  a->GetTuple(0, out);
  return true;
}

std::string GetString(vtkFieldData* fd, const char* name)
{
  auto* a = fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray(name)) : nullptr;
  return a && a->GetNumberOfValues() > 0 ? a->GetValue(0) : std::string();
}

// The pixel array of a block: its point scalars, else an array "Pixels".
vtkDataArray* PixelArray(vtkImageData* image)
{
  vtkDataArray* a = image->GetPointData()->GetScalars();
  if (!a)
  {
    a = image->GetPointData()->GetArray(PixelsName);
  }
  return a && a->GetNumberOfTuples() > 0 ? a : nullptr;
}

} // namespace

meshnbv::TriangleMesh ToTriangleMesh(vtkPolyData* polydata)
{
  if (!polydata)
  {
    throw Error("no mesh input");
  }
  if (polydata->GetNumberOfVerts() || polydata->GetNumberOfLines() || polydata->GetNumberOfStrips())
  {
    throw Error("the mesh must consist of triangles only; it has " +
      std::to_string(polydata->GetNumberOfVerts()) + " vertex cells, " +
      std::to_string(polydata->GetNumberOfLines()) + " lines and " +
      std::to_string(polydata->GetNumberOfStrips()) + " strips (run vtkTriangleFilter first)");
  }
  meshnbv::TriangleMesh mesh;
  const vtkIdType np = polydata->GetNumberOfPoints();
  mesh.vertices.resize(static_cast<std::size_t>(np));
  for (vtkIdType i = 0; i < np; ++i)
  {
    polydata->GetPoint(i, mesh.vertices[static_cast<std::size_t>(i)].data());
  }
  vtkCellArray* polys = polydata->GetPolys();
  if (!polys)
  {
    return mesh;
  }
  mesh.faces.reserve(static_cast<std::size_t>(polys->GetNumberOfCells()));
  auto it = vtk::TakeSmartPointer(polys->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    if (n != 3)
    {
      throw Error("cell " + std::to_string(it->GetCurrentCellId()) + " has " + std::to_string(n) +
        " points: the mesh must consist of triangles (run vtkTriangleFilter first)");
    }
    mesh.faces.push_back({ static_cast<int>(ids[0]), static_cast<int>(ids[1]), static_cast<int>(ids[2]) });
  }
  return mesh;
}

vtkSmartPointer<vtkPolyData> ToPolyData(const meshnbv::TriangleMesh& mesh)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(mesh.vertices.size()));
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
  {
    points->SetPoint(static_cast<vtkIdType>(i), mesh.vertices[i].data());
  }
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(static_cast<vtkIdType>(mesh.faces.size()), 3 * static_cast<vtkIdType>(mesh.faces.size()));
  for (const meshnbv::Face& f : mesh.faces)
  {
    const vtkIdType ids[3] = { f[0], f[1], f[2] };
    polys->InsertNextCell(3, ids);
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(points);
  out->SetPolys(polys);
  for (const auto& [name, values] : mesh.face_attributes)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName(name.c_str());
    a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
    std::copy(values.begin(), values.end(), a->GetPointer(0));
    out->GetCellData()->AddArray(a);
  }
  if (!mesh.face_colors.empty())
  {
    vtkNew<vtkUnsignedCharArray> rgb;
    rgb->SetName("RGB");
    rgb->SetNumberOfComponents(3);
    rgb->SetNumberOfTuples(static_cast<vtkIdType>(mesh.face_colors.size()));
    for (std::size_t i = 0; i < mesh.face_colors.size(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        rgb->SetTypedComponent(static_cast<vtkIdType>(i), c, mesh.face_colors[i][static_cast<std::size_t>(c)]);
      }
    }
    out->GetCellData()->AddArray(rgb);
  }
  return out;
}

vtkSmartPointer<vtkImageData> ToViewBlock(const meshnbv::View& view, const meshnbv::Image* pixels)
{
  const meshnbv::PinholeCamera& c = view.camera;
  auto block = vtkSmartPointer<vtkImageData>::New();
  block->SetDimensions(c.width, c.height, 1);
  vtkFieldData* fd = block->GetFieldData();
  AddString(fd, LabelName, view.label);
  const int size[2] = { c.width, c.height };
  AddInts(fd, ImageSizeName, size, 2);
  const double k[9] = { c.fx, c.skew, c.cx, 0, c.fy, c.cy, 0, 0, 1 };
  AddDoubles(fd, KName, k, 9);
  double r[9];
  for (int i = 0; i < 9; ++i)
  {
    r[i] = c.R(i / 3, i % 3);
  }
  AddDoubles(fd, RName, r, 9);
  AddDoubles(fd, TName, c.t.data(), 3);
  const double distortion[2] = { c.k1, c.k2 };
  AddDoubles(fd, DistortionName, distortion, 2);
  if (c.lens != meshnbv::LensModel::Brown || c.k3 != 0.0 || c.k4 != 0.0 || c.k5 != 0.0 ||
    c.k6 != 0.0 || c.p1 != 0.0 || c.p2 != 0.0)
  {
    const double lens[9] = { c.lens == meshnbv::LensModel::Fisheye ? 1.0 : 0.0, c.k1, c.k2, c.k3,
      c.k4, c.k5, c.k6, c.p1, c.p2 };
    AddDoubles(fd, LensName, lens, 9);
  }
  const int used = view.used ? 1 : 0;
  AddInts(fd, UsedName, &used, 1);
  AddString(fd, ImagePathName, view.image_path);
  if (pixels && !pixels->empty())
  {
    const int w = pixels->width(), h = pixels->height(), ch = pixels->channels();
    block->SetDimensions(w, h, 1);
    // 8-bit photos as unsigned char, 16-bit ones as unsigned short; rows
    // bottom-up.
    vtkSmartPointer<vtkDataArray> a;
    if (pixels->bits() == 16)
    {
      a = vtkSmartPointer<vtkUnsignedShortArray>::New();
    }
    else
    {
      a = vtkSmartPointer<vtkUnsignedCharArray>::New();
    }
    a->SetName(PixelsName);
    a->SetNumberOfComponents(ch);
    a->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
    const std::size_t row = static_cast<std::size_t>(w) * ch * (pixels->bits() / 8);
    auto* base = static_cast<std::uint8_t*>(a->GetVoidPointer(0));
    for (int y = 0; y < h; ++y)
    {
      std::memcpy(base + static_cast<std::size_t>(h - 1 - y) * row, pixels->data() + y * row, row);
    }
    block->GetPointData()->SetScalars(a);
  }
  return block;
}

namespace
{

// The leaf's name in its parent's metadata, or "".
std::string LeafName(vtkDataObjectTreeIterator* it)
{
  if (it->HasCurrentMetaData() && it->GetCurrentMetaData()->Has(vtkCompositeDataSet::NAME()))
  {
    return it->GetCurrentMetaData()->Get(vtkCompositeDataSet::NAME());
  }
  return std::string();
}

// The camera of a view block's field data; `what` names the block in errors.
meshnbv::PinholeCamera CameraOf(vtkFieldData* fd, const std::string& what)
{
  double size[2], k[9], r[9], t[3];
  std::string missing;
  if (!GetTuple(fd, ImageSizeName, 2, size))
  {
    missing += " ImageSize";
  }
  if (!GetTuple(fd, KName, 9, k))
  {
    missing += " K";
  }
  if (!GetTuple(fd, RName, 9, r))
  {
    missing += " R";
  }
  if (!GetTuple(fd, TName, 3, t))
  {
    missing += " t";
  }
  if (!missing.empty())
  {
    throw Error(what + ": no camera data (field arrays ImageSize (2), K (9), R (9) and t (3) are "
                       "needed; missing or malformed:" + missing + ")");
  }
  meshnbv::PinholeCamera c;
  c.skew = k[1];
  c.width = static_cast<int>(size[0]);
  c.height = static_cast<int>(size[1]);
  c.fx = k[0];
  c.cx = k[2];
  c.fy = k[4];
  c.cy = k[5];
  for (int i = 0; i < 9; ++i)
  {
    c.R(i / 3, i % 3) = r[i];
  }
  c.t = meshnbv::Vec3(t[0], t[1], t[2]);
  double distortion[2];
  if (GetTuple(fd, DistortionName, 2, distortion))
  {
    c.k1 = distortion[0];
    c.k2 = distortion[1];
  }
  double lens[9];
  if (GetTuple(fd, LensName, 9, lens))
  {
    if (lens[0] != 0.0 && lens[0] != 1.0)
    {
      throw Error(what + ": Lens[0] must be 0 (Brown-Conrady) or 1 (fisheye)");
    }
    c.lens = lens[0] == 1.0 ? meshnbv::LensModel::Fisheye : meshnbv::LensModel::Brown;
    c.k1 = lens[1];
    c.k2 = lens[2];
    c.k3 = lens[3];
    c.k4 = lens[4];
    c.k5 = lens[5];
    c.k6 = lens[6];
    c.p1 = lens[7];
    c.p2 = lens[8];
  }
  return c;
}

// Whether the block carries pixels; throws for a type ToImage does not convert.
bool HasPixels(vtkImageData* image, const std::string& what)
{
  vtkDataArray* pixels = PixelArray(image);
  if (!pixels)
  {
    return false;
  }
  const int nc = pixels->GetNumberOfComponents();
  const int type = pixels->GetDataType();
  if ((type != VTK_UNSIGNED_CHAR && type != VTK_UNSIGNED_SHORT) || nc < 1 || nc > 4)
  {
    throw Error(what + ": pixels must be unsigned char or unsigned short with 1 to 4 "
                       "components, got " + std::string(pixels->GetDataTypeAsString()) +
      " with " + std::to_string(nc) +
      " (convert them first, e.g. vtkImageShiftScale with SetOutputScalarTypeToUnsignedChar "
      "and the scale that maps their range to 0..255)");
  }
  return true;
}

// Leaf `index` of the views input, named `name` (may be empty).
ViewBlock ReadViewBlock(vtkDataObject* leaf, std::size_t index, const std::string& name)
{
  const std::string what =
    "view " + std::to_string(index) + (name.empty() ? "" : " ('" + name + "')");
  auto* image = vtkImageData::SafeDownCast(leaf);
  if (!image)
  {
    throw Error(what + ": no camera data (the block is " +
      (leaf ? std::string("a ") + leaf->GetClassName() : std::string("empty")) +
      ", not a vtkImageData with ImageSize, K, R and t in its field data)");
  }
  vtkFieldData* fd = image->GetFieldData();
  ViewBlock v;
  v.block = image;
  v.view.camera = CameraOf(fd, what);
  double used = 1;
  GetTuple(fd, UsedName, 1, &used);
  v.view.used = used != 0;
  v.view.label = GetString(fd, LabelName);
  if (v.view.label.empty())
  {
    v.view.label = name.empty() ? "view_" + std::to_string(index) : name;
  }
  v.view.image_path = GetString(fd, ImagePathName);
  v.hasPixels = HasPixels(image, what);
  return v;
}

} // namespace

std::vector<ViewBlock> ExtractViews(vtkDataObject* views)
{
  auto* tree = vtkDataObjectTree::SafeDownCast(views);
  if (!tree)
  {
    throw Error(std::string("the views input must be a vtkMultiBlockDataSet of vtkImageData (one "
                            "block per view), got ") +
      (views ? views->GetClassName() : "nothing"));
  }
  std::vector<ViewBlock> out;
  auto it = vtk::TakeSmartPointer(tree->NewTreeIterator());
  it->SetSkipEmptyNodes(false);
  it->VisitOnlyLeavesOn();
  it->TraverseSubTreeOn();
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    out.push_back(ReadViewBlock(it->GetCurrentDataObject(), out.size(), LeafName(it)));
  }
  return out;
}

namespace
{

// Rows flipped back to top-down, the first `image->channels()` components
// of each tuple (alpha dropped), as T (8 or 16 bits as the image holds).
template <typename T>
void CopyPixels(const T* values, int width, int height, int nc, meshnbv::Image* image)
{
  const int channels = image->channels();
  for (int y = 0; y < height; ++y)
  {
    const T* src = values + static_cast<std::size_t>(height - 1 - y) * width * nc;
    T* dst;
    if constexpr (sizeof(T) == 2)
    {
      dst = image->pixel16(0, y);
    }
    else
    {
      dst = image->pixel(0, y);
    }
    for (int x = 0; x < width; ++x)
    {
      for (int c = 0; c < channels; ++c)
      {
        dst[x * channels + c] = src[x * nc + c];
      }
    }
  }
}

} // namespace

meshnbv::Image ToImage(const ViewBlock& view)
{
  vtkImageData* block = view.block;
  vtkDataArray* a = PixelArray(block);
  int dims[3];
  block->GetDimensions(dims);
  // Any array-of-structs layout (vtkUnsignedCharArray, vtkUnsignedShortArray, ...).
  auto* u8 = vtkAOSDataArrayTemplate<unsigned char>::FastDownCast(a);
  auto* u16 = vtkAOSDataArrayTemplate<unsigned short>::FastDownCast(a);
  if (!a || (!u8 && !u16) || dims[2] != 1 ||
    a->GetNumberOfTuples() != static_cast<vtkIdType>(dims[0]) * dims[1])
  {
    throw Error("view '" + view.view.label +
      "': the pixels are not a 2-D image in an unsigned char or unsigned short array of "
      "contiguous tuples");
  }
  const int nc = a->GetNumberOfComponents();
  // Alpha dropped; unsigned short stays 16-bit, as the core keeps 16-bit files.
  meshnbv::Image image(dims[0], dims[1], nc >= 3 ? 3 : 1, u16 ? 16 : 8);
  if (u8)
  {
    CopyPixels(u8->GetPointer(0), dims[0], dims[1], nc, &image);
  }
  else
  {
    CopyPixels(u16->GetPointer(0), dims[0], dims[1], nc, &image);
  }
  return image;
}

meshnbv::View ToViewWithPixels(const ViewBlock& block)
{
  meshnbv::View view = block.view;
  if (!block.hasPixels)
  {
    return view;
  }
  auto image = std::make_shared<const meshnbv::Image>(ToImage(block));
  const meshnbv::PinholeCamera& c = view.camera;
  if (image->width() != c.width || image->height() != c.height)
  {
    throw Error("view '" + view.label + "': the pixels are " + std::to_string(image->width()) +
      "x" + std::to_string(image->height()) + " but its camera says " + std::to_string(c.width) +
      "x" + std::to_string(c.height));
  }
  view.pixels = std::move(image);
  view.image_path.clear();
  return view;
}

} // namespace vtkMeshNBV
