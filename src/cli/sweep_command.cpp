// `vibromap sweep`: a scene's [sweep] on all MPI ranks into one HDF5 map (the sweep campaign);
// its summary is io/sweep_output.hpp. Also the helpers the campaigns' commands share
// (commands.hpp: load_scene_everywhere, farm_figures, campaign_exit).

#include <filesystem>
#include <iostream>
#include <memory>

#include "command.hpp"
#include "commands.hpp"
#include "vibromap/campaigns/exit_status.hpp"
#include "vibromap/campaigns/sweep/sweep_run.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/io/sweep_output.hpp"
#include "vibromap/parallel/signals.hpp"

namespace vibromap::cli {

// `vibromap sweep SCENE [--set section.key=value]... [--output FILE.h5] [--resume | --overwrite]`
// Collective under mpirun: every rank runs it; only rank 0 prints.
struct SweepArgs {
  std::string scene;
  std::vector<std::string> sets;
  std::string output;        // map file; empty: the scene's name with .h5, in the current directory
  bool resume = false;       // continue an existing map
  bool overwrite = false;    // replace an existing map
  bool quiet = false;        // no progress lines
  std::string format = "table";  // final summary: "table" or "json"
};

// Runs the sweep on all ranks. Returns the exit code (stopped when a signal stopped it, with
// a checkpoint written).
int sweep_command(const SweepArgs& args, std::ostream& out);

namespace {

std::string default_output(const std::string& scene_path) {
  return std::filesystem::path(scene_path).stem().string() + ".h5";
}

}  // namespace

Scene load_scene_everywhere(const MpiSession& mpi, const std::string& path, const std::vector<std::string>& sets,
                            const std::vector<CommandAxis>& axes) {
  Scene scene;
  mpi.agree([&] { scene = load_scene(path, sets, axes); }, exit_status_of);
  std::vector<char> text(scene.text.begin(), scene.text.end());
  mpi.broadcast(text);
  if (mpi.rank() != 0) scene = parse_scene(std::string_view(text.data(), text.size()), path, {}, axes);
  return scene;
}

std::optional<Scene> load_scene_before_mpi(const std::string& path, const std::vector<std::string>& sets) {
  if (launched_by_mpi()) return std::nullopt;
  return load_scene(path, sets);
}

Scene load_scene_everywhere(const MpiSession& mpi, std::optional<Scene> read_before, const std::string& path,
                            const std::vector<std::string>& sets) {
  if (read_before) return std::move(*read_before);
  return load_scene_everywhere(mpi, path, sets);
}

int sweep_command(const SweepArgs& args, std::ostream& out) {
  std::optional<Scene> read = load_scene_before_mpi(args.scene, args.sets);
  const MpiSession mpi;
  const Scene scene = load_scene_everywhere(mpi, std::move(read), args.scene, args.sets);
  SweepRunConfig config;
  config.output = args.output.empty() ? default_output(args.scene) : args.output;
  config.resume = args.resume;
  config.overwrite = args.overwrite;
  config.progress = !args.quiet;
  const SweepReport report = run_sweep(mpi, scene, config);
  if (mpi.rank() != 0) return report.farm.stop_signal ? code(ExitCode::stopped) : code(ExitCode::ok);
  if (args.format == "json") {
    write_sweep_json(out, farm_figures(report.farm), report.totals, config.output);
  } else {
    write_sweep_table(out, farm_figures(report.farm), report.totals, config.output);
  }
  out.flush();
  return campaign_exit(report.farm, config.output, "cells");
}

FarmFigures farm_figures(const FarmReport& farm) {
  return {.items = farm.items,
          .items_resumed = farm.items_resumed,
          .items_computed = farm.items_computed,
          .complete = farm.complete(),
          .ranks = farm.ranks,
          .wall_s = farm.wall_s,
          .items_per_s = farm.items_per_s(),
          .checkpoints = farm.checkpoints,
          .checkpoint_s = farm.checkpoint_s,
          .checkpoint_max_s = farm.checkpoint_max_s,
          .final_checkpoint_s = farm.final_checkpoint_s,
          .requests = farm.requests,
          .request_s = farm.request_s,
          .stopped_by = farm.stop_signal ? signal_name(farm.stop_signal) : std::string()};
}

int campaign_exit(const FarmReport& farm, const std::string& output, const char* noun) {
  if (farm.stop_signal == 0) return code(ExitCode::ok);
  std::cerr << "vibromap: stopped by " << signal_name(farm.stop_signal) << " after a checkpoint: " << output << " holds "
            << farm.items_resumed + farm.items_computed << " of " << farm.items << " " << noun
            << "; run the same command with --resume to go on\n";
  return code(ExitCode::stopped);
}

namespace {

std::string sweep_footer() {
  return "The scene's [sweep] section gives the axes, the quantities to store and the checkpoint\n"
         "interval ('vibromap keys' documents them). An axis can be any real or integer scene key,\n"
         "up to 8: \"forcing.omega\" = { from = 5, to = 9, n = 41 } (or forcing.omega = ..., or\n"
         "omega = ... when only one section has the key), E1 = { values = [...] }.\n"
         "Run on MPI ranks with: mpirun -n N vibromap sweep SCENE (as root add --allow-run-as-root,\n"
         "and --oversubscribe for more ranks than cores). Cells are handed out dynamically; rank 0\n"
         "computes too and writes the map. Progress goes to stderr: a live line on a terminal,\n"
         "plain lines every [sweep] progress_interval seconds otherwise.\n\n"
         "The map is made (every chunk allocated, its size checked against the disk) before any\n"
         "cell is computed, and cells are written into it as they arrive. Every [sweep]\n"
         "checkpoint_interval seconds the new cells are synced and then marked done, so a run\n"
         "killed at any moment (kill -9 included) leaves a map that opens; --resume continues it,\n"
         "verifying every chunk's checksum and computing the cells of a damaged one again. The\n"
         "run must be the same, judged key by key from the parsed scenes: formatting, comments and\n"
         "the checkpoint and progress intervals may differ, and an error names the keys that do.\n"
         "A run holds FILE.h5.lock: a second run on the same map is refused. SIGINT, SIGTERM or\n"
         "SIGUSR1 to any rank write a final checkpoint and stop (exit code 3); through mpirun send\n"
         "SIGUSR1 (mpirun turns SIGINT and SIGTERM into a kill 2 s later and exits 1).";
}

}  // namespace

Command declare_sweep(CLI::App& app) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* sweep = app.add_subcommand("sweep", "Sweep a grid of parameter points on MPI ranks into an HDF5 map");
  add_scene_options(*sweep, args->scene, args->sets, "Scene file (TOML) with a [sweep] section");
  add_output_option(*sweep, "-o,--output", args->output, "Map file to write (default: the scene's name with .h5)");
  add_resume_options(*sweep, args->resume, args->overwrite, "Continue an existing map of the same scene",
                     "Replace an existing map");
  sweep->add_flag("-q,--quiet", args->quiet, "No progress lines");
  add_format_option(*sweep, args->format, "Final summary on stdout: table or json");
  return {.app = sweep, .footer = sweep_footer(), .topic = "a sweep", .campaign = always_campaign,
          .run = [args](std::ostream& out) { return sweep_command(*args, out); }};
}

}  // namespace vibromap::cli
