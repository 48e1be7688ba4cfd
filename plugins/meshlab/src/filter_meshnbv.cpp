#include "filter_meshnbv.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <sstream>
#include <thread>
#include <vector>

#include <vcg/complex/algorithms/update/selection.h>

#include "document_scene.h"
#include "meshnbv/energy.h"
#include "meshnbv/error.h"
#include "meshnbv/results.h"
#include "meshnbv/planner.h"
#include "meshnbv/pri.h"
#include "shot_conversion.h"

using namespace meshnbv;
using meshnbv::meshlab::decimal;

namespace {

// Parameter names are public API: the core's snake_case option names, the
// same in the CLI (with dashes), the VTK properties and the JSON outputs.
// Each is listed once here: its dialog label, a brief for the filter's info
// text (kept short: MeshLab shows the info above the parameters) and the
// full help shown as the tooltip and under the dialog's Help button.
struct ParameterHelp {
  const char* name;
  const char* label;
  const char* brief;
  const char* help;
};

const ParameterHelp kPriParameters[] = {
    {"measure", "Measure", "ssd (the paper's) or ncc",
     "Photo-consistency measure of a pair of views: ssd = mean squared difference of the "
     "samples (the paper's choice); ncc = (1 - normalised cross-correlation) / 2, insensitive "
     "to contrast, pairs with a textureless patch skipped."},
    {"samples_per_side", "Samples per side", "lattice subdivisions per face side, 0 = automatic",
     "Subdivisions r of the barycentric lattice on each face ((r+1)(r+2)/2 samples). 0 = "
     "automatic: the largest projected edge in pixels, clamped to [2, 32]."},
    {"max_views_per_face", "Max views per face", "best-facing views compared, 0 = all",
     "Views compared per face, those with the smallest incidence angle first (0 = all views "
     "that see the face; otherwise at least 2)."},
    {"max_incidence_angle", "Max incidence angle", "degrees; more grazing views do not count",
     "Degrees. A view whose direction makes a larger angle with the face normal does not count "
     "as seeing the face (grazing views give slivers). 90 = the plain back-face rule."},
    {"edge_margin", "Edge margin", "pixels the samples stay inside each face",
     "Pixels. The sampling lattice is contracted towards the face's centroid so that it stays "
     "this far inside the face in every view: samples on the border would read the pixels "
     "beyond it (the next face, the background). 0 = sample the whole face."},
    {"check_interior_occlusion", "Check interior occlusion",
     "centroid and edge midpoints must be unoccluded too",
     "Besides its three vertices, the face's centroid and edge midpoints must be unoccluded in a "
     "view (catches partial occlusion, e.g. behind a thin parapet)."},
    {"color", "Compare colour", "compare R, G, B instead of luminance",
     "Compare R, G, B samples instead of luminance."},
    {"threads", "Threads", "0 = all cores",
     "Worker threads (0 = all cores). Results do not depend on it."},
};

const ParameterHelp kSuggestParameters[] = {
    {"candidates", "Candidates", "given (raster layers without image), sampled or refined",
     "Where candidate poses come from. given: the raster layers without an image (e.g. poses "
     "planned elsewhere), all ranked; sampled: a Fibonacci spiral of directions on the "
     "hemisphere of the worst region's mean normal, at 0.75, 1 and 1.5 times the median viewing "
     "distance of the existing rasters, looking at the region, with their intrinsics; refined: "
     "the best sampled poses improved by Nelder-Mead over position and viewing direction."},
    {"top", "Suggestions", "number of suggestions (greedy batch)",
     "Number of suggestions, chosen greedily: each pick counts as an existing view for the next "
     "ones."},
    {"worst", "Worst faces (K)", "faces in the worst region",
     "The K observed faces with the highest PRI form the worst region whose vertices the energy "
     "scores."},
    {"weight_occlusion", "Weight occlusion (m1)", "m1",
     "Weight of the occlusion term O (1 if a worst vertex is visible, else the penalty)."},
    {"weight_focus", "Weight focus (m2)", "m2",
     "Weight of the focus term F (Gaussian preference for projecting near the image centre)."},
    {"weight_parallax", "Weight parallax (m3)", "m3",
     "Weight of the parallax term Par (baseline / depth to each existing view above the "
     "threshold)."},
    {"weight_incidence", "Weight incidence (m4)", "m4",
     "Weight of the incidence term I (von Mises preference for the angle to the vertex "
     "normal)."},
    {"penalty", "Penalty (Kp)", "value of a failed term",
     "Value of a term when its condition fails (vertex occluded or outside the image, too small "
     "a baseline)."},
    {"parallax_delta", "Parallax threshold", "baseline / depth threshold",
     "Baseline / depth ratio above which a pair (candidate, existing view) counts as parallax."},
    {"incidence_mu", "Incidence mean", "preferred incidence angle, degrees",
     "Preferred angle (degrees) between the vertex normal and the ray to the camera."},
    {"incidence_sigma", "Incidence spread", "its spread, degrees",
     "Degrees; the von Mises concentration is 1 / sigma^2 (sigma in radians)."},
    {"directions", "Sampled directions", "directions on the hemisphere",
     "sampled/refined: directions on the hemisphere."},
    {"safety_distance", "Safety distance", "minimum distance to the surface, share of the diagonal",
     "Candidates nearer than this share of the bounding-box diagonal to the surface, or inside "
     "the mesh's volume, are rejected."},
    {"refine_best", "Refined candidates", "poses refined per suggestion",
     "refined: best sampled poses refined per suggestion."},
    {"refine_iterations", "Refine iterations", "Nelder-Mead iterations",
     "refined: Nelder-Mead iterations per pose."},
    {"seed", "Seed", "turns the sampling spiral",
     "Turns the sampling spiral (same seed, same candidates)."},
    {"threads", "Threads", "0 = all cores", "Worker threads (0 = all cores)."},
    {"use_face_quality", "Use face quality as PRI", "else PRI is computed with defaults",
     "Take PRI from the mesh's per-face quality, as Compute PRI leaves it (NaN = unobserved). "
     "Off, or when the mesh has no face quality: PRI is computed with Compute PRI's defaults."},
    {"add_frustum_layer", "Add frustum layer", "also add a mesh layer of the suggestions' frustums",
     "Also add a mesh layer 'nbv_frustums': one pyramid per suggestion (apex at the camera "
     "centre), coloured from red (first) to yellow, face quality = rank."},
};

const ParameterHelp kSelectParameters[] = {
    {"worst", "Worst faces (K)", "number of faces to select",
     "Number of faces to select: the observed faces with the highest face quality (PRI), ties "
     "by face index, as Suggest Next View picks its worst region. NaN (unobserved) faces are "
     "never selected."},
};

template <std::size_t N>
const ParameterHelp& help(const ParameterHelp (&table)[N], const char* name) {
  for (const ParameterHelp& p : table)
    if (std::string(p.name) == name) return p;
  throw std::logic_error(std::string("no help for parameter ") + name);
}

// One compact paragraph: MeshLab shows the info above the parameters.
template <std::size_t N>
QString parameter_list(const ParameterHelp (&table)[N]) {
  QStringList items;
  for (const ParameterHelp& p : table)
    items << QString("<b>%1</b>: %2").arg(p.name).arg(QString(p.brief).toHtmlEscaped());
  return "<p>Parameters (each explained in its tooltip and under Help): " + items.join("; ") +
         ".</p>";
}

const char* kCitation =
    "<p>See: <i>Luca Morreale, Andrea Romanoni, Matteo Matteucci</i>, <b>\"Predicting the Next "
    "Best View for 3D Mesh Refinement\"</b>, 2018. Implemented by MeshNBV; numbers equal the "
    "<tt>meshnbv</tt> command line's on the same project.</p>";

// Forwards the core's progress to MeshLab's callback, from the filter's own
// thread only (the GUI's callback touches widgets), and once per 10%.
class Progress {
 public:
  Progress(vcg::CallBackPos* meshlab_callback, std::string filter)
      : callback_(meshlab_callback), filter_(std::move(filter)), thread_(std::this_thread::get_id()) {}

