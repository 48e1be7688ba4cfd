// Surface from sparse points and their visibility, after Labatut, Pons and
// Keriven, "Efficient multi-view reconstruction of large-scale scenes using
// interest points, Delaunay triangulation and graph cuts" (ICCV 2007), the
// family of methods the paper reconstructs with (also Romanoni and
// Matteucci 2015):
// 1. a 3-D Delaunay triangulation of the points (CGAL);
// 2. every camera-to-point ray says that the tetrahedra it crosses are free
//    space and that the one just behind the point is matter;
// 3. tetrahedra are labelled free or occupied, by an s-t minimum cut
//    (Boost's Boykov-Kolmogorov max-flow) or by a plain vote;
// 4. the triangles between free and occupied tetrahedra, oriented towards
//    the free side, are the surface.
#pragma once

#include <string>
#include <vector>

#include "meshnbv/mesh.h"
#include "meshnbv/progress.h"

namespace meshnbv::eval {

// A 3-D point and the cameras that observed it (indices into the centres
// passed to the mesher).
struct SparsePoint {
  Vec3 position = Vec3::Zero();
  std::vector<int> views;
};

enum class Labelling { GraphCut, Vote };
enum class FacetSupport { All, Any, Edges, Common };
FacetSupport parse_facet_support(const std::string& name);  // all | any | edges | common
std::string facet_support_name(FacetSupport support);
Labelling parse_labelling(const std::string& name);  // "graphcut" | "vote"
std::string labelling_name(Labelling labelling);

struct VisibilityMesherOptions {
  Labelling labelling = Labelling::GraphCut;
  double visibility_weight = 1.0;  // alpha_vis of each ray (free facets and the cell behind the point)
  // Cost of every facet in the cut, times the median visibility votes per
  // facet: a small value smooths the surface and removes thin slivers.
  double surface_weight = 0.05;
  // Vote labelling: a tetrahedron crossed by at least this many rays is free.
  int min_free_votes = 1;
  // Points seen by fewer cameras are dropped: on templeRing, half of the
  // points outside the object have 2 views, 7% of those on it.
  int min_views_per_point = 3;
  // Outliers (sparse points far from the object: a few, triangulated from
  // near-parallel rays, make huge triangles): points farther from the
  // points' median than `max_spread` times the 90th percentile of that
  // distance are dropped (0 = keep all) ...
  double max_spread = 2.0;
  // ... and so are isolated points: mean distance to their 3 nearest
  // Delaunay neighbours above `max_isolation` times the median of that (0 = keep).
  double max_isolation = 5.0;
  // Which surface triangles are output (the occupied/free boundary also
  // runs where no camera looked):
  // - Any: a camera that saw one of its corners looks at its front;
  // - Edges: besides, the two ends of each edge were seen by a common
  //   camera (no triangle bridges parts seen by different cameras, like
  //   two facades seen from different sides, through the inside);
  // - Common: one camera saw all three corners and looks at its front
  //   (strictest: with short tracks many true triangles fail);
  // - All: every boundary triangle.
  FacetSupport facet_support = FacetSupport::Any;
  // Connected pieces of the output with fewer faces than this share of the
  // largest one are dropped (0 keeps everything).
  double min_component_share = 0.02;

  void check() const;
};

struct VisibilityMesherResult {
  TriangleMesh mesh;  // oriented outwards (towards the free side)
  std::size_t points = 0;        // vertices of the triangulation
  std::size_t outliers = 0;      // points dropped as outliers
  std::size_t tetrahedra = 0;    // finite cells
  std::size_t free_tetrahedra = 0, occupied_tetrahedra = 0;
  std::size_t rays = 0, failed_rays = 0;  // failed: degenerate traversal, skipped
  double seconds = 0;  // the whole call, of which:
  double seconds_delaunay = 0;    // outliers, triangulation (twice when isolated points are dropped)
  double seconds_visibility = 0;  // the rays' walks (parallel)
  double seconds_labelling = 0;   // graph cut or vote
};

// `centres[i]` is the centre of camera i. Fewer than 4 usable points (or
// all coplanar) give an empty mesh, not an error.
VisibilityMesherResult mesh_from_visibility(const std::vector<SparsePoint>& points,
                                            const std::vector<Vec3>& centres,
                                            const VisibilityMesherOptions& options = {},
                                            const ProgressCallback& progress = {});

}  // namespace meshnbv::eval
