#include "document_scene.h"

#include <vcg/complex/algorithms/update/bounding.h>
#include <vcg/complex/algorithms/update/normal.h>

#include "meshnbv/error.h"
#include "raster_images.h"
#include "shot_conversion.h"

namespace meshnbv::meshlab {
namespace {

bool is_identity(const Matrix44m& m) {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      if (m.ElementAt(r, c) != (r == c ? 1.0f : 0.0f)) return false;
  return true;
}

}  // namespace

ModelMesh mesh_from_model(MeshModel& model) {
  ModelMesh out;
  CMeshO& m = model.cm;
  const std::string name = model.label().toStdString();
  if (m.fn == 0) throw Error("the mesh layer '" + name + "' has no faces");

  // Vertices in world coordinates: MeshLab draws a layer through its Tr.
  // Tr comes from the project's text like the cameras: decimal() as they.
  const bool transformed = !is_identity(m.Tr);
  double tr[4][4];
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) tr[r][c] = decimal(m.Tr.ElementAt(r, c));
  std::vector<int> index(m.vert.size(), -1);
  TriangleMesh& mesh = out.mesh;
  mesh.vertices.reserve(std::size_t(m.vn));
  for (std::size_t i = 0; i < m.vert.size(); ++i) {
    const CVertexO& v = m.vert[i];
    if (v.IsD()) continue;
    Vec3 p(double(v.cP()[0]), double(v.cP()[1]), double(v.cP()[2]));
    if (transformed) {
      double q[4];
      for (int r = 0; r < 4; ++r)
        q[r] = tr[r][0] * p.x() + tr[r][1] * p.y() + tr[r][2] * p.z() + tr[r][3];
      p = Vec3(q[0], q[1], q[2]) / q[3];
    }
    index[i] = int(mesh.vertices.size());
    mesh.vertices.push_back(p);
  }
  mesh.faces.reserve(std::size_t(m.fn));
  out.faces.reserve(std::size_t(m.fn));
  for (CFaceO& f : m.face) {
    if (f.IsD()) continue;
    Face face;
    for (int k = 0; k < 3; ++k) {
      const int vi = index[vcg::tri::Index(m, f.V(k))];
      if (vi < 0) throw Error("mesh layer '" + name + "': a face uses a deleted vertex");
      face[std::size_t(k)] = vi;
    }
    mesh.faces.push_back(face);
    out.faces.push_back(&f);
  }
  mesh.validate("mesh layer '" + name + "'");
  return out;
}

std::vector<float> face_quality(const ModelMesh& mesh) {
  std::vector<float> q;
  q.reserve(mesh.faces.size());
  for (const CFaceO* f : mesh.faces) q.push_back(float(f->cQ()));
  return q;
}

DocumentScene scene_from_document(MeshDocument& document, MeshModel& model) {
  DocumentScene out;
  ModelMesh converted = mesh_from_model(model);
  out.scene.mesh = std::move(converted.mesh);
  out.faces = std::move(converted.faces);
  out.scene.mesh_path = model.fullName().toStdString();
  out.scene.source = document.pathName().toStdString();
  out.scene.format = "meshlab";

  for (RasterModel* raster : document.rasterList) {
    View view;
    view.label = raster->label().toStdString();
    view.camera = camera_from_shot(raster->shot, "raster '" + view.label + "'");
    // currentPlane is left uninitialised by MeshLab when a raster has no
    // plane: look at planeList first.
    Plane* plane = nullptr;
    if (raster->planeList.size() == 1)
      plane = raster->planeList.first();
    else if (!raster->planeList.empty())
      plane = raster->planeList.contains(raster->currentPlane) ? raster->currentPlane
                                                               : raster->planeList.first();
    if (plane) {
      if (!plane->image.isNull()) {
        view.pixels = std::make_shared<const Image>(image_from_qimage(plane->image));
      } else {
        view.image_path = plane->fullPathFileName.toStdString();
        if (view.image_path.empty())
          throw Error("raster '" + view.label + "': its image plane has neither pixels nor a file");
      }
      ++out.views_with_image;
    }
    out.scene.views.push_back(std::move(view));
    out.rasters.push_back(raster);
  }
  return out;
}

void fill_model(const TriangleMesh& mesh, MeshModel& model, const std::string& quality_attribute) {
  CMeshO& m = model.cm;
  m.Clear();
  const std::vector<float>* quality = mesh.face_attribute(quality_attribute);
  int mask = 0;
  if (!mesh.face_colors.empty()) mask |= MeshModel::MM_FACECOLOR;
  if (quality) mask |= MeshModel::MM_FACEQUALITY;
  if (mask) model.updateDataMask(mask);
  auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(m, mesh.num_vertices());
  for (const Vec3& p : mesh.vertices) {
    vi->P() = Point3m(Scalarm(p.x()), Scalarm(p.y()), Scalarm(p.z()));
    ++vi;
  }
  auto fi = vcg::tri::Allocator<CMeshO>::AddFaces(m, mesh.num_faces());
  for (std::size_t f = 0; f < mesh.num_faces(); ++f, ++fi) {
    for (int k = 0; k < 3; ++k) fi->V(k) = &m.vert[std::size_t(mesh.faces[f][std::size_t(k)])];
    if (!mesh.face_colors.empty()) {
      const Rgb8& c = mesh.face_colors[f];
      fi->C() = vcg::Color4b(c[0], c[1], c[2], 255);
    }
    if (quality) fi->Q() = (*quality)[f];
  }
  m.Tr.SetIdentity();
  vcg::tri::UpdateBounding<CMeshO>::Box(m);
  vcg::tri::UpdateNormal<CMeshO>::PerFaceNormalized(m);
  vcg::tri::UpdateNormal<CMeshO>::PerVertexNormalized(m);
}

}  // namespace meshnbv::meshlab