  ProgressCallback callback() {
    return [this](double fraction, const std::string& stage) {
      if (!callback_ || std::this_thread::get_id() != thread_) return true;
      // Every 10%: meshlabserver prints each message on one line, unbroken.
      const int percent = std::clamp(int(fraction * 10.0), 0, 10) * 10;
      if (percent == last_percent_ && stage == last_stage_) return true;
      last_percent_ = percent;
      last_stage_ = stage;
      const std::string message = filter_ + ": " + stage;
      return callback_(percent, message.c_str());
    };
  }

 private:
  vcg::CallBackPos* callback_;
  std::string filter_;
  std::thread::id thread_;
  int last_percent_ = -1;
  std::string last_stage_;
};

std::string format(double value) {
  std::ostringstream ss;
  ss.precision(6);
  ss << value;
  return ss.str();
}

PriOptions pri_options(const RichParameterList& par) {
  PriOptions o;
  o.measure = par.getEnum("measure") == 1 ? Measure::NCC : Measure::SSD;
  o.samples_per_side = par.getInt("samples_per_side");
  o.max_views_per_face = par.getInt("max_views_per_face");
  o.max_incidence_angle = decimal(par.getFloat("max_incidence_angle"));
  o.edge_margin = decimal(par.getFloat("edge_margin"));
  o.check_interior_occlusion = par.getBool("check_interior_occlusion");
  o.color = par.getBool("color");
  o.threads = par.getInt("threads");
  o.check();
  return o;
}

SuggestOptions suggest_options(const RichParameterList& par) {
  SuggestOptions o;
  static const CandidateMode modes[] = {CandidateMode::Given, CandidateMode::Sampled,
                                        CandidateMode::Refined};
  const int mode = par.getEnum("candidates");
  if (mode < 0 || mode > 2) throw Error("candidates: unknown value " + std::to_string(mode));
  o.mode = modes[mode];
  o.top = par.getInt("top");
  o.worst_k = par.getInt("worst");
  o.energy.weights = {decimal(par.getFloat("weight_occlusion")), decimal(par.getFloat("weight_focus")),
                      decimal(par.getFloat("weight_parallax")), decimal(par.getFloat("weight_incidence"))};
  o.energy.penalty = decimal(par.getFloat("penalty"));
  o.energy.parallax_delta = decimal(par.getFloat("parallax_delta"));
  o.energy.incidence_mu = decimal(par.getFloat("incidence_mu"));
  o.energy.incidence_sigma = decimal(par.getFloat("incidence_sigma"));
  o.sampling.directions = par.getInt("directions");
  o.safety_distance = decimal(par.getFloat("safety_distance"));
  o.refine_best = par.getInt("refine_best");
  o.refine.iterations = par.getInt("refine_iterations");
  const int seed = par.getInt("seed");
  if (seed < 0) throw Error("seed must be >= 0");
  o.sampling.seed = std::uint64_t(seed);
  o.threads = par.getInt("threads");
  o.check();
  return o;
}

void require_rasters(const MeshDocument& document, int with_image, int needed, const char* why) {
  if (document.rasterList.empty())
    throw Error(std::string("the document has no raster layers; ") + why +
                ": open a MeshLab project (.mlp) with calibrated images, or import rasters and "
                "align them");
  if (with_image == 0)
    throw Error("none of the " + std::to_string(document.rasterList.size()) +
                " raster layers has an image; " + why);
  if (with_image < needed)
    throw Error("only " + std::to_string(with_image) + " of the " +
                std::to_string(document.rasterList.size()) + " raster layers has an image; " + why);
}

}  // namespace

