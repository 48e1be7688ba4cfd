// The convex hull of a point set, as outward-facing triangles: an
// incremental hull (hull.cpp; the core links no CGAL). Used by the
// whole-mesh energy (gain.h) as a proxy for surface not yet reconstructed.
#pragma once

#include <array>
#include <vector>

#include "meshnbv/mesh.h"

namespace meshnbv {

using HullTriangle = std::array<Vec3, 3>;

// Outward triangles of the hull of `points`; empty when the points span
// less than three dimensions (fewer than four, or all coplanar within
// 1e-9 of their extent). A point within 1e-12 of the extent of a hull
// face's plane counts as on it (coplanar points add no vertex).
std::vector<HullTriangle> convex_hull_triangles(const std::vector<Vec3>& points);

}  // namespace meshnbv
