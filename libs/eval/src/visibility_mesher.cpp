// Delaunay + visibility + graph cut surface reconstruction (Labatut et al.
// 2007). One of the few translation units with CGAL (slow to compile).
#include "meshnbv/eval/visibility_mesher.h"
#include "meshnbv/enum_names.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

// Boost.Graph trips GCC 12's flow analysis at the point of inlining, where
// a push/pop around the includes does not reach.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#pragma GCC diagnostic pop

#include "meshnbv/error.h"

namespace meshnbv::eval {

constexpr detail::EnumTable<Labelling, 2> kLabellings = {
    {"graphcut", Labelling::GraphCut},
    {"vote", Labelling::Vote},
};

Labelling parse_labelling(const std::string& name) {
  return detail::parse_enum(name, kLabellings, "labelling");
}

std::string labelling_name(Labelling labelling) {
  return detail::enum_name(labelling, kLabellings);
}

constexpr detail::EnumTable<FacetSupport, 4> kFacetSupports = {
    {"all", FacetSupport::All},
    {"any", FacetSupport::Any},
    {"edges", FacetSupport::Edges},
    {"common", FacetSupport::Common},
};

FacetSupport parse_facet_support(const std::string& name) {
  return detail::parse_enum(name, kFacetSupports, "facet support");
}

std::string facet_support_name(FacetSupport support) {
  return detail::enum_name(support, kFacetSupports);
}

void VisibilityMesherOptions::check() const {
  check_option(visibility_weight > 0 && visibility_weight <= 1e6, "mesher visibility_weight",
               "in (0, 1e6]", visibility_weight);
  check_option(surface_weight >= 0 && surface_weight <= 1e6, "mesher surface_weight", "in [0, 1e6]",
               surface_weight);
  check_option(min_free_votes >= 1 && min_free_votes <= 1000000, "mesher min_free_votes",
               "in [1, 1000000]", min_free_votes);
  check_option(min_views_per_point >= 1 && min_views_per_point <= 100000,
               "mesher min_views_per_point", "in [1, 100000]", min_views_per_point);
  check_option(max_spread >= 0 && max_spread <= 1e6, "mesher max_spread", "0 (off) or in (0, 1e6]",
               max_spread);
  check_option(max_isolation >= 0 && max_isolation <= 1e6, "mesher max_isolation",
               "0 (off) or in (0, 1e6]", max_isolation);
  check_option(min_component_share >= 0 && min_component_share <= 1, "mesher min_component_share",
               "in [0, 1]", min_component_share);
}

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>;
using CellBase = CGAL::Triangulation_cell_base_with_info_3<
    int, Kernel, CGAL::Delaunay_triangulation_cell_base_3<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
using Point = Kernel::Point_3;
using CellHandle = Delaunay::Cell_handle;
using VertexHandle = Delaunay::Vertex_handle;
using SegmentCells = Delaunay::Segment_cell_iterator;

Point to_cgal(const Vec3& p) { return Point(p.x(), p.y(), p.z()); }
Vec3 from_cgal(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }

// Per cell: terminal weights, and the capacity of the edge to each of its
// four neighbours (edge c -> neighbour(i) in slot 4c + i).
struct Weights {
  std::vector<double> source, sink, facet;
  std::vector<int> votes;
  explicit Weights(std::size_t cells)
      : source(cells, 0.0), sink(cells, 0.0), facet(4 * cells, 0.0), votes(cells, 0) {}
};

// The labelling by s-t minimum cut: true = free (source side), the cells
// reachable from the source in the residual graph (the same set for every
// maximum flow). Boost's Boykov-Kolmogorov max-flow on a compressed sparse
// row graph, built in two passes over the arcs (count, then place).
std::vector<char> label_by_graph_cut(const Delaunay& dt, const std::vector<CellHandle>& cells,
                                     const Weights& w, double surface_cost) {
  using Graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, boost::no_property,
                                                   boost::no_property, std::uint32_t, std::size_t>;
  using Edge = boost::graph_traits<Graph>::edge_descriptor;
  const std::size_t n = cells.size();
  const auto s = std::uint32_t(n), t = std::uint32_t(n + 1);
  double total = 0;
  for (std::size_t c = 0; c < n; ++c) total += w.source[c] + w.sink[c];
  const double infinite = 10.0 * (total + 1.0);
  // Every arc pair (u -> v with capacity uv, v -> u with vu), in one order.
  auto for_each_pair = [&](auto&& pair) {
    for (std::size_t c = 0; c < n; ++c) {
      const CellHandle ch = cells[c];
      const bool inf = dt.is_infinite(ch);
      const double src = inf ? infinite : w.source[c];
      const auto cu = std::uint32_t(c);
      if (src > 0) pair(s, cu, src, 0.0);
      if (!inf && w.sink[c] > 0) pair(cu, t, w.sink[c], 0.0);
      for (int i = 0; i < 4; ++i) {
        const CellHandle nb = ch->neighbor(i);
        const auto m = static_cast<std::size_t>(nb->info());
        if (m < c) continue;  // each facet once
        const int j = nb->index(ch);
        const double extra = inf && dt.is_infinite(nb) ? 0.0 : surface_cost;
        const double cm = w.facet[4 * c + std::size_t(i)] + extra;
        const double mc = w.facet[4 * m + std::size_t(j)] + extra;
        if (cm > 0 || mc > 0) pair(cu, std::uint32_t(m), cm, mc);
      }
    }
  };
  std::vector<std::size_t> start(n + 3, 0);
  for_each_pair([&](std::uint32_t u, std::uint32_t v, double, double) {
    ++start[u + 1];
    ++start[v + 1];
  });
  for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
  const std::size_t arcs = start[n + 2];
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ends(arcs);
  std::vector<double> capacity(arcs), residual(arcs);
  std::vector<std::size_t> reverse_index(arcs);
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for_each_pair([&](std::uint32_t u, std::uint32_t v, double uv, double vu) {
    const std::size_t e1 = next[u]++, e2 = next[v]++;
    ends[e1] = {u, v};
    ends[e2] = {v, u};
    capacity[e1] = uv;
    capacity[e2] = vu;
    reverse_index[e1] = e2;
    reverse_index[e2] = e1;
  });
  Graph g(boost::edges_are_sorted, ends.begin(), ends.end(), std::uint32_t(n + 2), arcs);
  std::vector<Edge> reverse(arcs);
  for (std::size_t e = 0; e < arcs; ++e) reverse[e] = Edge(ends[reverse_index[e]].first, reverse_index[e]);
  std::vector<std::pair<std::uint32_t, std::uint32_t>>().swap(ends);
  std::vector<std::size_t>().swap(reverse_index);
  const auto edge_index = boost::get(boost::edge_index, g);
  const auto vertex_index = boost::get(boost::vertex_index, g);
  std::vector<Edge> predecessor(n + 2);
  std::vector<boost::default_color_type> color(n + 2);
  std::vector<std::uint32_t> distance(n + 2);
  boost::boykov_kolmogorov_max_flow(
      g, boost::make_iterator_property_map(capacity.begin(), edge_index),
      boost::make_iterator_property_map(residual.begin(), edge_index),
      boost::make_iterator_property_map(reverse.begin(), edge_index),
      boost::make_iterator_property_map(predecessor.begin(), vertex_index),
      boost::make_iterator_property_map(color.begin(), vertex_index),
      boost::make_iterator_property_map(distance.begin(), vertex_index), vertex_index, s, t);
  std::vector<char> free(n, 0);
  for (std::size_t c = 0; c < n; ++c) free[c] = color[c] == color[s] ? 1 : 0;
  return free;
}

// Points far from the bulk: distance to the per-axis median beyond
// `spread` times the 90th percentile of those distances.
void drop_far_points(const std::vector<SparsePoint>& points, double spread, std::vector<char>* usable,
                     std::size_t* dropped) {
  if (spread <= 0) return;
  std::vector<double> xs[3];
  for (std::size_t i = 0; i < points.size(); ++i)
    if ((*usable)[i])
      for (int k = 0; k < 3; ++k) xs[k].push_back(points[i].position[k]);
  if (xs[0].size() < 10) return;
  Vec3 median;
  for (int k = 0; k < 3; ++k) {
    std::nth_element(xs[k].begin(), xs[k].begin() + long(xs[k].size() / 2), xs[k].end());
    median[k] = xs[k][xs[k].size() / 2];
  }
  std::vector<double> d;
  for (std::size_t i = 0; i < points.size(); ++i)
    if ((*usable)[i]) d.push_back((points[i].position - median).norm());
  const std::size_t at = std::min(d.size() - 1, std::size_t(0.9 * double(d.size())));
  std::nth_element(d.begin(), d.begin() + long(at), d.end());
  const double limit = spread * d[at];
  for (std::size_t i = 0; i < points.size(); ++i)
    if ((*usable)[i] && (points[i].position - median).norm() > limit) {
      (*usable)[i] = 0;
      ++*dropped;
    }
}

// Faces grouped into pieces connected through shared vertices.
void drop_small_components(TriangleMesh* mesh, double min_share) {
  if (mesh->faces.empty() || min_share <= 0) return;
  std::vector<int> parent(mesh->num_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[std::size_t(x)] != x) {
      parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
      x = parent[std::size_t(x)];
    }
    return x;
  };
  for (const Face& f : mesh->faces) {
    const int a = find(f[0]);
    parent[std::size_t(find(f[1]))] = a;
    parent[std::size_t(find(f[2]))] = a;
  }
  std::unordered_map<int, std::size_t> count;
  for (const Face& f : mesh->faces) ++count[find(f[0])];
  std::size_t largest = 0;
  for (const auto& [root, k] : count) largest = std::max(largest, k);
  const double keep = min_share * double(largest);
  std::vector<Face> kept;
  for (const Face& f : mesh->faces)
    if (double(count[find(f[0])]) >= keep) kept.push_back(f);
  // Compact the vertices.
  std::vector<int> remap(mesh->num_vertices(), -1);
  std::vector<Vec3> vertices;
  for (Face& f : kept)
    for (int& v : f) {
      if (remap[std::size_t(v)] < 0) {
        remap[std::size_t(v)] = int(vertices.size());
        vertices.push_back(mesh->vertices[std::size_t(v)]);
      }
      v = remap[std::size_t(v)];
    }
  mesh->faces = std::move(kept);
  mesh->vertices = std::move(vertices);
}