FilterMeshNbvPlugin::FilterMeshNbvPlugin() {
  typeList << FP_COMPUTE_PRI << FP_SUGGEST_NEXT_VIEW << FP_SELECT_WORST_FACES;
  for (FilterIDType id : types()) actionList << new QAction(filterName(id), this);
}

QString FilterMeshNbvPlugin::pluginName() const { return "FilterMeshNBV"; }

QString FilterMeshNbvPlugin::filterName(FilterIDType filter) const {
  switch (filter) {
    case FP_COMPUTE_PRI: return "Compute PRI";
    case FP_SUGGEST_NEXT_VIEW: return "Suggest Next View";
    case FP_SELECT_WORST_FACES: return "Select Worst Faces";
  }
  return "";
}

QString FilterMeshNbvPlugin::filterInfo(FilterIDType filter) const {
  switch (filter) {
    case FP_COMPUTE_PRI:
      return "Photo-consistency Reconstruction Index (PRI) per face of the current mesh, from "
             "every raster layer with an image: how well the calibrated photos agree about "
             "the face. Each face is sampled on a barycentric lattice, the samples are "
             "projected into every view that sees it (vertices unoccluded, facing the camera), "
             "and the patches of every pair of views are compared; PRI is the mean error over "
             "the pairs. <b>Higher is worse.</b><br>Writes PRI as per-face quality (NaN where "
             "fewer than two views see the face or, with ncc, every pair is textureless) and "
             "colours faces from green (5th percentile) to red (95th), grey where undefined. "
             "The log gives the counts, percentiles and time." +
             parameter_list(kPriParameters) + kCitation;
    case FP_SUGGEST_NEXT_VIEW:
      return "Suggests where the next photos should be taken to fix the worst part of the "
             "mesh. The K faces with the highest PRI form the worst region; each candidate "
             "pose P is scored by the energy E(P) = sum over the region's vertices of "
             "m1 O + m2 F + m3 Par + m4 I (occlusion, focus, parallax to every existing view, "
             "incidence), and the best poses are added as raster layers without image, "
             "labelled nbv_1, nbv_2, ... (save the project to keep them). The log lists each "
             "suggestion's energy, its four terms, its centre and the worst faces it sees.<br>"
             "Existing views = raster layers with an image. MeshLab has no 4-vector parameter, "
             "so the weights m1..m4 are four parameters (the CLI's --weights m1,m2,m3,m4)." +
             parameter_list(kSuggestParameters) + kCitation;
    case FP_SELECT_WORST_FACES:
      return "Selects the K worst faces by PRI (the current per-face quality, as Compute PRI "
             "writes it), replacing the current face selection, so that you see where the "
             "reconstruction is poor. They are the faces Suggest Next View starts from." +
             parameter_list(kSelectParameters) + kCitation;
  }
  return "";
}

