// `vibromap optimise`: a scene's [optimise] on all MPI ranks; starts and best points on stdout
// (io/optimise_output.hpp).

#include <filesystem>
#include <iostream>
#include <memory>

#include "command.hpp"
#include "commands.hpp"
#include "vibromap/campaigns/multistart/optimise_run.hpp"
#include "vibromap/io/optimise_output.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/parallel/mpi_session.hpp"
#include "vibromap/parallel/signals.hpp"

namespace vibromap::cli {

// `vibromap optimise SCENE [--set section.key=value]... [--output FILE.h5] [--resume | --overwrite]
// [--format table|json] [-q]`. Collective under mpirun: every rank runs it; only rank 0 prints.
struct OptimiseArgs {
  std::string scene;
  std::vector<std::string> sets;
  std::string output;            // result file; empty: the scene's name with _optimise.h5, in the current directory
  bool resume = false;           // finish a killed run from its journal FILE.h5.journal
  bool overwrite = false;        // replace an existing result file (and recompute the seeding sweep's map)
  bool quiet = false;            // no progress lines
  std::string format = "table";  // stdout: "table" or "json"
};

// The files of an optimisation with result file `output` (FILE.h5): the seeding sweep's map
// FILE_map.h5, the best point's trajectory FILE_trajectory.h5 and, while it runs, the journal of
// its finished starts FILE.h5.journal.
std::string optimise_map_path(const std::string& output);
std::string optimise_trajectory_path(const std::string& output);
std::string optimise_journal_path(const std::string& output);

// Runs the scene's [optimise] on all ranks and prints the starts and the best points.
// Returns the exit code (stopped when a signal stopped the seeding sweep or the starts, with
// the map or the journal checkpointed).
int optimise_command(const OptimiseArgs& args, std::ostream& out);

namespace {

std::string stem_path(const std::string& output) {
  const std::filesystem::path p(output);
  return (p.parent_path() / p.stem()).string();
}

std::string default_output(const std::string& scene_path) {
  return std::filesystem::path(scene_path).stem().string() + "_optimise.h5";
}

}  // namespace

std::string optimise_map_path(const std::string& output) { return stem_path(output) + "_map.h5"; }
std::string optimise_trajectory_path(const std::string& output) { return stem_path(output) + "_trajectory.h5"; }

std::string optimise_journal_path(const std::string& output) { return output + ".journal"; }

int optimise_command(const OptimiseArgs& args, std::ostream& out) {
  std::optional<Scene> read = load_scene_before_mpi(args.scene, args.sets);
  const MpiSession mpi;
  const Scene scene = load_scene_everywhere(mpi, std::move(read), args.scene, args.sets);
  OptimiseRunConfig config;
  config.output = args.output.empty() ? default_output(args.scene) : args.output;
  config.map_output = optimise_map_path(config.output);
  config.trajectory = optimise_trajectory_path(config.output);
  config.journal = optimise_journal_path(config.output);
  config.resume = args.resume;
  config.overwrite = args.overwrite;
  config.progress = !args.quiet;
  const OptimiseRun run = run_optimise(mpi, scene, config);
  if (run.stop_signal != 0) {
    if (mpi.rank() == 0)
      std::cerr << "vibromap: stopped by " << signal_name(run.stop_signal) << " after a checkpoint: "
                << (run.starts.items > 0 ? config.journal + " holds the finished starts"
                                         : config.map_output + " holds the seeding sweep")
                << "; run the same command with --resume to go on\n";
    return code(ExitCode::stopped);
  }
  if (mpi.rank() != 0) return code(ExitCode::ok);
  const OptimiseRunInfo info{
      .output = config.output, .starts_resumed = run.starts_resumed, .sweep_cells_computed = run.sweep.items_computed};
  if (args.format == "json") {
    write_optimise_json(out, run.report, *scene.optimise, info);
  } else {
    write_optimise_table(out, run.report, *scene.optimise, info);
  }
  return code(ExitCode::ok);
}

namespace {

std::string optimise_footer() {
  return "The scene's [optimise] section names the free parameters and their box (any of E1, E2, R1,\n"
         "R2, m2, k2|omega2; log-scaled where it says so), the objective (min_k_con, max_T_con of one\n"
         "impact, min_F_max), the regime to keep (a constraint, default a stable (1,1)), the local\n"
         "algorithm(s) (bobyqa, cobyla, sbplx, slsqp, mma through NLopt; gradient_projection, the source\n"
         "paper's method) and their stopping rules ('vibromap keys' documents them).\n\n"
         "Seeds: the best cells of [optimise] map; without it, the scene's [sweep] runs first into\n"
         "FILE_map.h5 (reused, or resumed, by the next run of the same scene; --overwrite recomputes it);\n"
         "without either, the scene's point. Every seed is started with every algorithm; starts are\n"
         "handed out to the MPI ranks dynamically (mpirun -n N vibromap optimise SCENE), and the answer\n"
         "does not depend on the number of ranks. A line per finished start goes to stderr.\n\n"
         "The best distinct points are re-solved from scratch at [optimise] verify_rtol, by brute-force\n"
         "integration from rest and by shooting, with regime, Floquet stability, T_con, k_con and F_max.\n"
         "FILE.h5 holds every evaluation of every start (vibromap-post plot_optimise FILE.h5 draws\n"
         "them), FILE_trajectory.h5 the best point's steady motion. --format json prints one object\n"
         "whose 'best' lists those points, best first. An existing FILE.h5 is replaced only with\n"
         "--overwrite.\n\n"
         "Finished starts go to the journal FILE.h5.journal as they arrive (synced every 10 s). SIGINT,\n"
         "SIGTERM or SIGUSR1 stop the run after a final checkpoint (exit code 3, and a 'vibromap:\n"
         "stopped by' line even with -q), during the seeding sweep, the starts or the re-solves;\n"
         "--resume then finishes it with the same answer, computing only what is missing. The journal\n"
         "is removed once FILE.h5 is written. Under mpirun, Ctrl-C or SIGTERM to mpirun makes mpirun\n"
         "itself exit 1 (it passes SIGTERM, then SIGKILL, to the ranks, which stop within that); SIGUSR1\n"
         "is forwarded and mpirun exits 3. A script tells a stop by the 'stopped by' line, or by\n"
         "FILE.h5.journal left and no FILE.h5.";
}

}  // namespace

Command declare_optimise(CLI::App& app) {
  auto args = std::make_shared<OptimiseArgs>();
  CLI::App* opt = app.add_subcommand("optimise", "Multistart optimisation of the softest impact on MPI ranks (NLopt)");
  add_scene_options(*opt, args->scene, args->sets, "Scene file (TOML) with an [optimise] section");
  add_output_option(*opt, "-o,--output", args->output, "Result file to write (default: the scene's name with _optimise.h5)");
  add_resume_options(*opt, args->resume, args->overwrite, "Finish a stopped or killed run from its journal (FILE.h5.journal)",
                     "Replace an existing result file and recompute the seeding sweep");
  opt->add_flag("-q,--quiet", args->quiet, "No progress lines");
  add_format_option(*opt, args->format, "Output on stdout: a table for people or JSON for scripts");
  return {.app = opt, .footer = optimise_footer(), .topic = "the optimisation", .campaign = always_campaign,
          .run = [args](std::ostream& out) { return optimise_command(*args, out); }};
}

}  // namespace vibromap::cli
