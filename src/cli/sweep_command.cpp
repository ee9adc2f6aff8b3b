// `vibromap sweep`: a scene's [sweep] on all MPI ranks into one HDF5 map (the sweep campaign).

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

#include "command.hpp"
#include "commands.hpp"
#include "vibromap/campaigns/exit_status.hpp"
#include "vibromap/campaigns/sweep/sweep_run.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/scene/scene.hpp"
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

// A census map: initial states followed per second (K per cell computed).
double state_rate(const SweepReport& r) { return r.farm.items_per_s() * r.census_initial_conditions; }

// An adaptive map: its points solved per second of this run (the fill copies, it solves nothing).
double solved_rate(const SweepReport& r) {
  return r.farm.wall_s > 0 ? static_cast<double>(r.refine_solved_now) / r.farm.wall_s : 0.0;
}

void print_json(std::ostream& out, const SweepReport& r, const std::string& output) {
  const FarmReport& f = r.farm;
  JsonWriter w(out);
  w.begin_object()
      .field("output", output)
      .field("cells_total", f.items)
      .field("cells_resumed", f.items_resumed)
      .field("cells_computed", f.items_computed)
      .field("complete", f.complete())
      .field("ranks", f.ranks)
      .field("wall_s", f.wall_s)
      .field("cells_per_s", f.items_per_s())
      .field("checkpoints", f.checkpoints)
      .field("checkpoint_s", f.checkpoint_s)
      .field("checkpoint_max_s", f.checkpoint_max_s)
      .field("final_checkpoint_s", f.final_checkpoint_s)
      .field("stopped_by", f.stop_signal ? signal_name(f.stop_signal) : std::string())
      .field("requests", f.requests)
      .field("request_us", f.requests ? 1e6 * f.request_s / static_cast<double>(f.requests) : 0.0);
  if (r.census_initial_conditions > 0)
    w.field("census_initial_conditions", r.census_initial_conditions)
        .field("initial_conditions_per_s", state_rate(r))
        .field("census_budget_states", r.census_budget_states);
  w.field("soft_cells", r.soft).field("impacting_cells", r.impacting).field("hertz_invalid_cells", r.hertz_invalid);
  if (r.refine_levels > 0) {
    const RefineFigures& x = r.refine;
    w.field("refine_levels", r.refine_levels).key("refine_solved_per_level").begin_array();
    for (const std::uint64_t n : x.solved_per_level) w.value(n);
    w.end_array()
        .field("points_solved_now", r.refine_solved_now)
        .field("points_solved_per_s", solved_rate(r))
        .field("refine_solved", x.solved)
        .field("refine_inherited", x.inherited)
        .field("refine_audited", x.audited)
        .field("refine_mismatches", x.mismatches)
        .field("refine_mismatch_bound", x.mismatch_bound)
        .field("refine_whole_cells", x.whole_blocks);
  }
  w.key("regimes").begin_object();
  for (const auto& [label, count] : r.regimes) w.field(label, count);
  w.end_object().end_object();
  out << "\n";
}

// The counts and the rate: of cells for a uniform map; for an adaptive map of points, by how
// each got its values, and the rate per point solved.
void print_counts(std::ostream& out, const SweepReport& r) {
  const FarmReport& f = r.farm;
  if (r.refine_levels == 0) {
    out << "cells          " << f.items << " (" << f.items_resumed << " from the resumed map, " << f.items_computed
        << " computed now)\n"
        << "ranks          " << f.ranks << "\n"
        << "wall time      " << std::setprecision(4) << f.wall_s << " s, " << f.items_per_s() << " cells/s\n";
    return;
  }
  const RefineFigures& x = r.refine;
  const std::uint64_t decided = x.solved + x.audited + x.inherited;
  out << "points         " << f.items << " (" << x.solved << " solved, " << x.audited << " audited, " << x.inherited
      << " inherited";
  if (decided < f.items) out << ", " << f.items - decided << " not decided yet";
  out << "; " << f.items_resumed << " from the resumed map, " << r.refine_solved_now << " solved now)\n"
      << "ranks          " << f.ranks << "\n"
      << "wall time      " << std::setprecision(4) << f.wall_s << " s, " << solved_rate(r) << " points solved/s\n";
}