MeshFilterInterface::FilterClass FilterMeshNbvPlugin::getClass(QAction* action) {
  switch (ID(action)) {
    case FP_COMPUTE_PRI: return FilterClass(Quality | RasterLayer);
    case FP_SUGGEST_NEXT_VIEW: return Camera;
    case FP_SELECT_WORST_FACES: return FilterClass(Selection | Quality);
  }
  return Generic;
}

MeshFilterInterface::FILTER_ARITY FilterMeshNbvPlugin::filterArity(QAction*) const {
  return SINGLE_MESH;
}

int FilterMeshNbvPlugin::getRequirements(QAction* action) {
  return ID(action) == FP_COMPUTE_PRI ? MeshModel::MM_FACEQUALITY | MeshModel::MM_FACECOLOR
                                      : MeshModel::MM_NONE;
}

int FilterMeshNbvPlugin::getPreConditions(QAction* action) const {
  switch (ID(action)) {
    case FP_SELECT_WORST_FACES: return MeshModel::MM_FACENUMBER | MeshModel::MM_FACEQUALITY;
    default: return MeshModel::MM_FACENUMBER;
  }
}

int FilterMeshNbvPlugin::postCondition(QAction* action) const {
  switch (ID(action)) {
    case FP_COMPUTE_PRI: return MeshModel::MM_FACEQUALITY | MeshModel::MM_FACECOLOR;
    case FP_SELECT_WORST_FACES: return MeshModel::MM_FACEFLAGSELECT;
    default: return MeshModel::MM_NONE;  // adds raster (and mesh) layers only
  }
}

