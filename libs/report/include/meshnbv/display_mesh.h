// The mesh the report's 3-D view shows: the scene's mesh, or above a face
// budget a decimated copy (OpenMesh quadric edge collapses) that a browser
// renders interactively in software WebGL, with the map from every original
// face to the display face that stands for it.
#pragma once

#include <cstdint>
#include <vector>

#include "meshnbv/mesh.h"
#include "meshnbv/pri.h"

namespace meshnbv {

inline constexpr std::size_t kDefaultDisplayFaces = 250000;
// The interaction level of detail (coarse_display_mesh): the face budget of
// the mesh the 3-D view draws while the camera moves. The principle: a round
// budget whose frame renders within 33 ms (30 frames a second) in software
// WebGL (SwiftShader) on this project's 2-core machines at the report's
// canvas size. bench/report/run.sh fits a frame's time as fixed (mostly the
// pixels) + per face through both levels' turning frames and writes the
// faces a 33 ms frame holds (bench/results/report/report_3d.md: 27,000 to
// 33,000 under a load of 3 to 6, so 40,000 gives about 50 ms frames there;
// not yet measured on an idle machine). `meshnbv run --interaction-faces`.
inline constexpr std::size_t kDefaultInteractionFaces = 40000;

struct DisplayMesh {
  TriangleMesh mesh;                 // positions and faces only (no attributes)
  bool decimated = false;            // false: mesh is the original, face for face
  // Per original face: the display face standing for it. The identity when
  // not decimated. A face kept by the decimation stands for itself; a face
  // an edge collapse removed is taken over by its neighbour across the edge
  // that the collapse stretches over it (followed to a face still there).
  std::vector<int> display_face;
  // The inverse: the original faces of display face d are
  // members[member_begin[d] .. member_begin[d + 1]).
  std::vector<std::uint32_t> member_begin, members;
  // Per vertex of `mesh`: the vertex of the input mesh it is (a decimation
  // moves no vertex: an edge collapse keeps the vertex it collapses onto).
  std::vector<int> source_vertex;
};

// The mesh itself when it has at most `max_faces` faces; otherwise decimated
// to at most `max_faces` faces. Faces OpenMesh cannot hold (non-manifold
// edges, repeated indices) are kept unchanged, each standing for itself.
// Throws Error when max_faces is 0.
DisplayMesh display_mesh(const TriangleMesh& mesh, std::size_t max_faces = kDefaultDisplayFaces);

// A coarser copy of a display mesh, drawn while the camera moves: `display`
// decimated again (display_mesh(display.mesh, max_faces), the same path)
// with the maps composed, so that `mesh.display_face` / `members` map the
// *original* faces (those `display` maps) to the coarse faces, and
// display_pri(mesh, original, ...) gives each coarse face the area-weighted
// PRI of the original faces it stands for. `mesh.source_vertex` names
// vertices of `display.mesh`, so the coarse mesh can share its positions.
// `coarse_face`: per display face, the coarse face standing for it. At most
// `max_faces` faces: the display mesh itself (not decimated further) when
// it has no more. Throws Error when max_faces is 0.
struct CoarseDisplayMesh {
  DisplayMesh mesh;
  std::vector<int> coarse_face;
};
CoarseDisplayMesh coarse_display_mesh(const DisplayMesh& display, std::size_t max_faces = kDefaultInteractionFaces);

// Per display face flags of what its value rests on.
enum DisplayFlag : std::uint8_t {
  kDisplayUnobserved = 1,  // no PRI (grey)
  kDisplayTwoViews = 2,    // compared on 2 views only
  kDisplayLowTexture = 4,  // texture below low_texture_below (or none read)
};

// What each display face shows, from the original faces it stands for:
// the area-weighted mean PRI of those that are observed, NaN (unobserved)
// when they cover less than half of its members' area; kDisplayTwoViews /
// kDisplayLowTexture when the faces so flagged (pri_evidence's rules) make up
// more than half of the observed members' area. When not decimated these are
// each face's own value and flags.
struct DisplayPri {
  std::vector<float> pri;
  std::vector<std::uint8_t> flags;
};
DisplayPri display_pri(const DisplayMesh& display, const TriangleMesh& original, const PriResult& pri,
                       double low_texture_below);

}  // namespace meshnbv
