// `vibromap run` and `vibromap keys`.

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "vibromap/core/analysis/point_solver.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/io/scene/docs.hpp"
#include "vibromap/io/summary_output.hpp"
#include "vibromap/io/trajectory_file.hpp"

namespace vibromap::cli {
namespace {

// The scene with the command line's overrides. A trajectory is computed only when it will be
// written: with --trajectory, trajectory_periods 0 becomes kDefaultTrajectoryPeriods; without
// it, trajectory_periods becomes 0. Done as one more override, so Scene::text records it.
Scene load_run_scene(const RunArgs& args) {
  std::vector<std::string> sets = args.sets;
  Scene scene = load_scene(args.scene, sets);
  const int periods = scene.options.analysis.trajectory_periods;
  if (!args.trajectory.empty() && periods == 0) {
    sets.push_back("analysis.trajectory_periods=" + std::to_string(kDefaultTrajectoryPeriods));
  } else if (args.trajectory.empty() && periods != 0) {
    sets.push_back("analysis.trajectory_periods=0");
  } else {
    return scene;
  }
  return load_scene(args.scene, sets);
}

// Fails before the (possibly long) solve when the trajectory file's directory is missing.
void check_output_directory(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec)) {
    throw IoError(path + ": cannot write trajectory: directory '" + dir.string() + "' does not exist");
  }
}

void print_summary(std::ostream& out, const PointSummary& summary, const Scene& scene, const std::string& format) {
  if (format == "json") {
    write_summary_json(out, summary);
  } else {
    write_summary_table(out, summary, scene);
  }
  out.flush();
}

void save_trajectory(const std::string& path, const PointSummary& summary, const Scene& scene) {
  if (summary.trajectory.empty()) {
    std::cerr << "vibromap: note: no trajectory was kept (status " << to_string(summary.status) << "); " << path
              << " not written\n";
    return;
  }
  write_trajectory(path, summary, scene.text);
}

}  // namespace

int run_command(const RunArgs& args, std::ostream& out) {
  const Scene scene = load_run_scene(args);
  if (!args.trajectory.empty()) check_output_directory(args.trajectory);
  const PointSummary summary = solve_point(scene.params, scene.options);
  if (summary.status == SolveStatus::invalid_input) throw SceneError(scene.path + ": " + summary.message);
  print_summary(out, summary, scene, args.format);
  if (!args.trajectory.empty()) save_trajectory(args.trajectory, summary, scene);
  return kExitOk;
}

int keys_command(bool as_toml, std::ostream& out) {
  if (as_toml) {
    write_reference_scene(out);
  } else {
    write_scene_keys(out);
    out << "\nGive a key in a scene as `key = value` under its [section], or on the command line as\n"
           "`--set section.key=value`. Keys marked 'or give ...' form a pair: give one of the two.\n";
  }
  return kExitOk;
}

}  // namespace vibromap::cli
