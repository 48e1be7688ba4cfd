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
};

// The mesh itself when it has at most `max_faces` faces; otherwise decimated
// to at most `max_faces` faces. Faces OpenMesh cannot hold (non-manifold
// edges, repeated indices) are kept unchanged, each standing for itself.
// Throws Error when max_faces is 0.
DisplayMesh display_mesh(const TriangleMesh& mesh, std::size_t max_faces = kDefaultDisplayFaces);

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
