// Photo-consistency Reconstruction Index (PRI) per face, after Morreale,
// Romanoni, Matteucci, "Predicting the Next Best View for 3D Mesh
// Refinement" (2018), exactly as ../shared/SPEC.md sections 2-3 define it:
// each face is sampled on a barycentric lattice, the 3-D samples are
// projected into every view that sees the face, and the patches of every
// pair of views are compared (SSD or NCC). Higher PRI = worse.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "meshnbv/progress.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/scene.h"
#include "meshnbv/visibility.h"

namespace meshnbv {

// SSD and NCC: the SPEC's pairwise patch comparisons. Offset (beyond the
// paper, docs/deviations.md): the distance along the face's normal from the
// face to the position where its views agree best, found by a sweep of
// offsets (plane-sweep stereo on a support patch around the face); in
// scene units, so it estimates the face's error itself.
enum class Measure { SSD, NCC, Offset };
Measure parse_measure(const std::string& name);  // "ssd" | "ncc" | "offset"
std::string measure_name(Measure measure);

enum class FaceStatus : std::uint8_t {
  Observed = 0,     // PRI defined
  Unobserved = 1,   // seen by fewer than 2 views
  Textureless = 2,  // seen by >= 2 views, but every pair was textureless (NCC)
};

struct PriOptions {
  Measure measure = Measure::SSD;  // the paper's choice for its experiments
  int samples_per_side = 0;        // r of the lattice; 0 = automatic (largest projected edge, in [2, 32])
  int max_views_per_face = 0;      // 0 = all; else the smallest incidence angles
  bool color = false;              // compare R, G, B samples instead of luminance
  int threads = 0;                 // 0 = all cores
  double textureless_variance = 1e-6;  // NCC: patches with lower variance are textureless
  // A view whose direction makes a larger angle with the face normal does
  // not count as seeing the face [deviation, docs/deviations.md]: at grazing
  // angles the patch projects to a sliver and its samples are meaningless.
  // 90 = the SPEC's plain back-face rule.
  double max_incidence_angle = 80.0;  // degrees
  // Besides its three vertices, the face's centroid and edge midpoints
  // must be unoccluded in a view [deviation, docs/deviations.md]: vertex
  // visibility alone misses partial occlusion (a face behind a thin
  // parapet, in a concave corner). False = the SPEC's vertex rule only.
  bool check_interior_occlusion = true;
  // Keep the lattice this many pixels inside the face's projection in
  // every view, by contracting it towards the centroid (at most to half
  // size) [deviation, docs/deviations.md]: bilinear samples on a face's
  // border read the pixels beyond it -- the next face across a crease, the
  // background across a silhouette -- which differ between views even for
  // a perfect mesh. 0 = the SPEC's lattice over the whole face.
  double edge_margin = 0.5;  // pixels
  // offset: each face's signed offset is averaged with those of the faces
  // around its vertices, with Gaussian weights of this standard deviation
  // (pixels in the face's reference view) on the distance between
  // centroids: a support region for faces of a few pixels. 0 = none.
  double support_radius = 4.0;  // pixels
  // offset: offsets swept along the normal, up to this disparity (pixels in
  // the view where a normal offset moves the face most), both directions.
  double offset_range = 3.0;  // pixels
  // offset: hypotheses per side of zero; hypothesis j sits at
  // offset_range (j / offset_steps)^1.5 (finer near the face).
  int offset_steps = 4;
  // A JPEG photo may be decoded 2, 4 or 8 times smaller on each side (the
  // largest power of two up to this; the decoder's DCT scaling,
  // Image::load) when every face that may sample it has its lattice rows
  // at least that many pixels apart there: faster and less memory [beyond
  // the SPEC, docs/deviations.md]. Default 1 (always whole): where it
  // applies, the averaged pixels lose the fine texture that shows a face's
  // misregistration, and PRI finds error less well (measured:
  // bench/results/photos/reduction.md).
  int max_image_reduction = 1;
  VisibilityOptions visibility;