// Points seen by enough views and finite are usable; a view index out of
// range is an error.
std::vector<char> usable_points(const std::vector<SparsePoint>& points, const std::vector<Vec3>& centres,
                                const VisibilityMesherOptions& options) {
  std::vector<char> usable(points.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SparsePoint& p = points[i];
    for (int v : p.views)
      if (v < 0 || std::size_t(v) >= centres.size())
        throw Error("mesher: point " + std::to_string(i) + " names camera " + std::to_string(v) +
                    " of " + std::to_string(centres.size()));
    usable[i] = int(p.views.size()) >= options.min_views_per_point && p.position.allFinite();
  }
  return usable;
}

// The Delaunay triangulation of the usable points, and the vertex of each
// point (null for the others).
struct Triangulation {
  Delaunay dt;
  std::vector<VertexHandle> handle;

  // Inserted in one spatially sorted range (CGAL's Hilbert sort), the
  // fastest way in; the triangulation does not depend on the order (CGAL's
  // symbolic perturbation), only its internal numbering does. A point equal
  // to an earlier one shares its vertex.
  void build(const std::vector<SparsePoint>& points, const std::vector<char>& usable) {
    dt.clear();
    handle.assign(points.size(), VertexHandle());
    std::vector<std::pair<Point, int>> in;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (usable[i]) in.emplace_back(to_cgal(points[i].position), int(i));
    dt.insert(in.begin(), in.end());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
      handle[std::size_t(v->info())] = v;
    for (const auto& [q, i] : in)  // duplicates: the vertex already there
      if (handle[std::size_t(i)] == VertexHandle()) handle[std::size_t(i)] = dt.insert(q);
  }
};

