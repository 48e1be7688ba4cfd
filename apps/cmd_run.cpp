// meshnbv run: the main job. PRI, next-view suggestions and a visual report
// in one folder.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

#include "commands.h"
#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"
#include "meshnbv/results.h"
#include "meshnbv/io/suggestions_io.h"
#include "meshnbv/report.h"
#include "progress_bar.h"

namespace fs = std::filesystem;

namespace meshnbv::cli {

void add_run_command(CLI::App& app) {
  struct Args {
    SceneInput input;
    PriOptions pri;
    SuggestOptions suggest;
    OptionFlags flags;
    MissionFlags mission;
    ProgressChoice progress;
    std::string out;
    bool overwrite = false;
    int display_faces = int(kDefaultDisplayFaces);
    int interaction_faces = int(kDefaultInteractionFaces);
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "run", "The main job: PRI, next-view suggestions and a visual report (report.html) in one folder");
  a->input.add_to(cmd);
  add_pri_options(cmd, &a->flags, &a->pri);
  add_suggest_options(cmd, &a->flags, &a->suggest);
  a->mission.add_to(cmd, &a->flags);
  cmd->add_option("--out", a->out, "Output folder")->required();
  cmd->add_flag("--overwrite", a->overwrite, "Write into a folder that already holds results");
  cmd->add_option("--display-faces", a->display_faces,
                  "Face budget of the report's 3-D view: a larger mesh is shown decimated to this many faces")
      ->check(CLI::Range(100, 100000000))
      ->capture_default_str();
  cmd->add_option("--interaction-faces", a->interaction_faces,
                  "Face budget of the 3-D view while the camera moves: a coarser copy is drawn then "
                  "(none when the display mesh is not larger)")
      ->check(CLI::Range(100, 100000000))
      ->capture_default_str();
  a->progress.add_to(cmd);
  cmd->callback([a]() {
    using clock = std::chrono::steady_clock;
    SuggestOptions& so = a->suggest;
    finish_options(a->flags, &a->pri, &so);
    a->mission.options.check();
    const mission::MissionRequest mission_request = a->mission.request();
    // A mission was asked for when any of its inputs was given; otherwise it
    // is planned when the scene is georeferenced, and the report says why not.
    const bool mission_asked = !a->mission.georef.empty() || !a->mission.takeoff.empty() ||
                               !a->mission.takeoff_wgs84.empty() || !a->mission.keep_out.empty() ||
                               !a->mission.boxes.empty();
    const fs::path out(a->out);
    io::check_can_write_folder(a->out);
    const fs::path report = out / "report.html";
    std::error_code ec;
    if (fs::exists(report, ec) && !a->overwrite)
      throw Error("output folder already holds a report; pass --overwrite to replace it", a->out);
    std::vector<std::pair<std::string, double>> timings;
    auto t0 = clock::now();
    auto lap = [&](const std::string& step) {
      const auto t1 = clock::now();
      timings.emplace_back(step, std::chrono::duration<double>(t1 - t0).count());
      t0 = t1;
    };
    const Scene scene = a->input.read();
    lap("read scene");
    ProgressBar bar(a->progress.silent(), a->progress.json());
    const PriResult pri = scene_pri(scene, a->pri, bar.callback());
    lap("PRI");
    const SuggestResult sug = suggest_views(scene, pri.pri, so, {}, bar.callback(), candidate_scorer());
    lap("suggestions");

    const std::string suggestions_text =
        suggestions_json(sug, so, {a->input.path, "computed (" + measure_name(a->pri.measure) + ")"});
    // The mission, in memory before anything is written.
    ReportMission report_mission;
    std::optional<mission::SceneMission> planned;
    try {
      planned = mission::plan_scene_mission(
          scene, mission::parse_suggestions_json(suggestions_text, "suggestions"), mission_request);
    } catch (const Error& e) {
      if (mission_asked) throw;
      report_mission.unavailable = e.what();
    }
    lap("mission");

    fs::create_directories(out);
    io::PlyWriteOptions ply;
    ply.overwrite = true;
    ply.exact_coordinates = true;
    ply.comments = pri_key_comments(pri);  // the very mesh, for meshnbv pri --previous
    io::write_ply(mesh_with_pri(scene.mesh, pri), (out / "pri.ply").string(), ply);
    io::write_atomically((out / "pri.json").string(),
                         [&](std::ostream& o) { o << pri_summary_json(pri, a->pri); });
    io::write_atomically((out / "suggestions.json").string(), [&](std::ostream& o) { o << suggestions_text; });
    if (planned) {
      mission::write_mission_files(*planned, (out / "mission").string(), true);
      const mission::MissionPlan& plan = planned->plan;
      report_mission.georef = planned->frame->georef().source;
      std::ostringstream at;
      at.setf(std::ios::fixed);
      at.precision(7);
      at << std::abs(plan.takeoff_geo.latitude) << (plan.takeoff_geo.latitude >= 0 ? " N, " : " S, ")
         << std::abs(plan.takeoff_geo.longitude) << (plan.takeoff_geo.longitude >= 0 ? " E" : " W");
      report_mission.takeoff = at.str();
      for (const mission::Flight& f : plan.flights)
        report_mission.flights.push_back({int(f.waypoints.size()), f.length_m, f.minutes, f.detours});
      for (const mission::Note& n : plan.notes)
        report_mission.notes.push_back(n.label + ": " + n.action + " (" + n.reason + ")");
      for (const auto& [name, content] : planned->files)
        if (name == "mission.svg") report_mission.svg = content;
      report_mission.folder = "mission";
    }
    // An optional output that cannot hold the lens never fails the main job.
    const std::string no_mlp = io::mlp_unsupported_reason(scene);
    if (no_mlp.empty())
      io::write_suggestions_mlp(scene, sug, (out / "suggestions.mlp").string(), true);
    else
      std::cerr << "warning: suggestions.mlp skipped: " << no_mlp << "\n";
    io::write_ply(frustum_mesh(sug), (out / "frustums.ply").string(), ply);
    lap("write results");

    ReportInputs r;
    r.scene = &scene;
    r.pri = &pri;
    r.pri_options = a->pri;
    r.suggestions = &sug;
    r.suggest_options = so;
    r.scene_path = a->input.path;
    r.timings = timings;
    r.files = {{"pri.ply", "mesh with face quality = PRI and PRI colours"},
               {"pri.json", "PRI summary"},
               {"suggestions.json", "the suggested views with every energy term"}};
    if (no_mlp.empty())
      r.files.push_back({"suggestions.mlp", "MeshLab project with rasters nbv_1, nbv_2, ..."});
    r.files.push_back({"frustums.ply", "frustums of the suggestions, red = best"});
    r.files.push_back({"viewer", "the 3-D view's script (three.js, bundled) and data, loaded by report.html"});
    if (planned)
      r.files.push_back({"mission", "drone mission of the suggestions: KML, DJI WPML KMZ, Litchi CSV, GeoJSON, CSV"});
    r.mission = &report_mission;
    r.display_faces = std::size_t(a->display_faces);
    r.interaction_faces = std::size_t(a->interaction_faces);
    const ReportFiles files = write_report(r, out.string(), bar.callback());
    bar.finish();
    std::cout << scene.mesh.num_faces() << " faces: " << pri.observed << " observed, " << pri.unobserved
              << " unobserved; " << sug.suggestions.size() << " suggestions\n";
    for (const auto& s : sug.suggestions)
      std::cout << "  " << s.label << "  energy " << s.energy.total << "  sees " << s.seen_faces.size()
                << " worst faces\n";
    if (planned)
      std::cout << "mission: " << planned->plan.waypoints.size() << " photos in " << planned->plan.flights.size()
                << " flight(s), " << planned->plan.total_minutes() << " min: " << (out / "mission").string() << "\n";
    else if (report_mission.unavailable.rfind("no georeference", 0) != 0)
      std::cerr << "warning: no mission: " << report_mission.unavailable << "\n";
    std::cout << "report: " << files.html << "\n";
  });
}

}  // namespace meshnbv::cli