void FilterMeshNbvPlugin::initParameterSet(QAction* action, MeshDocument&, RichParameterList& par) {
  // Defaults come from the core's option structs, so they cannot drift.
  const PriOptions pri;
  const SuggestOptions sug;
  auto label = [](const auto& table, const char* name) { return QString(help(table, name).label); };
  auto tip = [](const auto& table, const char* name) { return QString(help(table, name).help); };
#define MESHNBV_TEXT(table, name) label(table, name), tip(table, name)
  switch (ID(action)) {
    case FP_COMPUTE_PRI: {
      const auto& t = kPriParameters;
      par.addParam(RichEnum("measure", pri.measure == Measure::NCC ? 1 : 0, QStringList{"ssd", "ncc"},
                            MESHNBV_TEXT(t, "measure")));
      par.addParam(RichInt("samples_per_side", pri.samples_per_side, MESHNBV_TEXT(t, "samples_per_side")));
      par.addParam(RichInt("max_views_per_face", pri.max_views_per_face,
                           MESHNBV_TEXT(t, "max_views_per_face")));
      par.addParam(RichFloat("max_incidence_angle", float(pri.max_incidence_angle),
                             MESHNBV_TEXT(t, "max_incidence_angle")));
      par.addParam(RichFloat("edge_margin", float(pri.edge_margin), MESHNBV_TEXT(t, "edge_margin")));
      par.addParam(RichBool("check_interior_occlusion", pri.check_interior_occlusion,
                            MESHNBV_TEXT(t, "check_interior_occlusion")));
      par.addParam(RichBool("color", pri.color, MESHNBV_TEXT(t, "color")));
      par.addParam(RichInt("threads", pri.threads, MESHNBV_TEXT(t, "threads")));
      break;
    }
    case FP_SUGGEST_NEXT_VIEW: {
      const auto& t = kSuggestParameters;
      par.addParam(RichEnum("candidates", int(sug.mode), QStringList{"given", "sampled", "refined"},
                            MESHNBV_TEXT(t, "candidates")));
      par.addParam(RichInt("top", sug.top, MESHNBV_TEXT(t, "top")));
      par.addParam(RichInt("worst", sug.worst_k, MESHNBV_TEXT(t, "worst")));
      par.addParam(RichFloat("weight_occlusion", float(sug.energy.weights[0]), MESHNBV_TEXT(t, "weight_occlusion")));
      par.addParam(RichFloat("weight_focus", float(sug.energy.weights[1]), MESHNBV_TEXT(t, "weight_focus")));
      par.addParam(RichFloat("weight_parallax", float(sug.energy.weights[2]), MESHNBV_TEXT(t, "weight_parallax")));
      par.addParam(RichFloat("weight_incidence", float(sug.energy.weights[3]), MESHNBV_TEXT(t, "weight_incidence")));
      par.addParam(RichFloat("penalty", float(sug.energy.penalty), MESHNBV_TEXT(t, "penalty")));
      par.addParam(RichFloat("parallax_delta", float(sug.energy.parallax_delta), MESHNBV_TEXT(t, "parallax_delta")));
      par.addParam(RichFloat("incidence_mu", float(sug.energy.incidence_mu), MESHNBV_TEXT(t, "incidence_mu")));
      par.addParam(RichFloat("incidence_sigma", float(sug.energy.incidence_sigma), MESHNBV_TEXT(t, "incidence_sigma")));
      par.addParam(RichInt("directions", sug.sampling.directions, MESHNBV_TEXT(t, "directions")));
      par.addParam(RichFloat("safety_distance", float(sug.safety_distance), MESHNBV_TEXT(t, "safety_distance")));
      par.addParam(RichInt("refine_best", sug.refine_best, MESHNBV_TEXT(t, "refine_best")));
      par.addParam(RichInt("refine_iterations", sug.refine.iterations, MESHNBV_TEXT(t, "refine_iterations")));
      par.addParam(RichInt("seed", int(sug.sampling.seed), MESHNBV_TEXT(t, "seed")));
      par.addParam(RichInt("threads", sug.threads, MESHNBV_TEXT(t, "threads")));
      par.addParam(RichBool("use_face_quality", true, MESHNBV_TEXT(t, "use_face_quality")));
      par.addParam(RichBool("add_frustum_layer", false, MESHNBV_TEXT(t, "add_frustum_layer")));
      break;
    }
    case FP_SELECT_WORST_FACES:
      par.addParam(RichInt("worst", sug.worst_k, MESHNBV_TEXT(kSelectParameters, "worst")));
      break;
  }
#undef MESHNBV_TEXT
}

