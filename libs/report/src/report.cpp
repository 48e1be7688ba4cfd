#include "meshnbv/report.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "meshnbv/error.h"
#include "meshnbv/options.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/results.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/renderer.h"
#include "meshnbv/visualize.h"
#include "base64.h"
#include "viewer_data.h"

namespace fs = std::filesystem;

namespace meshnbv {
namespace {

using report_detail::base64;

const Rgb8 kExisting{40, 90, 230};
const Rgb8 kHighlight{255, 0, 255};

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::string fixed(double v, int digits = 3) {
  std::ostringstream ss;
  ss.setf(std::ios::fixed);
  ss.precision(digits);
  ss << v;
  return ss.str();
}

std::string general(double v) {
  std::ostringstream ss;
  ss.precision(4);
  ss << v;
  return ss.str();
}

// A camera with the same pose and field of view, `width` pixels wide.
PinholeCamera scaled(const PinholeCamera& c, int width) {
  if (c.width == width) return c;
  PinholeCamera s = c;
  const double k = double(width) / c.width;
  s.width = width;
  s.height = std::max(2, int(std::lround(c.height * k)));
  s.fx *= k;
  s.fy *= k;
  s.cx = (c.cx + 0.5) * k - 0.5;
  s.cy = (c.cy + 0.5) * k - 0.5;
  return s;
}

// The 5th and 95th percentiles: the ends of the colour scale.
std::pair<double, double> colour_range(const PriSummary& summary) {
  double lo = 0, hi = 1;
  for (const auto& [p, v] : summary.percentiles) {
    if (p == 5.0) lo = v;
    if (p == 95.0) hi = v;
  }
  return {lo, hi};
}

// Saves a picture into the report's folder and lists it.
void save_picture(const Image& img, const std::string& folder, const std::string& name, ReportFiles* out) {
  const std::string path = (fs::path(folder) / name).string();
  img.save(path);
  out->pictures.push_back(path);
}

// What the overviews draw over the mesh (existing cameras in blue,
// suggestions red..yellow), the points that frame the mesh alone, and those
// that frame the whole rig.
struct OverviewContent {
  std::vector<FrustumOverlay> overlays;
  std::vector<Vec3> mesh_points;  // the mesh's bounding box: overview_1/2 (the mesh fills them)
  std::vector<Vec3> rig_points;   // ... and every camera centre: cameras.png
};

OverviewContent overview_content(const Scene& scene, const SuggestResult& sug) {
  OverviewContent oc;
  const double diag = scene.mesh.bounding_box().diagonal();
  for (const Vec3& c : scene.mesh.bounding_box().corners()) oc.mesh_points.push_back(c);
  oc.rig_points = oc.mesh_points;
  for (const auto& v : scene.views) {
    if (!v.has_image() || !v.used) continue;
    oc.overlays.push_back({v.camera, kExisting, 0.06 * diag * v.camera.fx / v.camera.width, 1, ""});
    oc.rig_points.push_back(v.camera.center());
  }
  const std::size_t n_sug = sug.suggestions.size();
  for (std::size_t i = 0; i < n_sug; ++i) {
    const Suggestion& s = sug.suggestions[i];
    const double t = n_sug > 1 ? double(i) / double(n_sug - 1) : 0.0;
    const double depth = 0.2 * std::max(1e-9, s.camera.depth(s.look_at));
    oc.overlays.push_back({s.camera, Rgb8{255, std::uint8_t(std::lround(200 * t)), 0}, depth, 3, s.label});
    oc.rig_points.push_back(s.camera.center());
  }
  return oc;
}

// An embedded picture of the report's folder, with its caption and link.
void write_picture(std::ostream& h, const std::string& folder, const std::string& name,
                   const std::string& alt) {
  const std::string data = io::read_file((fs::path(folder) / name).string());
  h << "<figure><img alt=\"" << html_escape(alt) << "\" src=\"data:image/png;base64," << base64(data)
    << "\"><figcaption>" << html_escape(alt) << " (<a href=\"" << name << "\">" << name << "</a>)</figcaption></figure>\n";
}

void write_head(std::ostream& h, const ReportInputs& in) {
  const Scene& scene = *in.scene;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>MeshNBV report</title>\n<style>"
       "body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}"
       "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}"
       "th{background:#eee}td.l,th.l{text-align:left}figure{display:inline-block;margin:0.5em}"
       "img{max-width:100%;border:1px solid #ccc}.row{display:flex;flex-wrap:wrap}"
       "</style></head><body>\n";
  h << "<h1>MeshNBV report</h1>\n<p>Scene <code>" << html_escape(in.scene_path) << "</code>: "
    << scene.mesh.num_faces() << " faces, " << scene.views.size() << " views ("
    << in.pri->views_used << " with images used). Method: Morreale, Romanoni, Matteucci, "
    << "<i>Predicting the Next Best View for 3D Mesh Refinement</i> (2018).</p>\n";
}

// What the observed faces' PRI rests on (pri_evidence).
void write_evidence(std::ostream& h, const PriEvidence& e) {
  h << "<p>What PRI rests on: of " << e.observed << " observed faces, " << e.two_views
    << " rest on 2 views only and " << e.low_texture << " on low texture (standard deviation of the samples "
    << "below " << general(e.low_texture_below) << " of the intensity range); a high PRI there is weak "
    << "evidence.</p>\n";
  if (e.pairs_percentiles.empty()) return;
  h << "<table><tr><th class=l>per observed face</th>";
  for (const auto& [p, v] : e.pairs_percentiles) h << "<th>p" << int(p) << "</th>";
  h << "</tr>";
  const std::pair<const char*, const std::vector<std::pair<double, double>>*> rows[] = {
      {"comparisons (pri_pairs)", &e.pairs_percentiles},
      {"samples per view (pri_samples)", &e.samples_percentiles},
      {"texture (pri_texture)", &e.texture_percentiles}};
  for (const auto& [name, pct] : rows) {
    if (pct->empty()) continue;
    h << "<tr><td class=l>" << name << "</td>";
    for (const auto& [p, v] : *pct) h << "<td>" << general(v) << "</td>";
    h << "</tr>";
  }
  h << "</table>\n";
}

void write_pri_section(std::ostream& h, const std::string& folder, const PriSummary& summary,
                       std::pair<double, double> range, Measure measure, const PriEvidence& evidence) {
  h << "<h2>Where the mesh is poorly reconstructed</h2>\n<p>PRI measure <b>" << measure_name(measure)
    << "</b>, in " << html_escape(measure_unit(measure)) << ". Faces coloured by PRI from green (best, "
    << general(range.first) << ") to red (worst, " << general(range.second) << "; 5th and 95th percentiles), grey where no two views "
    << "see a face. Blue: the existing cameras. Red to yellow: the suggested next views, best first. The "
    << "overviews frame the mesh (frustums where they fall); the last picture shows the whole rig.</p>\n<div class=\"row\">\n";
  write_picture(h, folder, "overview_1.png", "Overview from one side");
  write_picture(h, folder, "overview_2.png", "Overview from the other side");
  write_picture(h, folder, "cameras.png", "The mesh among every camera");
  h << "</div>\n<table><tr><th class=l>faces</th><th>observed</th><th>unobserved</th><th>textureless</th></tr><tr><td class=l>"
    << summary.faces << "</td><td>" << summary.observed << "</td><td>" << summary.unobserved << "</td><td>"
    << summary.textureless << "</td></tr></table>\n<table><tr>";
  for (const auto& [p, v] : summary.percentiles) h << "<th>p" << int(p) << "</th>";
  h << "</tr><tr>";
  for (const auto& [p, v] : summary.percentiles) h << "<td>" << general(v) << "</td>";
  h << "</tr></table>\n";
  write_evidence(h, evidence);
  write_picture(h, folder, "histogram.png", "PRI histogram");
}

// The interactive view: the viewer builds itself in #meshnbv-viewer from
// viewer/report_data.js (write_viewer).
void write_viewer_section(std::ostream& h, const report_detail::ViewerFiles& v) {
  h << "<h2>3-D view</h2>\n<p>Drag to turn, scroll to zoom, right-drag to pan. Click a suggestion (in the list or "
       "its label) to look through it with its pose and field of view, a region to frame it, a face to read its "
       "values. ";
  if (v.decimated)
    h << "Display mesh decimated from " << v.original_faces << " to " << v.display_faces
      << " faces (each display face shows the area-weighted mean PRI of the faces it stands for; a click reports "
         "the original face nearest the point).";
  else
    h << "Display mesh: the " << v.original_faces << " faces of the mesh.";
  if (v.interaction_faces > 0)
    h << " While the camera moves the view draws a coarser copy of " << v.interaction_faces
      << " faces (the same decimation, each face the area-weighted mean PRI of the faces it stands for), and the "
      << v.display_faces << " display faces again as soon as it rests.";
  h << "</p>\n<div id=\"meshnbv-viewer\"><noscript>The 3-D view needs JavaScript.</noscript></div>\n"
    << "<script src=\"" << v.folder << "/report_data.js\"></script>\n<script src=\"" << v.folder
    << "/meshnbv_viewer.js\"></script>\n";
}

void write_suggestions_section(std::ostream& h, const std::string& folder, const SuggestResult& sug,
                               int n_views) {
  // The terms of the energy that scored them: the paper's four, or the
  // whole-mesh energy's two (shares of the mesh's deficit, in percent).
  const bool whole_mesh = !sug.suggestions.empty() && sug.suggestions.front().energy.whole_mesh;
  h << "<h2>Where to take the next photos</h2>\n<table><tr><th>rank</th><th class=l>label</th><th class=l>from</th>"
       "<th>region</th><th>energy</th>"
    << (whole_mesh ? "<th>refinement (%)</th><th>exploration (%)</th>"
                   : "<th>occlusion</th><th>focus</th><th>parallax</th><th>incidence</th>")
    << "<th>worst faces seen</th><th class=l>centre</th></tr>\n";
  for (const auto& s : sug.suggestions) {
    const Vec3 c = s.camera.center();
    h << "<tr><td>" << s.rank << "</td><td class=l>" << html_escape(s.label) << "</td><td class=l>"
      << html_escape(s.source) << "</td><td>" << s.region << "</td><td>";
    if (whole_mesh)
      h << fixed(100 * s.energy.total, 2) << "</td><td>" << fixed(100 * s.energy.refinement, 2) << "</td><td>"
        << fixed(100 * s.energy.exploration, 2) << "</td><td>";
    else
      h << fixed(s.energy.total, 2) << "</td><td>" << fixed(s.energy.occlusion, 2) << "</td><td>"
        << fixed(s.energy.focus, 2) << "</td><td>" << fixed(s.energy.parallax, 2) << "</td><td>"
        << fixed(s.energy.incidence, 2) << "</td><td>";
    h << s.seen_faces.size() << " / " << sug.regions[std::size_t(s.region)].faces.size() << "</td><td class=l>("
      << fixed(c.x()) << ", " << fixed(c.y()) << ", " << fixed(c.z()) << ")</td></tr>\n";
  }
  h << "</table>\n<p>" << sug.candidates_evaluated << " candidate evaluations";
  if (sug.candidates_generated)
    h << "; " << sug.candidates_generated << " poses sampled, " << sug.rejected_inside << " rejected inside the mesh, "
      << sug.rejected_too_close << " nearer than the safety distance, " << sug.rejected_below_ground
      << " below the ground";
  h << ".</p>\n<div class=\"row\">\n";
  for (int i = 0; i < n_views; ++i) {
    const auto& s = sug.suggestions[std::size_t(i)];
    write_picture(h, folder, s.label + ".png", s.label + " as its camera would see the mesh; worst faces in magenta");
  }
  h << "</div>\n";
}

void write_mission_section(std::ostream& h, const ReportMission& m) {
  h << "<h2>Flying the suggested views</h2>\n";
  if (!m.unavailable.empty()) {
    h << "<p>No drone mission: " << html_escape(m.unavailable) << ".</p>\n";
    return;
  }
  double minutes = 0;
  int photos = 0;
  for (const ReportFlight& f : m.flights) minutes += f.minutes, photos += f.photos;
  h << "<p>Georeference: " << html_escape(m.georef) << ". Take-off at " << html_escape(m.takeoff) << ". "
    << photos << " photos in " << m.flights.size() << " flight(s), " << fixed(minutes, 1)
    << " min in all; files (KML, DJI WPML KMZ, Litchi CSV, GeoJSON, CSV) in <a href=\""
    << html_escape(m.folder) << "/\">" << html_escape(m.folder) << "/</a>.</p>\n";
  h << "<figure>" << m.svg << "<figcaption>The flights from above (north up) over the mesh, keep-out "
       "volumes in red, take-off point in black</figcaption></figure>\n";
  h << "<table><tr><th>flight</th><th>photos</th><th>length (m)</th><th>minutes</th><th>detours</th></tr>";
  for (std::size_t k = 0; k < m.flights.size(); ++k) {
    const ReportFlight& f = m.flights[k];
    h << "<tr><td>" << k + 1 << "</td><td>" << f.photos << "</td><td>" << fixed(f.length_m, 1) << "</td><td>"
      << fixed(f.minutes, 1) << "</td><td>" << f.detours << "</td></tr>";
  }
  h << "</table>\n";
  if (!m.notes.empty()) {
    h << "<ul>";
    for (const std::string& n : m.notes) h << "<li>" << html_escape(n) << "</li>";
    h << "</ul>\n";
  }
}

// Every option of the two tables, under its one name (options.h).
template <class Options>
void write_option_rows(std::ostream& h, const char* what, const Options& options,
                       const OptionTable<Options>& table) {
  h << "<table><tr><th class=l>" << what << "</th><th class=l>value</th></tr>";
  for (const auto& spec : table)
    h << "<tr><td class=l>" << html_escape(spec.name) << "</td><td class=l>"
      << html_escape(option_value_text(spec.get(options))) << "</td></tr>";
  h << "</table>\n";
}

void write_inputs_section(std::ostream& h, const ReportInputs& in) {
  h << "<h2>Inputs, options and timings</h2>\n";
  write_option_rows(h, "PRI option", in.pri_options, pri_option_table());
  write_option_rows(h, "suggestion option", in.suggest_options, suggest_option_table());
  h << "<table><tr><th class=l>step</th><th>seconds</th></tr>";
  for (const auto& [step, sec] : in.timings) h << "<tr><td class=l>" << html_escape(step) << "</td><td>" << fixed(sec) << "</td></tr>";
  h << "</table>\n<table><tr><th class=l>file</th><th class=l>what</th></tr>";
  for (const auto& [file, what] : in.files) h << "<tr><td class=l><a href=\"" << html_escape(file) << "\">" << html_escape(file) << "</a></td><td class=l>" << html_escape(what) << "</td></tr>";
  h << "</table>\n";
}

}  // namespace

ReportFiles write_report(const ReportInputs& in, const std::string& folder,
                         const ProgressCallback& progress) {
  if (!in.scene || !in.pri || !in.suggestions) throw Error("report: missing scene, PRI or suggestions");
  fs::create_directories(folder);
  const Scene& scene = *in.scene;
  const SuggestResult& sug = *in.suggestions;
  const TriangleMesh coloured = mesh_with_pri(scene.mesh, *in.pri);
  const RayCaster caster(scene.mesh);
  RenderOptions ro;
  ro.background = Vec3(1.0, 1.0, 1.0);
  ro.ambient = 0.55;
  ro.diffuse = 0.45;
  const PriSummary summary = summarize_pri(*in.pri, 10);
  const auto [lo, hi] = colour_range(summary);
  ReportFiles out;

  // Overviews: the mesh by PRI framed on the mesh, then on the whole rig.
  const OverviewContent oc = overview_content(scene, sug);
  const RenderInputs coloured_inputs{&coloured, &caster, nullptr, nullptr, &coloured.face_colors};
  struct Overview {
    std::string name;
    const std::vector<Vec3>* frame;
    double azimuth;
  };
  const Overview overviews[3] = {{"overview_1.png", &oc.mesh_points, 35.0},
                                 {"overview_2.png", &oc.mesh_points, 215.0},
                                 {"cameras.png", &oc.rig_points, 35.0}};
  for (int k = 0; k < 3; ++k) {
    const Overview& o = overviews[k];
    const PinholeCamera viewer = overview_camera(*o.frame, o.azimuth, 35.0, in.image_width, in.image_height);
    Image img = render(coloured_inputs, viewer, ro);
    draw_frustums(img, viewer, oc.overlays);
    draw_color_scale(img, lo, hi, "PRI (" + measure_name(in.pri_options.measure) + ")");
    save_picture(img, folder, o.name, &out);
    report_progress(progress, 0.1 * (k + 1), "report");
  }
  const report_detail::ViewerFiles viewer = report_detail::write_viewer(in, folder, {lo, hi});
  report_progress(progress, 0.4, "report");

  // The top suggestions as their cameras would see the mesh, worst faces in magenta.
  const int n_views = std::min<int>(in.suggestion_views, int(sug.suggestions.size()));
  for (int i = 0; i < n_views; ++i) {
    const Suggestion& s = sug.suggestions[std::size_t(i)];
    TriangleMesh highlighted = coloured;
    for (int f : sug.regions[std::size_t(s.region)].faces) highlighted.face_colors[std::size_t(f)] = kHighlight;
    const RenderInputs hin{&highlighted, &caster, nullptr, nullptr, &highlighted.face_colors};
    save_picture(render(hin, scaled(s.camera, 640), ro), folder, s.label + ".png", &out);
    report_progress(progress, 0.4 + 0.5 * (i + 1) / std::max(1, n_views), "report");
  }
  save_picture(histogram_image(in.pri->pri, 30, 640, 300, "PRI of observed faces (" + measure_name(in.pri_options.measure) + ")"),
               folder, "histogram.png", &out);

  // The page.
  std::ostringstream h;
  write_head(h, in);
  write_viewer_section(h, viewer);
  write_pri_section(h, folder, summary, {lo, hi}, in.pri_options.measure, pri_evidence(*in.pri));
  write_suggestions_section(h, folder, sug, n_views);
  if (in.mission) write_mission_section(h, *in.mission);
  write_inputs_section(h, in);
  h << "</body></html>\n";
  out.html = (fs::path(folder) / "report.html").string();
  io::write_atomically(out.html, [&](std::ostream& o) { o << h.str(); });
  report_progress(progress, 1.0, "report");
  return out;
}

}  // namespace meshnbv