// Points whose 3 shortest Delaunay edges are longer, on average, than
// `max_isolation` times the median of that mean: no longer usable. Returns
// how many.
std::size_t drop_isolated_points(const std::vector<SparsePoint>& points, const Triangulation& t,
                                 double max_isolation, std::vector<char>* usable) {
  std::vector<double> isolation(points.size(), -1.0), all;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 256), [&](const auto& range) {
    std::vector<VertexHandle> nb;
    std::vector<double> d;
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      if (!(*usable)[i]) continue;
      nb.clear();
      d.clear();
      t.dt.adjacent_vertices_threadsafe(t.handle[i], std::back_inserter(nb));  // no marks on the cells
      for (const auto& u : nb)
        if (!t.dt.is_infinite(u)) d.push_back((from_cgal(u->point()) - points[i].position).norm());
      const std::size_t k = std::min<std::size_t>(3, d.size());
      std::partial_sort(d.begin(), d.begin() + long(k), d.end());
      double sum = 0;
      for (std::size_t j = 0; j < k; ++j) sum += d[j];
      isolation[i] = k ? sum / double(k) : 0.0;
    }
  });
  for (std::size_t i = 0; i < points.size(); ++i)
    if ((*usable)[i]) all.push_back(isolation[i]);
  if (all.empty()) return 0;
  std::nth_element(all.begin(), all.begin() + long(all.size() / 2), all.end());
  const double limit = max_isolation * all[all.size() / 2];
  std::size_t dropped = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    if ((*usable)[i] && isolation[i] > limit) {
      (*usable)[i] = 0;
      ++dropped;
    }
  return dropped;
}