void print_table(std::ostream& out, const SweepReport& r, const std::string& output) {
  const FarmReport& f = r.farm;
  out << "map            " << output << stopped_note(f) << "\n";
  print_counts(out, r);
  out << "checkpoints    " << f.checkpoints << " (" << f.checkpoint_s << " s writing, longest " << f.checkpoint_max_s
      << " s)\n";
  if (r.census_initial_conditions > 0)
    out << "census         " << r.census_initial_conditions << " initial states per cell, " << state_rate(r)
        << " initial states/s\n"
        << "budget         " << r.census_budget_states << " of "
        << (f.items_resumed + f.items_computed) * static_cast<std::uint64_t>(r.census_initial_conditions)
        << " initial states followed to analysis.max_periods (no early decision: brute force follows them as far)\n";
  out << "soft           " << r.soft << " cells (periodic with impacts, stable, Hertz-valid, k_con <= analysis.soft_kcon); "
      << r.hertz_invalid << " of " << r.impacting << " cells with impacts beyond the Hertz limit\n";
  if (r.refine_levels > 0) {
    const RefineFigures& x = r.refine;
    out << "refine         " << r.refine_levels << " levels: " << x.solved << " points solved (" << std::setprecision(3)
        << 100.0 * static_cast<double>(x.solved) / static_cast<double>(std::max<std::uint64_t>(f.items, 1))
        << " %; per level";
    for (const std::uint64_t n : x.solved_per_level) out << " " << n;
    out << "; " << x.whole_blocks << " speckled coarse cells solved whole), " << x.inherited << " inherited, ";
    if (x.audited == 0) out << "no audit (sweep.refine_audit = 0 or nothing inherited: the inherited points' mismatch is unmeasured)\n";
    else
      out << "audit " << x.mismatches << " of " << x.audited << " audited points differ (95 % upper bound on the mismatch rate "
          << std::setprecision(3) << x.mismatch_bound << ")\n";
  }
  out << "regimes       ";
  for (const auto& [label, count] : r.regimes) out << " " << label << " " << count;
  out << "\n";
}

}  // namespace

Scene load_scene_everywhere(const MpiSession& mpi, const std::string& path, const std::vector<std::string>& sets) {
  Scene scene;
  mpi.agree([&] { scene = load_scene(path, sets); }, exit_status_of);
  std::vector<char> text(scene.text.begin(), scene.text.end());
  mpi.broadcast(text);
  if (mpi.rank() != 0) scene = parse_scene(std::string_view(text.data(), text.size()), path);
  return scene;
}

int sweep_command(const SweepArgs& args, std::ostream& out) {
  const MpiSession mpi;
  const Scene scene = load_scene_everywhere(mpi, args.scene, args.sets);
  SweepRunConfig config;
  config.output = args.output.empty() ? default_output(args.scene) : args.output;
  config.resume = args.resume;
  config.overwrite = args.overwrite;
  config.progress = !args.quiet;
  const SweepReport report = run_sweep(mpi, scene, config);
  if (mpi.rank() != 0) return report.farm.stop_signal ? code(ExitCode::stopped) : code(ExitCode::ok);
  if (args.format == "json") {
    print_json(out, report, config.output);
  } else {
    print_table(out, report, config.output);
  }
  out.flush();
  return campaign_exit(report.farm, config.output, "cells");
}

std::string stopped_note(const FarmReport& farm) {
  return farm.stop_signal ? "  (stopped by " + signal_name(farm.stop_signal) + ": go on with --resume)" : "";
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