bool FilterMeshNbvPlugin::applyFilter(QAction* action, MeshDocument& document,
                                      const RichParameterList& par, vcg::CallBackPos* callback) {
  const FilterIDType id = ID(action);
  std::string reason;
  try {
    switch (id) {
      case FP_COMPUTE_PRI: computePri(document, par, callback); return true;
      case FP_SUGGEST_NEXT_VIEW: suggestNextView(document, par, callback); return true;
      case FP_SELECT_WORST_FACES: selectWorstFaces(document, par); return true;
    }
    reason = "unknown filter";
  } catch (const std::exception& e) {  // meshnbv::Error (and Cancelled) included
    reason = e.what();
  }
  // meshlabserver prints only the log on failure: the reason goes there too.
  errorMessage = filterName(id) + " failed: " + QString::fromStdString(reason);
  logLine(errorMessage.toStdString());
  return false;
}

void FilterMeshNbvPlugin::logLine(const std::string& line) { Log(line); }

void FilterMeshNbvPlugin::computePri(MeshDocument& document, const RichParameterList& par,
                                     vcg::CallBackPos* callback) {
  MeshModel* model = document.mm();
  if (!model) throw Error("no current mesh layer");
  const PriOptions options = pri_options(par);
  meshlab::DocumentScene ds = meshlab::scene_from_document(document, *model);
  require_rasters(document, ds.views_with_image, 2, "PRI compares the photos of at least two");
  Progress progress(callback, "Compute PRI");
  const PriResult r = compute_pri(ds.scene, options, progress.callback());

  const TriangleMesh coloured = mesh_with_pri(ds.scene.mesh, r);
  model->updateDataMask(MeshModel::MM_FACEQUALITY | MeshModel::MM_FACECOLOR);
  for (std::size_t f = 0; f < ds.faces.size(); ++f) {
    ds.faces[f]->Q() = r.pri[f];
    const Rgb8& c = coloured.face_colors[f];
    ds.faces[f]->C() = vcg::Color4b(c[0], c[1], c[2], 255);
  }

  const PriSummary s = summarize_pri(r, 1);
  std::ostringstream line;
  line << "Compute PRI (" << measure_name(options.measure) << "): " << s.faces << " faces: "
       << s.observed << " observed, " << s.unobserved << " unobserved, " << s.textureless
       << " textureless; " << r.views_used << " raster images; " << format(r.seconds) << " s";
  logLine(line.str());
  if (!s.percentiles.empty()) {
    std::ostringstream pct;
    pct << "PRI percentiles:";
    for (const auto& [p, v] : s.percentiles) pct << " p" << int(p) << " " << format(v);
    pct << "; worst face " << s.worst[0].face << " (PRI " << format(s.worst[0].pri) << ", "
        << s.worst[0].views << " views)";
    logLine(pct.str());
  }
  logLine("face quality = PRI (NaN where undefined); face colour green (p5) .. red (p95), grey "
          "where undefined");
}

void FilterMeshNbvPlugin::selectWorstFaces(MeshDocument& document, const RichParameterList& par) {
  MeshModel* model = document.mm();
  if (!model) throw Error("no current mesh layer");
  if (!model->hasDataMask(MeshModel::MM_FACEQUALITY))
    throw Error("the mesh layer '" + model->label().toStdString() +
                "' has no face quality: run Compute PRI first (or open a mesh saved with PRI as "
                "face quality, e.g. by `meshnbv pri`)");
  const int k = par.getInt("worst");
  if (k < 1) throw Error("worst must be >= 1");
  const meshlab::ModelMesh mesh = meshlab::mesh_from_model(*model);
  const WorstRegion region = worst_region(mesh.mesh, meshlab::face_quality(mesh), k);
  vcg::tri::UpdateSelection<CMeshO>::FaceClear(model->cm);
  for (int f : region.faces) mesh.faces[std::size_t(f)]->SetS();
  model->cm.sfn = int(region.faces.size());
  const float hi = mesh.faces[std::size_t(region.faces.front())]->cQ();
  const float lo = mesh.faces[std::size_t(region.faces.back())]->cQ();
  logLine("Select Worst Faces: selected " + std::to_string(region.faces.size()) + " of " +
          std::to_string(mesh.faces.size()) + " faces, PRI from " + format(lo) + " to " + format(hi));
}