// The triangulation numbered: vertex ids and cell ids in `info()`, every
// cell (infinite ones too) by id, and the cameras of each vertex, sorted
// (duplicate points share a vertex and their views).
struct Numbering {
  std::vector<std::vector<int>> sorted_views;  // per vertex id
  std::vector<CellHandle> cells;               // per cell id
};

Numbering number_triangulation(const std::vector<SparsePoint>& points, Triangulation* t) {
  Numbering n;
  Delaunay& dt = t->dt;
  int next_vertex_id = 0;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
    v->info() = next_vertex_id++;
  n.sorted_views.resize(static_cast<std::size_t>(next_vertex_id));
  for (std::size_t i = 0; i < points.size(); ++i)
    if (t->handle[i] != VertexHandle()) {
      auto& views = n.sorted_views[std::size_t(t->handle[i]->info())];
      views.insert(views.end(), points[i].views.begin(), points[i].views.end());
    }
  for (auto& views : n.sorted_views) {
    std::sort(views.begin(), views.end());
    views.erase(std::unique(views.begin(), views.end()), views.end());
  }
  n.cells.reserve(dt.number_of_cells() + 64);
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
    c->info() = int(n.cells.size());
    n.cells.push_back(c);
  }
  return n;
}

// What the rays say, counted: per cell the rays ending just in front of a
// point (source) or just behind it (sink) and the rays crossing it (votes),
// and per facet slot (4c + i) the rays crossing it. Counts add up in any
// order, so the rays can be traced by any number of threads with the same
// result.
struct RayCounts {
  std::vector<std::uint32_t> source, sink, facet, votes;
  std::size_t rays = 0, failed_rays = 0;
  explicit RayCounts(std::size_t cells) : source(cells, 0), sink(cells, 0), facet(4 * cells, 0), votes(cells, 0) {}
  void add(const RayCounts& o) {
    auto sum = [](std::vector<std::uint32_t>& x, const std::vector<std::uint32_t>& y) {
      for (std::size_t k = 0; k < x.size(); ++k) x[k] += y[k];
    };
    sum(source, o.source);
    sum(sink, o.sink);
    sum(facet, o.facet);
    sum(votes, o.votes);
    rays += o.rays;
    failed_rays += o.failed_rays;
  }
};

// The ray from point p (vertex v) to camera centre c: every crossed facet
// should not be surface, the cells crossed are free, the cell just behind
// the point is matter. Throws what CGAL throws on a degenerate walk. Reads
// the triangulation only (CGAL's walks keep their state locally).
void trace_ray(const Delaunay& dt, const VertexHandle& v, const Vec3& p, const Vec3& c, RayCounts* w) {
  // The walk starts just off the point: CGAL's traverser started at a
  // vertex on the convex hull may begin in any incident finite cell, even
  // when the segment leaves the hull at once.
  const Vec3 dir = (c - p).normalized();
  const double eps = 1e-7 * (c - p).norm();
  const Point ray_start = to_cgal(p + eps * dir);
  const CellHandle first = dt.locate(ray_start, v->cell());
  if (!dt.is_infinite(first)) {  // else the ray leaves the (convex) hull for good
    SegmentCells it(&dt, ray_start, to_cgal(c), first);
    const SegmentCells end = dt.segment_traverser_cells_end();
    CellHandle previous;
    bool left_hull = false;
    for (; it != end; ++it) {
      const CellHandle cell = it;
      const auto id = std::size_t(cell->info());
      int facet = -1;
      if (previous != CellHandle() && cell->has_neighbor(previous, facet)) ++w->facet[4 * id + std::size_t(facet)];
      if (dt.is_infinite(cell)) {
        left_hull = true;
        break;
      }
      ++w->votes[id];
      previous = cell;
    }
    if (!left_hull && previous != CellHandle()) ++w->source[std::size_t(previous->info())];
  }
  // Just behind the point: matter.
  const CellHandle back = dt.locate(to_cgal(p - eps * dir), v->cell());
  if (!dt.is_infinite(back)) ++w->sink[std::size_t(back->info())];
}

