// MeshLab's document (current mesh layer + raster layers) as a core Scene,
// and core meshes back into mesh layers.
#pragma once

#include <string>
#include <vector>

#include <common/meshmodel.h>

#include "meshnbv/scene.h"

namespace meshnbv::meshlab {

struct ModelMesh {
  TriangleMesh mesh;
  std::vector<CFaceO*> faces;  // MeshLab face of each core face (deleted faces skipped)
};

// The mesh layer `model` with its vertices through the layer's transform Tr
// (as MeshLab draws it); deleted elements skipped. Throws meshnbv::Error
// for a layer without faces.
ModelMesh mesh_from_model(MeshModel& model);

// Face quality of each face of `mesh` (NaN stays NaN).
std::vector<float> face_quality(const ModelMesh& mesh);

struct DocumentScene {
  Scene scene;
  std::vector<CFaceO*> faces;         // MeshLab face of each core face
  std::vector<RasterModel*> rasters;  // raster layer of each view
  int views_with_image = 0;
};

// The mesh layer `model` (mesh_from_model) and every raster layer: a raster
// with an image plane is an existing view, one without is a candidate view
// (no image). A plane's image is the QImage MeshLab holds, converted once
// (image_from_qimage) and held by the view in memory (View::pixels): no
// file is read or written. A plane whose QImage is null (MeshLab could not
// decode its file) keeps the file as image_path, for the core's loader to
// try (it names the file and the view when it cannot). Throws
// meshnbv::Error with the reason.
DocumentScene scene_from_document(MeshDocument& document, MeshModel& model);

// Replaces the content of `model` by `mesh`: vertices, faces, face colours
// (when present) and the face attribute `quality_attribute` as face quality
// (when present).
void fill_model(const TriangleMesh& mesh, MeshModel& model,
                const std::string& quality_attribute = "quality");

}  // namespace meshnbv::meshlab