  void check() const;  // throws Error for values out of range
};

struct PriResult {
  std::vector<float> pri;        // NaN where undefined
  std::vector<int> pri_views;    // views that see the face (after max_views_per_face)
  std::vector<FaceStatus> status;
  // What each value rests on (NaN/0 where undefined), so that "bad" can be
  // told from "not enough evidence":
  std::vector<int> pri_pairs;      // comparisons averaged: view pairs (ssd, ncc), views against the reference (offset)
  std::vector<int> pri_samples;    // samples per view (lattice points)
  std::vector<float> pri_texture;  // texture strength: standard deviation of the samples
                                   // (intensity in [0, 1]), mean over the compared views
  // offset: each face's signed offset before the support smoothing, its
  // precision, the scene units per pixel at its centroid in its reference
  // view, and 1 where the sweep's least cost is at an end reached by a
  // steady fall of the cost, else 0 (what smooth_offsets reads); empty for
  // ssd and ncc.
  std::vector<float> offset_signed, offset_precision, offset_pixel, offset_steady;
  // What each face's value rests on, as one 64-bit key (pri_evidence_key):
  // the options and, in order, the identity of every view compared. The
  // same face (identical vertex positions, in order) with the same key has
  // the same value, bit for bit: incremental PRI (PriPrevious) reuses it.
  std::vector<std::uint64_t> evidence_key;
  // pri_view_key of each view that took part, in order (what the keys
  // above were formed from; incremental PRI compares them).
  std::vector<std::uint64_t> view_keys;
  std::uint64_t options_key = 0;  // pri_options_key of the options used
  std::size_t observed = 0, unobserved = 0, textureless = 0;
  std::size_t views_used = 0;    // views with an image that took part
  std::size_t recomputed = 0;    // faces computed by this call (the others were reused)
  std::size_t reselected = 0;    // faces whose views this call selected (all, or fewer when incremental)
  std::size_t images_decoded = 0;  // image decodes this call needed (cache misses)
  std::size_t views_reduced = 0;   // views whose photo was decoded reduced (max_image_reduction)
  double seconds = 0;
};

// Uses every view with an image and used == true. Throws Error when the
// mesh is invalid or an image is missing/undecodable; Cancelled when the
// progress callback says stop. Deterministic for any thread count.
// The views of each face that compute_pri compares, with its lattice: the
// first phase of compute_pri (validation, visibility, grazing and
// interior-occlusion rules, max_views_per_face), for tools that need the
// per-face view lists (bench/). Throws Error as compute_pri does.
struct PriFaceViews {
  std::vector<int> views;    // indices into PriViewSelection::cameras, ascending
  int samples_per_side = 0;  // r of the lattice (options' value or the automatic rule)
  double shrink = 0;         // lattice contraction towards the centroid (edge_margin)
  int reference = 0;         // offset: position in `views` of the reference view
  double step = 0;           // offset: scene units per pixel of disparity in the fastest view
  double pixel = 0;          // offset: scene units per pixel at the centroid in the reference view
};
struct PriViewSelection {
  std::vector<std::size_t> image_views;  // scene view of each camera below
  std::vector<PinholeCamera> cameras;
  std::vector<std::uint64_t> view_keys;  // pri_view_key of each camera's view
  // Per camera, how many times smaller its photo is decoded (1, 2, 4, 8;
  // max_image_reduction): the largest that keeps every face that may use
  // the view (in its frustum, facing it within max_incidence_angle; no
  // occlusion test) sampled at least that many pixels apart. Depends on the
  // whole mesh, never on the faces selected for, so tiles and ranks agree.
  std::vector<int> reductions;
  std::uint64_t options_key = 0;         // pri_options_key
  // The faces selected for: empty = every face of the mesh (faces[f] is
  // face f); else ascending face ids, faces[j] being face face_ids[j].
  std::vector<std::uint32_t> face_ids;
  std::vector<PriFaceViews> faces;
  std::uint32_t face_id(std::size_t j) const { return face_ids.empty() ? std::uint32_t(j) : face_ids[j]; }
};
// `faces`: ascending face ids to select for (a tile, docs/scale.md), empty =
// every face; only their vertices' visibility is computed, against the
// whole mesh, so each face's selection is the one of the whole-mesh call.
// `caster`: the whole mesh's ray caster when the caller keeps one (tiles
// of one mesh), else one is built.
// `views_only`: only the views, their cameras and keys (no face).
PriViewSelection select_pri_views(const Scene& scene, const PriOptions& options = {},
                                  const ProgressCallback& progress = {},
                                  const std::vector<std::uint32_t>& faces = {},
                                  const RayCaster* caster = nullptr, bool views_only = false);

PriResult compute_pri(const Scene& scene, const PriOptions& options = {},
                      const ProgressCallback& progress = {});

// Incremental PRI (docs/scale.md): the previous mesh and its PRI (with
// evidence_key, as compute_pri returns it or read_pri_previous reads it
// back). compute_pri then selects the views of every face of the new scene
// and samples only the faces that have no identical face in `mesh` with the
// same evidence key (new or moved faces, faces whose visible views,
// occluders, cameras, images or options changed); the others keep their
// previous values. The result equals a full computation bit for bit;
// `recomputed` counts the faces computed.
struct PriPrevious {
  TriangleMesh mesh;
  PriResult result;
};
PriResult compute_pri(const Scene& scene, const PriOptions& options, const ProgressCallback& progress,
                      const PriPrevious* previous);

// PRI in parts (tiles over processes, docs/scale.md): the values of the
// faces of `selection` before the whole-mesh step; `values`' arrays are
// indexed like `faces`. compute_pri = compute_pri_part over every face +
// assemble_pri.
struct PriPart {
  std::vector<std::uint32_t> faces;  // ascending
  PriResult values;
};
PriPart compute_pri_part(const Scene& scene, const PriOptions& options,
                         const PriViewSelection& selection, const ProgressCallback& progress = {});
// The whole result from parts that hold every face of the mesh exactly once
// (throws Error otherwise): values placed, the offset measure's support
// smoothing, the counts. `recomputed` = the faces of the parts computed
// by compute_pri_part (all of them here).
PriResult assemble_pri(const Scene& scene, const PriOptions& options, const std::vector<PriPart>& parts);

// Incremental PRI's first step: which faces of the new scene `previous`
// already holds (identical geometry and evidence key), with their values,
// and a view selection of the others alone. Views are selected only for
// the faces a change may reach; the others keep their previous selection,
// which is provably the same when
// - the options key is the same (PriResult::options_key), and the
//   previous view keys (PriResult::view_keys) come in the same order
//   among the new ones (views added anywhere; none removed or changed);
// - the mesh's bounding box is the same, bit for bit (it sets the
//   visibility tolerance and the ray caster's frame);
// - no view that is new, and no view through the edited geometry (the
//   triangles removed or added), sees the face's tile: judged on the tiles'
//   and the edits' bounding boxes projected into each pinhole camera.
// Otherwise every face's views are selected again (still only the faces
// whose key changed are sampled). `caster`: the new mesh's, when kept.
struct PriReuse {
  PriPart reused;
  PriViewSelection changed;  // face_ids: the faces to compute (none when empty)
  std::size_t selected = 0;  // faces whose views were selected again
};
PriReuse plan_incremental_pri(const Scene& scene, const PriOptions& options, const PriPrevious& previous,
                              const ProgressCallback& progress = {}, const RayCaster* caster = nullptr);

// Compact groups of faces for distributing PRI: the ids of `faces` (empty
// = every face) sorted along a Morton curve of their centroids (one scale on
// every axis) and cut into
// `count` runs of equal size (fewer when there are fewer faces); each run
// ascending. Deterministic.
std::vector<std::vector<std::uint32_t>> pri_tiles(const TriangleMesh& mesh, std::size_t count,
                                                  const std::vector<std::uint32_t>& faces = {});

// The identities behind evidence keys: a view's camera (every parameter)
// and image source (a file's path, size and modification time, or the
// content of in-memory pixels); the options that change values (all but
// threads); and a face's key from them and its views' keys in order.
std::uint64_t pri_view_key(const Scene& scene, std::size_t view);
std::uint64_t pri_options_key(const PriOptions& options);
// pri_view_key of every view with an image and used, in order.
std::vector<std::uint64_t> pri_view_keys(const Scene& scene);

// The similarity errors of the SPEC on two sample vectors of equal length:
// SSD = mean squared difference; NCC error = (1 - rho) / 2, or a negative
// value when either patch is textureless (variance < min_variance).
double ssd_error(const float* a, const float* b, std::size_t n);
double ncc_error(const float* a, const float* b, std::size_t n, double min_variance);

// The sum over every pair of `patches` (n floats each) of ssd_error, or of
// ncc_error over the pairs where neither patch is textureless, in O(m n)
// for m patches instead of O(m^2 n) (double accumulation):
//   SSD: sum_{a<b} |x_a - x_b|^2 = m sum_a |x_a - mu|^2, mu the mean patch;
//   NCC: sum_{a<b} rho_ab = (|sum_a z_a|^2 - sum_a |z_a|^2) / 2, z_a the
//        zero-mean, unit-norm patches of the textured views.
// Sets *pairs to the pairs counted. Agrees with the pairwise loop to 1e-9
// relative (tests/core/test_pri.cpp; NCC's per-pair clamp of rho to
// [-1, 1] only removes rounding). `scratch` is reused between calls.
double pair_error_sum(const std::vector<const float*>& patches, std::size_t n, Measure measure,
                      double min_variance, std::size_t* pairs, std::vector<double>* scratch);

// The same sum streamed: a face's patches added one at a time, as each
// view is sampled, into pair_accumulator_size(n) zeroed doubles, so that
// no patch is kept. pair_error_sum is this loop over its patches in order:
// the same patches in the same order give bitwise the same sum.
//   SSD: Welford's running mean patch and sum of squared deviations;
//   NCC: sum_a z_a and sum_a |z_a|^2 over the textured patches.
// Each patch's standard deviation is summed too (the face's texture).
std::size_t pair_accumulator_size(std::size_t n);
void pair_accumulate(double* acc, const float* patch, std::size_t n, Measure measure, double min_variance);
struct PairSum {
  double sum = 0;           // as pair_error_sum
  std::size_t pairs = 0;    // as pair_error_sum's *pairs
  std::size_t patches = 0;  // patches added
  double texture = 0;       // mean standard deviation of the patches added (0 without any)
};
PairSum pair_accumulated_sum(const double* acc, std::size_t n, Measure measure);

// Colours for a PRI map: hue from green (low PRI) to red (high PRI) over
// [lo, hi]; grey where the PRI is NaN.
std::vector<Rgb8> pri_colors(const std::vector<float>& pri, double lo, double hi);

struct PriSummary {
  std::size_t faces = 0, observed = 0, unobserved = 0, textureless = 0;
  std::vector<std::pair<double, double>> percentiles;  // (percent, value) over observed faces
  double histogram_min = 0, histogram_max = 0;
  std::vector<std::size_t> histogram;  // equal-width bins over [min, max]
  struct Worst {
    int face;
    float pri;
    int views;
  };
  std::vector<Worst> worst;  // the K highest PRI, worst first
};
PriSummary summarize_pri(const PriResult& result, std::size_t worst_k = 10, int bins = 20);

}  // namespace meshnbv
