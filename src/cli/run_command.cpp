// `vibromap run` and `vibromap keys`.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "vibromap/campaigns/census/point_census_run.hpp"
#include "vibromap/core/analysis/census.hpp"
#include "vibromap/core/analysis/point_solver.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/output_file.hpp"
#include "vibromap/io/census_output.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/io/scene/docs.hpp"
#include "vibromap/io/summary_output.hpp"
#include "vibromap/io/trajectory_file.hpp"
#include "vibromap/parallel/mpi_session.hpp"
#include "vibromap/parallel/signals.hpp"

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

// The memory the system can give without swapping (MemAvailable), bytes; 0 when unknown.
std::uint64_t available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  return 0;
}

std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g GB", bytes / 1e9);
  return text;
}

// Checks the trajectory file before the (possibly long) solve: its directory exists, an
// existing file is a regular one and may be replaced, and the trajectory fits in memory and on
// the disk.
void check_trajectory(const std::string& path, bool overwrite, const Scene& scene) {
  namespace fs = std::filesystem;
  std::error_code ec;
  check_output(path, {.option = "--trajectory", .overwrite = overwrite});
  const fs::path dir = fs::path(path).parent_path();
  const AnalysisOptions& a = scene.options.analysis;
  const double samples = static_cast<double>(a.trajectory_periods) * static_cast<double>(a.trajectory_samples);
  // The samples (7 float64 each) are kept once by the solver and once, column by column, by the
  // writer; a vector may hold twice its size while it grows.
  const double memory = 3.0 * samples * static_cast<double>(sizeof(TrajectorySample));
  const double file = samples * static_cast<double>(sizeof(TrajectorySample));
  const std::string what = "--trajectory: " + std::to_string(a.trajectory_periods) + " periods x " +
                           std::to_string(a.trajectory_samples) + " samples ([analysis] trajectory_periods, "
                           "trajectory_samples)";
  if (const std::uint64_t avail = available_memory(); avail > 0 && memory > 0.5 * static_cast<double>(avail))
    throw IoError(path + ": " + what + " need about " + gigabytes(memory) + " of memory, more than half the " +
                     gigabytes(static_cast<double>(avail)) + " available; keep fewer periods or samples");
  const fs::space_info space = fs::space(dir.empty() ? fs::path(".") : dir, ec);
  if (!ec && file > static_cast<double>(space.available))
    throw IoError(path + ": " + what + " make a " + gigabytes(file) + " file; its file system has " +
                     gigabytes(static_cast<double>(space.available)) + " free");
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

void print_labels(std::ostream& out, const CensusSummary& summary) {
  out << "\n  #  x1 (m)        x2 (m)        v1 (m/s)      v2 (m/s)      attractor\n";
  for (std::size_t i = 0; i < summary.labels.size(); ++i) {
    const Eigen::Vector4d& x = summary.initial_conditions[i];
    char line[160];
    std::snprintf(line, sizeof line, "%3zu  %12.5e  %12.5e  %12.5e  %12.5e  %d\n", i, x[0], x[1], x[2], x[3],
                  summary.labels[i]);
    out << line;
  }
}

// `run --census`: every attractor of the point ([census], or its defaults). Under an MPI
// launcher with several ranks the initial states are shared out over them (the point census
// campaign) and rank 0 prints; else one process follows them all (census_point).
int census_command(const RunArgs& args, std::ostream& out) {
  if (!args.trajectory.empty()) throw SceneError(args.scene + ": --trajectory cannot be combined with --census");
  std::optional<MpiSession> mpi;
  if (launched_by_mpi()) mpi.emplace();
  const Scene scene = mpi ? load_scene_everywhere(*mpi, args.scene, args.sets) : load_scene(args.scene, args.sets);
  CensusOptions census = scene.census.value_or(CensusOptions{});
  census.labels = args.labels;
  CensusSummary summary;
  if (mpi && mpi->size() > 1) {
    if (mpi->rank() == 0 && census.decide_by_recurrence)
      std::cerr << "vibromap: note: census.decide_by_recurrence is not used on several ranks (a label would depend on "
                   "what its rank followed before); run on one rank for it\n";
    const PointCensusReport r = run_point_census(*mpi, scene, census, true);
    // Every rank ends with rank 0's code (only rank 0's report knows of a stop).
    const int stop_signal = mpi->broadcast(r.farm.stop_signal);
    if (mpi->rank() != 0) return code(stop_signal ? ExitCode::stopped : ExitCode::ok);
    if (!r.farm.complete()) {
      std::cerr << "vibromap: " << scene.path << ": run --census stopped by " << signal_name(r.farm.stop_signal)
                << " after " << r.farm.items_computed << " of " << r.farm.items << " initial states; no census printed\n";
      return code(ExitCode::stopped);
    }
    summary = r.summary;
    summary.ranks = r.farm.ranks;
  } else {
    summary = census_point(scene.params, scene.options, census);
    if (summary.status == SolveStatus::invalid_input) throw SceneError(scene.path + ": " + summary.message);
  }
  if (args.format == "json") {
    write_census_json(out, summary);
  } else {
    write_census_table(out, summary, scene);
    if (args.labels) print_labels(out, summary);
  }
  out.flush();
  return code(ExitCode::ok);
}

}  // namespace

int run_command(const RunArgs& args, std::ostream& out) {
  if (args.labels && !args.census) throw SceneError(args.scene + ": --labels needs --census");
  if (args.census) return census_command(args, out);
  // One point: under an MPI launcher only the first rank solves and prints it.
  if (launcher_rank() != 0) return code(ExitCode::ok);
  const Scene scene = load_run_scene(args);
  if (!args.trajectory.empty()) check_trajectory(args.trajectory, args.overwrite, scene);
  const PointSummary summary = solve_point(scene.params, scene.options);
  if (summary.status == SolveStatus::invalid_input) throw SceneError(scene.path + ": " + summary.message);
  print_summary(out, summary, scene, args.format);
  if (!args.trajectory.empty()) save_trajectory(args.trajectory, summary, scene);
  return code(ExitCode::ok);
}

int keys_command(bool as_toml, std::ostream& out) {
  if (as_toml) {
    write_reference_scene(out);
  } else {
    write_scene_keys(out);
    out << "\nGive a key in a scene as `key = value` under its [section], or on the command line as\n"
           "`--set section.key=value` (or `--set key=value` when only one section has the key). Keys\n"
           "marked 'or give ...' form a pair: give one of the two.\n";
  }
  return code(ExitCode::ok);
}

}  // namespace vibromap::cli
