// `vibromap run`: one parameter point, or its census of attractors (--census).

#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "command.hpp"
#include "commands.hpp"
#include "vibromap/campaigns/census/point_census_run.hpp"
#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/output_file.hpp"
#include "vibromap/io/point_run.hpp"
#include "vibromap/io/report.hpp"
#include "vibromap/io/census_output.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/io/scene/docs.hpp"
#include "vibromap/io/summary_output.hpp"
#include "vibromap/io/trajectory_file.hpp"
#include "vibromap/parallel/mpi_session.hpp"
#include "vibromap/parallel/signals.hpp"

namespace vibromap::cli {

// `vibromap run SCENE [--set section.key=value]... [--format table|json] [--trajectory FILE.h5]`
struct RunArgs {
  std::string scene;              // scene file (TOML)
  std::vector<std::string> sets;  // overrides "section.key=value", in command-line order
  std::string format = "table";   // "table" or "json"
  std::string trajectory;         // HDF5 file for the kept trajectory; empty: none
  bool overwrite = false;         // replace an existing trajectory file
  bool census = false;            // look for every attractor ([census]) instead of the one from rest
  bool labels = false;            // with census: also print each initial state and its attractor
  bool shock = false;             // with census: also each attractor's minimal critical shock (census.shock)
};

// Solves the scene's point and prints its summary to `out`; writes the trajectory file when
// asked. Throws SceneError on a bad scene, IoError when a file cannot be written.
int run_command(const RunArgs& args, std::ostream& out);

namespace {

// The scene with the command line's overrides and trajectory_override's: a trajectory is
// computed only when it will be written (--trajectory).
Scene load_run_scene(const RunArgs& args) {
  std::vector<std::string> sets = args.sets;
  Scene scene = load_scene(args.scene, sets);
  const std::optional<std::string> periods = trajectory_override(scene, !args.trajectory.empty());
  if (!periods) return scene;
  sets.push_back(*periods);
  return load_scene(args.scene, sets);
}

// Checks the trajectory file before the (possibly long) solve: its directory exists, an
// existing file is a regular one and may be replaced, and the trajectory fits in memory and on
// the disk (check_trajectory_fits, the check optimise makes too).
void check_trajectory(const std::string& path, bool overwrite, const Scene& scene) {
  check_output(path, {.option = "--trajectory", .overwrite = overwrite});
  const AnalysisOptions& a = scene.options.analysis;
  check_trajectory_fits(path, "--trajectory", a.trajectory_periods, a.trajectory_samples);
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

// `run --census`: every attractor of the point ([census], or its defaults). Under an MPI
// launcher with several ranks the initial states are shared out over them (the point census
// campaign) and rank 0 prints; else one process follows them all (census_point).
int census_command(const RunArgs& args, std::ostream& out) {
  if (!args.trajectory.empty()) throw SceneError(args.scene + ": --trajectory cannot be combined with --census");
  std::optional<MpiSession> mpi;
  if (launched_by_mpi()) mpi.emplace();
  const Scene scene = mpi ? load_scene_everywhere(*mpi, args.scene, args.sets) : load_scene(args.scene, args.sets);
  const CensusOptions census = run_census_options(scene, args.labels, args.shock);
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
    summary = census_scene_point(scene, census);
  }
  if (args.format == "json") {
    write_census_json(out, summary);
  } else {
    write_census_table(out, summary, scene);
    if (args.labels) write_census_labels_table(out, summary);
  }
  out.flush();
  return code(ExitCode::ok);
}

}  // namespace

int run_command(const RunArgs& args, std::ostream& out) {
  if (args.labels && !args.census) throw SceneError(args.scene + ": --labels needs --census");
  if (args.shock && !args.census) throw SceneError(args.scene + ": --shock needs --census");
  if (args.census) return census_command(args, out);
  // One point: under an MPI launcher only the first rank solves and prints it.
  if (launcher_rank() != 0) return code(ExitCode::ok);
  const Scene scene = load_run_scene(args);
  if (!args.trajectory.empty()) check_trajectory(args.trajectory, args.overwrite, scene);
  const PointSummary summary = solve_scene_point(scene);
  print_summary(out, summary, scene, args.format);
  if (!args.trajectory.empty()) save_trajectory(args.trajectory, summary, scene);
  return code(ExitCode::ok);
}

namespace {

std::string run_footer() {
  std::ostringstream os;
  os << "Scene: a TOML file with the sections and keys below, in SI units. Every key is\n"
        "optional and defaults to Table 1 of docs/model.md. 'vibromap keys' lists each key's\n"
        "default, unit, allowed values and meaning; jobs/reference.toml gives every key\n"
        "with its default and a comment. Unknown sections and keys are errors. A scene is a\n"
        "regular file of at most " << kMaxSceneText << ": anything else (a directory, a\n"
        "FIFO, a device) is refused at once, the same for every command that reads a scene.\n";
  write_scene_key_summary(os);
  os << "\n--set section.key=value overrides one key after the file is read, with the same\n"
        "checks. The value is read as TOML (310, 1e-8, \"rk4\") or else as a string (rk4).\n"
        "Setting one key of a pair (k1|omega1, xi1|c1, ...) replaces the other one.\n\n"
        "--trajectory keeps [analysis] trajectory_periods forcing periods of the steady\n"
        "motion (" << kDefaultTrajectoryPeriods << " when the scene gives 0), sampled "
        "trajectory_samples times per period,\nand writes them to an HDF5 file (read by "
        "postprocess/). Without --trajectory no\ntrajectory is computed. An existing FILE.h5 is replaced "
        "only with --overwrite, and\nnever when it is not a regular file; a trajectory too big for the "
        "memory or the disk is\nrefused before the solve, with its size.\n\n"
        "--census follows [census] initial_conditions (K) states to their attractors. Under\n"
        "mpirun -n N (or srun) the K states are shared out over the N ranks, one follower each\n"
        "(captures by periodic orbits only: census.decide_by_recurrence is not used there), and\n"
        "rank 0 prints the census, the same for any N; SIGUSR1 to mpirun stops it (exit 3, no\n"
        "census printed). Without --census, rank 0 alone solves and prints the point.";
  return os.str();
}

// Under an MPI launcher `run --census` shares its initial states out over the ranks.
bool census_under_launcher(int argc, char** argv) {
  if (!launched_by_mpi()) return false;
  for (int i = 2; i < argc; ++i)
    if (std::string_view(argv[i]) == "--census") return true;
  return false;
}

}  // namespace

Command declare_run(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* run = app.add_subcommand("run", "Solve one parameter point: steady motion, impacts, regime");
  add_scene_options(*run, args->scene, args->sets, "Scene file (TOML)");
  run->add_option("-f,--format", args->format, "Output on stdout: a table for people or JSON for scripts")
      ->check(CLI::Validator(
          [](const std::string& s) { return s == "table" || s == "json" ? std::string() : "must be table or json"; },
          ""))
      ->type_name("table|json")
      ->capture_default_str();
  add_output_option(*run, "-t,--trajectory", args->trajectory, "Also write the steady motion's trajectory to FILE.h5");
  run->add_flag("--overwrite", args->overwrite, "Replace an existing trajectory file");
  run->add_flag("--census", args->census, "Find every attractor of the point with its basin fraction ([census])");
  run->add_flag("--labels", args->labels, "With --census: also print each initial state and its attractor's index");
  run->add_flag("--shock", args->shock,
                "With --census: also each attractor's minimal critical shock (census.shock; docs/model.md)");
  return {.app = run, .footer = run_footer(), .topic = "a run", .campaign = census_under_launcher,
          .run = [args](std::ostream& out) { return run_command(*args, out); }};
}

}  // namespace vibromap::cli
