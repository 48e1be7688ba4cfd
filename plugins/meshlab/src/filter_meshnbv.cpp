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
#include "meshnbv/options.h"
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

// The parameters that belong to the plugin alone (how it takes its input
// and shows its output); every other parameter is an option of the core's
// tables (meshnbv/options.h), with its name, default, range and help.
const ParameterHelp kSuggestOwnParameters[] = {
    {"use_face_quality", "Use face quality as PRI", "else PRI is computed with defaults",
     "Take PRI from the mesh's per-face quality, as Compute PRI leaves it (NaN = unobserved). "
     "Off, or when the mesh has no face quality: PRI is computed with Compute PRI's defaults."},
    {"add_frustum_layer", "Add frustum layer", "also add a mesh layer of the suggestions' frustums",
     "Also add a mesh layer 'nbv_frustums': one pyramid per suggestion (apex at the camera "
     "centre), coloured from red (first) to yellow, face quality = rank."},
};

// The help MeshLab shows: the table's text and the accepted range.
template <class Options>
QString tooltip(const OptionSpec<Options>& spec) {
  std::string text = spec.help;
  if (spec.type == OptionType::Int || spec.type == OptionType::Real)
    text += " (" + spec.range.describe() + ")";
  return QString::fromStdString(text + ".");
}

// One parameter per option of `table`, at the struct's default.
template <class Options>
void add_table_parameters(RichParameterList& par, const OptionTable<Options>& table,
                          const std::vector<std::string>& only = {}) {
  const Options defaults;
  for (const OptionSpec<Options>& s : table) {
    if (!only.empty() && std::find(only.begin(), only.end(), s.name) == only.end()) continue;
    const QString name = QString::fromStdString(s.name), label = QString::fromStdString(s.label);
    const OptionValue v = s.get(defaults);
    switch (s.type) {
      case OptionType::Bool: par.addParam(RichBool(name, std::get<bool>(v), label, tooltip(s))); break;
      case OptionType::Int:
        par.addParam(RichInt(name, int(std::get<std::int64_t>(v)), label, tooltip(s)));
        break;
      case OptionType::Real:
        par.addParam(RichFloat(name, float(std::get<double>(v)), label, tooltip(s)));
        break;
      case OptionType::Choice: {
        QStringList words;
        for (const auto& c : s.choices) words << QString::fromStdString(c);
        par.addParam(RichEnum(name, words.indexOf(QString::fromStdString(std::get<std::string>(v))),
                              words, label, tooltip(s)));
        break;
      }
    }
  }
}

// The options of `table` from the filter's parameters, checked (one-line
// errors naming the parameter and its range).
template <class Options>
Options table_options(const RichParameterList& par, const OptionTable<Options>& table,
                      const std::vector<std::string>& only = {}) {
  Options o;
  for (const OptionSpec<Options>& s : table) {
    if (!only.empty() && std::find(only.begin(), only.end(), s.name) == only.end()) continue;
    const QString name = QString::fromStdString(s.name);
    switch (s.type) {
      case OptionType::Bool: s.set(o, par.getBool(name)); break;
      case OptionType::Int: s.set(o, std::int64_t(par.getInt(name))); break;
      case OptionType::Real: s.set(o, decimal(par.getFloat(name))); break;
      case OptionType::Choice: {
        const int index = par.getEnum(name);
        if (index < 0 || std::size_t(index) >= s.choices.size())
          throw Error(s.name + ": unknown value " + std::to_string(index));
        s.set(o, s.choices[std::size_t(index)]);
        break;
      }
    }
    const std::string problem = s.problem(s.get(o));
    if (!problem.empty()) throw Error(problem);
  }
  return o;
}

// One compact paragraph: MeshLab shows the info above the parameters.
template <class Options>
QString parameter_list(const OptionTable<Options>& table, const std::vector<std::string>& only = {},
                       const std::vector<ParameterHelp>& own = {}) {
  QStringList items;
  for (const auto& s : table)
    if (only.empty() || std::find(only.begin(), only.end(), s.name) != only.end())
      items << QString("<b>%1</b>: %2")
                   .arg(QString::fromStdString(s.name))
                   .arg(QString::fromStdString(s.label).toHtmlEscaped());
  for (const ParameterHelp& p : own)
    items << QString("<b>%1</b>: %2").arg(p.name).arg(QString(p.brief).toHtmlEscaped());
  return "<p>Parameters (each explained in its tooltip and under Help): " + items.join("; ") +
         ".</p>";
}