void FilterMeshNbvPlugin::suggestNextView(MeshDocument& document, const RichParameterList& par,
                                          vcg::CallBackPos* callback) {
  MeshModel* model = document.mm();
  if (!model) throw Error("no current mesh layer");
  const SuggestOptions options = suggest_options(par);
  const bool have_quality = model->hasDataMask(MeshModel::MM_FACEQUALITY);
  const bool compute = !(par.getBool("use_face_quality") && have_quality);
  meshlab::DocumentScene ds = meshlab::scene_from_document(document, *model);
  require_rasters(document, ds.views_with_image, compute ? 2 : 1,
                  "the existing photos set the candidates' intrinsics, distance and parallax");
  if (options.mode == CandidateMode::Given && ds.views_with_image == int(ds.scene.views.size()))
    throw Error("candidates = given needs raster layers without an image (the candidate poses); "
                "every raster layer has one");
  Progress progress(callback, "Suggest Next View");

  std::vector<float> pri;
  if (compute) {
    PriOptions pri_defaults;
    pri_defaults.threads = options.threads;
    pri = compute_pri(ds.scene, pri_defaults, progress.callback()).pri;
    logLine(std::string("Suggest Next View: PRI computed with Compute PRI's defaults (") +
            (have_quality ? "use_face_quality is off" : "the mesh has no face quality") + ")");
  } else {
    pri.reserve(ds.faces.size());
    for (const CFaceO* f : ds.faces) pri.push_back(float(f->cQ()));
    logLine("Suggest Next View: PRI = the mesh's face quality");
  }
  const SuggestResult r = suggest_views(ds.scene, pri, options, {}, progress.callback());
  for (const Suggestion& s : r.suggestions) {
    RasterModel* raster = document.addNewRaster();
    raster->currentPlane = nullptr;  // MeshLab leaves it uninitialised for a raster without plane
    raster->setLabel(QString::fromStdString(s.label));
    raster->shot = meshlab::shot_from_camera(s.camera);
    const Vec3 c = s.camera.center();
    std::ostringstream line;
    line << s.label << ": energy " << format(s.energy.total) << " (occlusion "
         << format(s.energy.occlusion) << ", focus " << format(s.energy.focus) << ", parallax "
         << format(s.energy.parallax) << ", incidence " << format(s.energy.incidence)
         << "), centre (" << format(c.x()) << ", " << format(c.y()) << ", " << format(c.z())
         << "), sees " << s.seen_faces.size() << "/" << r.regions[std::size_t(s.region)].faces.size()
         << " worst faces of region " << s.region << " [" << s.source << "]";
    logLine(line.str());
  }
  std::ostringstream summary;
  summary << "Suggest Next View (" << candidate_mode_name(options.mode) << "): "
          << r.suggestions.size() << " suggestions from " << r.candidates_evaluated
          << " candidate evaluations";
  if (r.candidates_generated)
    summary << " (" << r.candidates_generated << " sampled, " << r.rejected_inside
            << " rejected inside the mesh, " << r.rejected_too_close << " too close)";
  summary << "; " << format(r.seconds) << " s";
  logLine(summary.str());

  if (par.getBool("add_frustum_layer") && !r.suggestions.empty()) {
    MeshModel* frustums = document.addNewMesh("", "nbv_frustums", false);
    meshlab::fill_model(frustum_mesh(r), *frustums, "rank");
    logLine("Suggest Next View: added the mesh layer 'nbv_frustums' (" +
            std::to_string(frustums->cm.fn) + " faces)");
  }
}