// Free facets and cells in front of each point, matter behind, from the
// rays of every point to its cameras, traced in parallel (TBB, the
// caller's arena) in 32 rounds with progress and cancellation between them;
// each ray weighs `alpha`.
Weights visibility_weights(const std::vector<SparsePoint>& points, const std::vector<Vec3>& centres,
                           const Triangulation& t, std::size_t cells, double alpha,
                           VisibilityMesherResult* result, const ProgressCallback& progress) {
  tbb::enumerable_thread_specific<RayCounts> local([cells] { return RayCounts(cells); });
  constexpr std::size_t kRounds = 32;
  for (std::size_t round = 0; round < kRounds; ++round) {
    const std::size_t begin = points.size() * round / kRounds, end = points.size() * (round + 1) / kRounds;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, 64), [&](const auto& range) {
      RayCounts& w = local.local();
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        if (t.handle[i] == VertexHandle()) continue;
        const Vec3 p = points[i].position;
        for (int view : points[i].views) {
          const Vec3 c = centres[std::size_t(view)];
          if ((c - p).norm() <= 0) continue;
          ++w.rays;
          try {
            trace_ray(t.dt, t.handle[i], p, c, &w);
          } catch (const std::exception&) {
            ++w.failed_rays;  // a degenerate configuration CGAL refused: skip the ray
          }
        }
      }
    });
    report_progress(progress, 0.2 + 0.6 * double(round + 1) / double(kRounds), "visibility");
  }
  RayCounts total(cells);
  for (const RayCounts& w : local) total.add(w);
  result->rays += total.rays;
  result->failed_rays += total.failed_rays;
  Weights w(cells);
  for (std::size_t c = 0; c < cells; ++c) {
    w.source[c] = alpha * double(total.source[c]);
    w.sink[c] = alpha * double(total.sink[c]);
    w.votes[c] = int(total.votes[c]);
  }
  for (std::size_t k = 0; k < w.facet.size(); ++k) w.facet[k] = alpha * double(total.facet[k]);
  return w;
}

// Free (1) or occupied (0) per cell, by vote or by graph cut.
std::vector<char> label_cells(const Delaunay& dt, const std::vector<CellHandle>& cells, const Weights& w,
                              const VisibilityMesherOptions& options) {
  std::vector<char> free;
  if (options.labelling == Labelling::Vote) {
    free.resize(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c)
      free[c] = dt.is_infinite(cells[c]) || w.votes[c] >= options.min_free_votes;
    return free;
  }
  std::vector<double> used;
  for (double x : w.facet)
    if (x > 0) used.push_back(x);
  double median = options.visibility_weight;
  if (!used.empty()) {
    std::nth_element(used.begin(), used.begin() + long(used.size() / 2), used.end());
    median = used[used.size() / 2];
  }
  return label_by_graph_cut(dt, cells, w, options.surface_weight * median);
}

// Whether a boundary triangle whose corners were seen by the cameras `v`
// counts as observed under `support` (not All): a camera of a corner faces
// it, and by Edges each edge's ends share a camera, or by Common one camera
// saw all three corners and faces it.
bool facet_supported(FacetSupport support, const std::vector<int>* const v[3], const Vec3& outward,
                     const Vec3& centroid, const std::vector<Vec3>& centres) {
  auto shares = [](const std::vector<int>& x, const std::vector<int>& y) {
    for (int view : x)
      if (std::binary_search(y.begin(), y.end(), view)) return true;
    return false;
  };
  auto faces_it = [&](int view) { return outward.dot(centres[std::size_t(view)] - centroid) > 0; };
  bool supported = false;
  if (support == FacetSupport::Common) {
    for (int view : *v[0])
      if (std::binary_search(v[1]->begin(), v[1]->end(), view) &&
          std::binary_search(v[2]->begin(), v[2]->end(), view) && faces_it(view)) {
        supported = true;
        break;
      }
  } else {
    for (int k = 0; k < 3 && !supported; ++k)
      for (int view : *v[k])
        if (faces_it(view)) {
          supported = true;
          break;
        }
    if (supported && support == FacetSupport::Edges)
      supported = shares(*v[0], *v[1]) && shares(*v[1], *v[2]) && shares(*v[2], *v[0]);
  }
  return supported;
}