// Select Worst Faces takes the suggestion's worst set size, under its name.
const std::vector<std::string> kSelectOptions = {"worst_faces"};

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
  PriOptions o = table_options(par, pri_option_table());
  o.check();
  return o;
}

SuggestOptions suggest_options(const RichParameterList& par) {
  SuggestOptions o = table_options(par, suggest_option_table());
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
             parameter_list(pri_option_table()) + kCitation;
    case FP_SUGGEST_NEXT_VIEW:
      return "Suggests where the next photos should be taken to fix the worst part of the "
             "mesh. The K faces with the highest PRI form the worst region; each candidate "
             "pose P is scored by the energy E(P) = sum over the region's vertices of "
             "m1 O + m2 F + m3 Par + m4 I (occlusion, focus, parallax to every existing view, "
             "incidence), and the best poses are added as raster layers without image, "
             "labelled nbv_1, nbv_2, ... (save the project to keep them). The log lists each "
             "suggestion's energy, its four terms, its centre and the worst faces it sees.<br>"
             "Existing views = raster layers with an image." +
             parameter_list(suggest_option_table(), {},
                            {std::begin(kSuggestOwnParameters), std::end(kSuggestOwnParameters)}) +
             kCitation;
    case FP_SELECT_WORST_FACES:
      return "Selects the K worst faces by PRI (the current per-face quality, as Compute PRI "
             "writes it), replacing the current face selection, so that you see where the "
             "reconstruction is poor. They are the faces Suggest Next View starts from." +
             parameter_list(suggest_option_table(), kSelectOptions) + kCitation;
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
  // Names, defaults, ranges and help come from the core's option tables, so
  // that they cannot drift from the other front ends (docs/options.md).
  switch (ID(action)) {
    case FP_COMPUTE_PRI: add_table_parameters(par, pri_option_table()); break;
    case FP_SUGGEST_NEXT_VIEW: {
      add_table_parameters(par, suggest_option_table());
      for (const ParameterHelp& p : kSuggestOwnParameters)
        par.addParam(RichBool(p.name, std::string(p.name) == "use_face_quality", p.label, p.help));
      break;
    }
    case FP_SELECT_WORST_FACES:
      add_table_parameters(par, suggest_option_table(), kSelectOptions);
      break;
  }
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
  line << "Compute PRI (" << measure_name(options.measure) << ", " << measure_unit(options.measure)
       << "): " << s.faces << " faces: " << s.observed << " observed, " << s.unobserved
       << " unobserved, " << s.textureless << " textureless; " << r.views_used
       << " raster images; " << format(r.seconds) << " s";
  logLine(line.str());
  const PriEvidence e = pri_evidence(r);
  std::ostringstream evidence;
  evidence << "PRI evidence: " << e.two_views << " of " << e.observed
           << " observed faces rest on 2 views; " << e.low_texture << " on low texture (below "
           << format(e.low_texture_below) << ")";
  if (!e.pairs_percentiles.empty())
    evidence << "; median " << format(e.pairs_percentiles[3].second) << " comparisons, "
             << format(e.samples_percentiles[3].second) << " samples, texture "
             << format(e.texture_percentiles.empty() ? 0.0 : e.texture_percentiles[3].second);
  logLine(evidence.str());
  if (!s.percentiles.empty()) {
    std::ostringstream pct;
    pct << "PRI percentiles:";
    for (const auto& [p, v] : s.percentiles) pct << " p" << int(p) << " " << format(v);
    const auto w = std::size_t(s.worst[0].face);
    pct << "; worst face " << s.worst[0].face << " (PRI " << format(s.worst[0].pri) << ", "
        << s.worst[0].views << " views, " << r.pri_pairs[w] << " comparisons, texture "
        << format(r.pri_texture[w]) << ")";
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
  const int k = table_options(par, suggest_option_table(), kSelectOptions).worst_k;
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
    line << s.label << ": energy " << format(s.energy.total) << " (" << energy_terms_text(s.energy)
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
            << " rejected inside the mesh, " << r.rejected_too_close << " too close, "
            << r.rejected_below_ground << " below the ground)";
  summary << "; " << format(r.seconds) << " s";
  logLine(summary.str());

  if (par.getBool("add_frustum_layer") && !r.suggestions.empty()) {
    MeshModel* frustums = document.addNewMesh("", "nbv_frustums", false);
    meshlab::fill_model(frustum_mesh(r), *frustums, "rank");
    logLine("Suggest Next View: added the mesh layer 'nbv_frustums' (" +
            std::to_string(frustums->cm.fn) + " faces)");
  }
}