// The free/occupied boundary into result->mesh, normals towards the free
// side, and the counts of free and occupied cells.
void extract_surface(const Numbering& n, const std::vector<char>& free, const std::vector<Vec3>& centres,
                     const VisibilityMesherOptions& options, VisibilityMesherResult* result) {
  std::vector<int> vertex_out(n.sorted_views.size(), -1);
  TriangleMesh& mesh = result->mesh;
  auto out_vertex = [&](const VertexHandle& vh) {
    int& slot = vertex_out[std::size_t(vh->info())];
    if (slot < 0) {
      slot = int(mesh.vertices.size());
      mesh.vertices.push_back(from_cgal(vh->point()));
    }
    return slot;
  };
  for (std::size_t c = 0; c < n.cells.size(); ++c) {
    if (free[c]) {
      ++result->free_tetrahedra;
      continue;
    }
    ++result->occupied_tetrahedra;
    const CellHandle ch = n.cells[c];
    for (int i = 0; i < 4; ++i) {
      if (!free[std::size_t(ch->neighbor(i)->info())]) continue;
      Face f{out_vertex(ch->vertex((i + 1) % 4)), out_vertex(ch->vertex((i + 2) % 4)),
             out_vertex(ch->vertex((i + 3) % 4))};
      const Vec3& a = mesh.vertices[std::size_t(f[0])];
      const Vec3 nrm = (mesh.vertices[std::size_t(f[1])] - a).cross(mesh.vertices[std::size_t(f[2])] - a);
      const bool flip = nrm.dot(from_cgal(ch->vertex(i)->point()) - a) > 0;
      if (flip) std::swap(f[1], f[2]);
      if (options.facet_support != FacetSupport::All) {
        const Vec3 outward = flip ? Vec3(-nrm) : nrm;
        const Vec3 centroid = (a + mesh.vertices[std::size_t(f[1])] + mesh.vertices[std::size_t(f[2])]) / 3.0;
        const std::vector<int>* v[3];
        for (int k = 0; k < 3; ++k) v[k] = &n.sorted_views[std::size_t(ch->vertex((i + 1 + k) % 4)->info())];
        if (!facet_supported(options.facet_support, v, outward, centroid, centres)) continue;
      }
      mesh.faces.push_back(f);
    }
  }
}

}  // namespace

VisibilityMesherResult mesh_from_visibility(const std::vector<SparsePoint>& points,
                                            const std::vector<Vec3>& centres,
                                            const VisibilityMesherOptions& options,
                                            const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  options.check();
  VisibilityMesherResult result;
  auto finish = [&]() {
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  };

  auto lap = [last = start]() mutable {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last).count();
    last = now;
    return s;
  };

  // 1. Delaunay triangulation of the usable points, without outliers.
  std::vector<char> usable = usable_points(points, centres, options);
  drop_far_points(points, options.max_spread, &usable, &result.outliers);
  Triangulation t;
  t.build(points, usable);
  if (options.max_isolation > 0 && t.dt.dimension() == 3) {
    const std::size_t dropped = drop_isolated_points(points, t, options.max_isolation, &usable);
    result.outliers += dropped;
    if (dropped) t.build(points, usable);
  }
  result.points = t.dt.number_of_vertices();
  if (t.dt.dimension() < 3) return finish();
  report_progress(progress, 0.2, "delaunay");
  const Numbering n = number_triangulation(points, &t);
  result.tetrahedra = t.dt.number_of_finite_cells();
  result.seconds_delaunay = lap();

  // 2. Visibility, 3. labels, 4. the boundary.
  const Weights w = visibility_weights(points, centres, t, n.cells.size(), options.visibility_weight,
                                       &result, progress);
  result.seconds_visibility = lap();
  const std::vector<char> free = label_cells(t.dt, n.cells, w, options);
  result.seconds_labelling = lap();
  report_progress(progress, 0.9, "labelling");
  extract_surface(n, free, centres, options, &result);
  result.free_tetrahedra -= std::min(result.free_tetrahedra, n.cells.size() - result.tetrahedra);
  drop_small_components(&result.mesh, options.min_component_share);
  report_progress(progress, 1.0, "mesh");
  return finish();
}

}  // namespace meshnbv::eval
