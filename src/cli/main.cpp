// The vibromap executable: declares the command line (CLI11), parses it and dispatches to
// the commands of commands.hpp. Every error ends here as one line on stderr,
// "vibromap: error: ...", with the exit code of commands.hpp.

#include <csignal>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/scene/docs.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/campaigns/exit_status.hpp"
#include "vibromap/core/analysis/restitution.hpp"
#include "vibromap/core/cancel.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/parallel/exit_code.hpp"
#include "vibromap/parallel/farm.hpp"
#include "vibromap/parallel/mpi_session.hpp"
#include "vibromap/parallel/signals.hpp"

namespace {

using namespace vibromap;

// The longest error line: messages clip the input they echo themselves; this is the backstop.
constexpr std::size_t kMaxErrorLine = 1000;

// An output option's value: a file name. An empty one is refused here; the rest (a link, a
// device, a name too long, an existing file without --overwrite) when the command checks it.
const CLI::Validator kOutputName(
    [](const std::string& s) { return s.empty() ? std::string("empty; name the file to write") : std::string(); }, "",
    "OUTPUT");

// CLI11 reads an empty value as 0 for a number option (--e '' was restitution 0); an empty
// number is bad input. Given to every number option.
const CLI::Validator kNumber(
    [](const std::string& s) { return s.empty() ? std::string("an empty value is not a number") : std::string(); },
    "");

int report(std::string_view message, ExitCode exit) {
  std::string what = clip(message, kMaxErrorLine);
  for (char& c : what) {
    if (c == '\n' || c == '\r') c = ' ';  // one line, always
  }
  std::cerr << "vibromap: error: " << what << "\n";
  return code(exit);
}

// A stop signal that cancelled a computation outside the farm's items (none does: the campaigns
// open their cancellation scopes around items only).
int stopped_outside_a_farm() {
  std::cerr << "vibromap: stopped by " << signal_name(stop_signal()) << "\n";
  return code(ExitCode::stopped);
}

std::string main_footer() {
  return exit_code_summary() +
         "\nOutputs are written as a new file beside the name given, synced and renamed into place: an\n"
         "existing file is replaced only with --overwrite, and a name that is a symbolic link, a directory,\n"
         "a device or a FIFO is refused (name the link's target itself).\n"
         "'vibromap run --help' explains a run, 'vibromap sweep --help' a sweep, 'vibromap accuracy\n"
         "--help' the accuracy study, 'vibromap optimise --help' the optimisation, 'vibromap basins\n"
         "--help' the basin pictures, 'vibromap orbit-diagram --help' the bifurcation diagram;\n"
         "'vibromap restitution' the contact laws' effective restitution; 'vibromap keys' lists\n"
         "the scene keys.";
}

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
        "motion (" << cli::kDefaultTrajectoryPeriods << " when the scene gives 0), sampled "
        "trajectory_samples times per period,\nand writes them to an HDF5 file (read by "
        "postprocess/). Without --trajectory no\ntrajectory is computed. An existing FILE.h5 is replaced "
        "only with --overwrite, and\nnever when it is not a regular file; a trajectory too big for the "
        "memory or the disk is\nrefused before the solve, with its size.\n\n"
        "--census follows [census] initial_conditions (K) states to their attractors. Under\n"
        "mpirun -n N (or srun) the K states are shared out over the N ranks, one follower each\n"
        "(captures by periodic orbits only: census.decide_by_recurrence is not used there), and\n"
        "rank 0 prints the census, the same for any N; SIGUSR1 to mpirun stops it (exit 3, no\n"
        "census printed). Without --census, rank 0 alone solves and prints the point.\n\n"
     << main_footer();
  return os.str();
}

// --set's help, the same for every command.
constexpr const char* kSetHelp =
    "Override one scene key (repeatable): section.key=value, or key=value when only one section has the key (as in [sweep])";

CLI::App* add_run(CLI::App& app, cli::RunArgs& args) {
  CLI::App* run = app.add_subcommand("run", "Solve one parameter point: steady motion, impacts, regime");
  run->add_option("scene", args.scene, "Scene file (TOML)")->required()->type_name("SCENE");
  run->add_option("-s,--set", args.sets, kSetHelp)
      ->allow_extra_args(false)
      ->type_name("SECTION.KEY=VALUE");
  run->add_option("-f,--format", args.format, "Output on stdout: a table for people or JSON for scripts")
      ->check(CLI::Validator(
          [](const std::string& s) { return s == "table" || s == "json" ? std::string() : "must be table or json"; },
          ""))
      ->type_name("table|json")
      ->capture_default_str();
  run->add_option("-t,--trajectory", args.trajectory, "Also write the steady motion's trajectory to FILE.h5")
      ->check(kOutputName)
      ->type_name("FILE.h5");
  run->add_flag("--overwrite", args.overwrite, "Replace an existing trajectory file");
  run->add_flag("--census", args.census, "Find every attractor of the point with its basin fraction ([census])");
  run->add_flag("--labels", args.labels, "With --census: also print each initial state and its attractor's index");
  run->footer(run_footer());
  return run;
}

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
         "SIGUSR1 (mpirun turns SIGINT and SIGTERM into a kill 2 s later and exits 1).\n\n" +
         main_footer();
}

CLI::App* add_sweep(CLI::App& app, cli::SweepArgs& args) {
  CLI::App* sweep = app.add_subcommand("sweep", "Sweep a grid of parameter points on MPI ranks into an HDF5 map");
  sweep->add_option("scene", args.scene, "Scene file (TOML) with a [sweep] section")->required()->type_name("SCENE");
  sweep->add_option("-s,--set", args.sets, kSetHelp)
      ->allow_extra_args(false)
      ->type_name("SECTION.KEY=VALUE");
  sweep->add_option("-o,--output", args.output, "Map file to write (default: the scene's name with .h5)")
      ->check(kOutputName)
      ->type_name("FILE.h5");
  auto* resume = sweep->add_flag("--resume", args.resume, "Continue an existing map of the same scene");
  sweep->add_flag("--overwrite", args.overwrite, "Replace an existing map")->excludes(resume);
  sweep->add_flag("-q,--quiet", args.quiet, "No progress lines");
  sweep->add_option("-f,--format", args.format, "Final summary on stdout: table or json")
      ->check(CLI::IsMember({"table", "json"}))
      ->type_name("table|json")
      ->capture_default_str();
  sweep->footer(sweep_footer());
  return sweep;
}

std::string accuracy_footer() {
  return "The study solves the scene's point (a [sweep] section is ignored) once per case below,\n"
         "one case at a time, and compares each with a reference solve of the same point:\n"
         "  reference        dopri5 at rtol 1e-13, steady state by brute-force integration: the most\n"
         "                   conservative combination (no closed form, no Newton)\n"
         "  rk4              the source paper's classical fixed-step RK4 (contact force always in the\n"
         "                   right-hand side), 2^11 ... 2^15 steps per forcing period; steady state by\n"
         "                   integration. Its order collapses at contact.\n"
         "  dopri5           adaptive Dormand-Prince 5(4) with located contact events, rtol 1e-6, 1e-8,\n"
         "                   1e-10, 1e-12; steady state by integration (hundreds of periods at xi = 0.01)\n"
         "  hybrid+shooting  closed-form free flight between impacts, dopri5 only in contact; steady\n"
         "                   state by Newton's method on the stroboscopic map (shooting, falling back to\n"
         "                   integration), rtol 1e-6, 1e-8, 1e-10, 1e-12\n"
         "atol scales with rtol (the scene's atol/rtol ratio is kept); steady_tol and newton_tol follow\n"
         "each tolerance (auto). The scene's other keys (budgets, n_max, max_step, ...) apply to every\n"
         "case; its method and tolerances are replaced by the cases'.\n\n"
         "Columns: the method and its setting, status, regime, the steady-state method that gave the\n"
         "answer (Newton iterations), wall s (the solve time of that one point on one core, so the\n"
         "run takes about the sum of the column), right-hand side evaluations, forcing periods\n"
         "integrated, and the relative errors |x - x_ref|/|x_ref| of T_con (duration of the longest\n"
         "impact), F_max (peak contact force) and k_con = T/T_con. nan: undefined (no impact, or a\n"
         "failed solve). A regime other than the reference's is noted. --csv writes the same rows for\n"
         "scripts; postprocess/vmpy plot_work_precision FILE.csv draws error against time.\n\n" +
         main_footer();
}

CLI::App* add_accuracy(CLI::App& app, cli::AccuracyArgs& args) {
  CLI::App* acc = app.add_subcommand("accuracy", "Error against run time of rk4, dopri5 and hybrid+shooting on one point");
  acc->add_option("scene", args.scene, "Scene file (TOML)")->required()->type_name("SCENE");
  acc->add_option("-s,--set", args.sets, kSetHelp)
      ->allow_extra_args(false)
      ->type_name("SECTION.KEY=VALUE");
  acc->add_option("--csv", args.csv, "Also write the rows to FILE.csv (one line per case, reference first)")
      ->check(kOutputName)
      ->type_name("FILE.csv");
  acc->add_flag("--overwrite", args.overwrite, "Replace an existing CSV file");
  acc->add_option("-f,--format", args.format, "Output on stdout: a table for people or JSON for scripts")
      ->check(CLI::IsMember({"table", "json"}))
      ->type_name("table|json")
      ->capture_default_str();
  acc->add_flag("-q,--quiet", args.quiet, "No progress lines on stderr");
  acc->footer(accuracy_footer());
  return acc;
}

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
         "FILE.h5 holds every evaluation of every start (postprocess/vmpy plot_optimise FILE.h5 draws\n"
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
         "FILE.h5.journal left and no FILE.h5.\n\n" +
         main_footer();
}

CLI::App* add_optimise(CLI::App& app, cli::OptimiseArgs& args) {
  CLI::App* opt = app.add_subcommand("optimise", "Multistart optimisation of the softest impact on MPI ranks (NLopt)");
  opt->add_option("scene", args.scene, "Scene file (TOML) with an [optimise] section")->required()->type_name("SCENE");
  opt->add_option("-s,--set", args.sets, kSetHelp)
      ->allow_extra_args(false)
      ->type_name("SECTION.KEY=VALUE");
  opt->add_option("-o,--output", args.output, "Result file to write (default: the scene's name with _optimise.h5)")
      ->check(kOutputName)
      ->type_name("FILE.h5");
  auto* resume = opt->add_flag("--resume", args.resume, "Finish a stopped or killed run from its journal (FILE.h5.journal)");
  opt->add_flag("--overwrite", args.overwrite, "Replace an existing result file and recompute the seeding sweep")
      ->excludes(resume);
  opt->add_flag("-q,--quiet", args.quiet, "No progress lines");
  opt->add_option("-f,--format", args.format, "Output on stdout: a table for people or JSON for scripts")
      ->check(CLI::IsMember({"table", "json"}))
      ->type_name("table|json")
      ->capture_default_str();
  opt->footer(optimise_footer());
  return opt;
}

CLI::App* add_continue(CLI::App& app, cli::ContinueArgs& args) {
  CLI::App* c = app.add_subcommand("continue", "Follow a periodic orbit in one key: branch, stability, bifurcations");
  c->add_option("scene", args.scene, "Scene file (TOML)")->required()->type_name("SCENE");
  c->add_option("-s,--set", args.sets, kSetHelp)
      ->allow_extra_args(false)
      ->type_name("SECTION.KEY=VALUE");
  c->add_option("-p,--param", args.param, "The scene key to follow the orbit in: forcing.omega, omega, m2, ...")
      ->required()
      ->type_name("KEY");
  c->add_option("--from", args.from, "Start value of the key (SI units): the orbit from rest there is followed")
      ->check(kNumber)
      ->required()
      ->type_name("A");
  c->add_option("--to", args.to, "End value (either side of A)")->check(kNumber)->required()->type_name("B");
  c->add_option("--ds-max", args.ds_max, "Largest step along the branch (scaled arclength)")
      ->check(kNumber)
      ->capture_default_str();
  c->add_option("--max-points", args.max_points, "Points on each branch at most (2..1000000)")
      ->check(kNumber)
      ->capture_default_str();
  c->add_option("--pd-depth", args.pd_depth,
                "Period-doubling generations to switch onto: 0 none, 1 the doubled branches of the first, 2 also theirs, ...")
      ->check(kNumber & CLI::Range(0, 8))
      ->capture_default_str();
  c->add_option("-o,--output", args.output, "Branch file to write (HDF5; postprocess/vmpy plot_branch draws it)")
      ->check(kOutputName)
      ->type_name("FILE.h5");
  c->add_flag("--overwrite", args.overwrite, "Replace an existing branch file");
  c->add_flag("--points", args.points,
              "Table: print every point of every branch too (by default a summary: branches and bifurcations)");
  c->add_option("-f,--format", args.format, "Output on stdout: table or json")
      ->check(CLI::IsMember({"table", "json"}))
      ->type_name("table|json")
      ->capture_default_str();
  c->footer(
      "The scene's point with KEY = A is solved from rest; its periodic orbit (period n T) is\n"
      "followed by pseudo-arclength continuation on the shooting equations P^n(y) - y = 0, the\n"
      "state scaled by the motion's scale and the key by |B - A|, with step-size control. The\n"
      "branch goes through folds (it turns back in the key) and ends when it leaves [A, B]. At\n"
      "every point: Floquet multipliers and stability, the orbit's regime, k_con and F_max.\n"
      "Bifurcations are detected and located by bisection along the branch: fold (the branch\n"
      "turns), period-doubling (a multiplier through -1), neimark-sacker (a complex pair through\n"
      "the unit circle), grazing (the number of contacts per cycle changes: an impact appears\n"
      "or vanishes; the map is not smooth there, and the branch goes on across it with the new\n"
      "count). At each period doubling the doubled branch (period 2n T) is switched onto and\n"
      "followed until it leaves [A, B] or rejoins the period-n orbit, to --pd-depth generations.\n\n" +
      main_footer());
  return c;
}

CLI::App* add_orbit_diagram(CLI::App& app, cli::OrbitDiagramArgs& args) {
  CLI::App* od = app.add_subcommand("orbit-diagram",
                                    "Brute-force bifurcation diagram: step one key up and down, carrying the state");
  od->add_option("scene", args.scene, "Scene file (TOML)")->required()->type_name("SCENE");
  od->add_option("-s,--set", args.sets, kSetHelp)
      ->allow_extra_args(false)
      ->type_name("SECTION.KEY=VALUE");
  od->add_option("-p,--param", args.param, "The scene key to step: forcing.omega, omega, contact.E2, m2, ...")
      ->required()
      ->type_name("KEY");
  od->add_option("--from", args.from, "First value of the key (SI units)")->check(kNumber)->required()->type_name("A");
  od->add_option("--to", args.to, "Last value (> A)")->check(kNumber)->required()->type_name("B");
  od->add_option("-n,--steps", args.steps, "Points from A to B, both included")->check(kNumber)->capture_default_str();
  od->add_option("--scale", args.scale, "Spacing of the points")
      ->check(CLI::IsMember({"lin", "log"}))
      ->type_name("lin|log")
      ->capture_default_str();
  od->add_option("--transient", args.transient, "Forcing periods integrated at each point before states are kept")
      ->check(kNumber)
      ->capture_default_str();
  od->add_option("--keep", args.keep, "Stroboscopic states kept at each point")->check(kNumber)->capture_default_str();
  od->add_option("-o,--output", args.output, "HDF5 file of the kept states (none by default)")
      ->check(kOutputName)->type_name("FILE.h5");
  od->add_flag("--overwrite", args.overwrite, "Replace an existing file");
  od->add_flag("-q,--quiet", args.quiet, "No progress lines");
  od->add_option("-f,--format", args.format, "Output on stdout: table or json")
      ->check(CLI::IsMember({"table", "json"}))
      ->type_name("table|json")
      ->capture_default_str();
  od->footer(
      "The scene's point is stepped through N values of KEY, from A to B and back from B to A.\n"
      "At the first point the motion starts from the scene's initial state (rest unless [initial]\n"
      "says otherwise); at every next point it starts from the last state of the point before, so\n"
      "a branch is followed as far as it lives and the up and down sweeps differ where the\n"
      "response is multivalued (hysteresis). At each point TRANSIENT forcing periods are\n"
      "integrated, then KEEP stroboscopic states (at the period starts) are kept: one value for a\n"
      "period-1 motion, n for period n, a cloud for a chaotic one. The two directions run on two\n"
      "MPI ranks at once. KEY is checked as a [sweep] axis would be (vibromap keys). The table\n"
      "prints the range of x1 and the number of distinct x1 values per point and direction;\n"
      "--format json prints steps (param, direction, status, strobe_x1); -o writes every kept state\n"
      "(postprocess/vmpy plot_orbit_diagram FILE.h5 draws it).\n\n" +
      main_footer());
  return od;
}

std::string basins_footer() {
  return "A plane of initial states: the two --plane variables (of x1, x2, v1, v2: positions of the\n"
         "bodies in m, velocities in m/s) on an evenly spaced NxM grid (--grid, N along the first\n"
         "variable, 2..4096 each) spanning the scene's [census] box of each (census.x1 = [lo, hi], ...;\n"
         "by default the rest state +- the motion's scale, 'vibromap keys'); the other two variables\n"
         "are the rest state's (x1 = 0, x2 = D, v1 = v2 = 0) unless --at gives them (--at x2=0.06).\n"
         "Each pixel's state is followed to the attractor its motion settles into, as 'run --census'\n"
         "follows its initial states ([census] and [analysis] set the numerics): one follower per MPI\n"
         "rank keeps every attractor it found, so later pixels are decided early against them. A pixel\n"
         "with the bodies overlapping (x1 > x2) is not followed (label -3).\n\n"
         "FILE.h5 (CF-1.8, opens in xarray): label (the attractor index of each pixel; -1 unresolved,\n"
         "-2 unlisted, -3 overlap, -4 not computed), done, the two coordinates, and per attractor its\n"
         "regime, n, k, k_con, T_con, F_max, max_floquet, stable, soft, pixels, fraction and\n"
         "stroboscopic states. Attractors are numbered by pixel count, so the file does not depend on\n"
         "the number of ranks. postprocess/vmpy plot_basins FILE.h5 -o FILE.png draws it.\n\n"
         "The file is rewritten atomically every --checkpoint seconds; a run stopped (SIGINT, SIGTERM,\n"
         "SIGUSR1: exit code 3) or killed leaves the file of its last checkpoint, and --resume computes\n"
         "the rest. An existing FILE.h5 is replaced only with --overwrite.\n\n" +
         main_footer();
}

CLI::App* add_basins(CLI::App& app, cli::BasinsArgs& args) {
  CLI::App* b = app.add_subcommand("basins", "Basins of attraction on a plane of initial states, on MPI ranks");
  b->add_option("scene", args.scene, "Scene file (TOML)")->required()->type_name("SCENE");
  b->add_option("-s,--set", args.sets, kSetHelp)
      ->allow_extra_args(false)
      ->type_name("SECTION.KEY=VALUE");
  b->add_option("--plane", args.plane, "The two state variables of the plane (of x1, x2, v1, v2)")
      ->type_name("A,B")
      ->capture_default_str();
  b->add_option("--grid", args.grid, "Points along the first and the second plane variable (2..4096 each)")
      ->type_name("NxM")
      ->capture_default_str();
  b->add_option("--at", args.at, "Fix a variable outside the plane (repeatable; default: the rest state)")
      ->allow_extra_args(false)
      ->type_name("VAR=VALUE");
  b->add_option("-o,--output", args.output, "File to write (default: the scene's name with _basins.h5)")
      ->check(kOutputName)
      ->type_name("FILE.h5");
  auto* resume = b->add_flag("--resume", args.resume, "Continue an existing file of the same run");
  b->add_flag("--overwrite", args.overwrite, "Replace an existing file")->excludes(resume);
  b->add_option("--checkpoint", args.checkpoint, "Seconds between rewrites of the file")
      ->check(kNumber)
      ->type_name("SECONDS")
      ->capture_default_str();
  b->add_flag("-q,--quiet", args.quiet, "No progress lines");
  b->add_option("-f,--format", args.format, "Summary on stdout: table or json")
      ->check(CLI::IsMember({"table", "json"}))
      ->type_name("table|json")
      ->capture_default_str();
  b->footer(basins_footer());
  return b;
}

// The lower limits of e (restitution.hpp), as the restitution footer states them.
std::string restitution_limits() {
  std::ostringstream os;
  os << "Lower limit: the slow separation of a heavily damped impact lasts about chi^0.6 contact\n"
        "times, so chi(e) must be at most "
     << kMaxImpactDamping << ": e >= " << min_restitution(ContactLawKind::flores) << " for flores, e >= "
     << min_restitution(ContactLawKind::gonthier) << " for gonthier,\nany e > 0 for hunt-crossley and "
        "lankarani-nikravesh (chi <= 1.5). A smaller e is refused.\n\n";
  return os.str();
}

CLI::App* add_restitution(CLI::App& app, cli::RestitutionArgs& args) {
  CLI::App* r = app.add_subcommand("restitution", "Effective restitution of each contact law for a target e");
  r->add_option("--law", args.laws, "Contact law (repeatable; default: every dissipative law)")
      ->allow_extra_args(false)
      ->type_name("hunt-crossley|lankarani-nikravesh|flores|gonthier|hertz");
  r->add_option("--e", args.e,
                 "Target restitution in (0, 1] (repeatable; default 0.1, 0.2, ..., 1; flores and gonthier have a lower "
                 "limit, below)")
      ->check(kNumber)
      ->allow_extra_args(false)
      ->type_name("E");
  r->add_option("-f,--format", args.format, "Output on stdout: a table, or JSON (a list of {law, e, chi, e_effective})")
      ->check(CLI::IsMember({"table", "json"}))
      ->type_name("table|json")
      ->capture_default_str();
  r->footer("Each law's force is K z^1.5 (1 + chi w / v_in), chi calibrated from e (docs/model.md, 'Dissipative\n"
            "contact laws'). For two free bodies one impact depends on chi alone, so the effective\n"
            "restitution |v_out / v_in| is a property of the law and e: this command integrates that\n"
            "impact at rtol 1e-12, until the bodies part. postprocess/vmpy plot_restitution draws the\n"
            "JSON output.\n\n" + restitution_limits() + main_footer());
  return r;
}

CLI::App* add_keys(CLI::App& app, bool& as_toml) {
  CLI::App* keys = app.add_subcommand("keys", "List every scene key: default, unit, allowed values, meaning");
  keys->add_flag("--toml", as_toml, "Print a reference scene instead (every key with its default)");
  return keys;
}

int parse_error(const CLI::App& app, const CLI::ParseError& e) {
  if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
  const auto subs = app.get_subcommands();
  const std::string help = subs.empty() ? "vibromap --help" : "vibromap " + subs.front()->get_name() + " --help";
  return report(std::string(e.what()) + " (see '" + help + "')", ExitCode::bad_input);
}

// CLI11 reports an unknown command as a missing one; name it instead.
void check_command_name(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return;
  std::string names;
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (sub->check_name(argv[1])) return;
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  throw CLI::ExtrasError("unknown command '" + std::string(argv[1]) + "' (commands: " + names + ")",
                         CLI::ExitCodes::ExtrasError);
}

int dispatch(int argc, char** argv) {
  CLI::App app{"vibromap: explorer of a two-body vibro-impact system with Hertz contact", "vibromap"};
  app.set_version_flag("--version", std::string("vibromap ") + VIBROMAP_VERSION);
  app.require_subcommand(1);
  app.footer(main_footer());
  cli::RunArgs run_args;
  bool keys_toml = false;
  cli::SweepArgs sweep_args;
  cli::AccuracyArgs accuracy_args;
  cli::OptimiseArgs optimise_args;
  cli::OrbitDiagramArgs orbit_diagram_args;
  cli::ContinueArgs continue_args;
  cli::BasinsArgs basins_args;
  cli::RestitutionArgs restitution_args;
  const CLI::App* run = add_run(app, run_args);
  const CLI::App* sweep = add_sweep(app, sweep_args);
  const CLI::App* accuracy = add_accuracy(app, accuracy_args);
  const CLI::App* optimise = add_optimise(app, optimise_args);
  const CLI::App* orbit_diagram = add_orbit_diagram(app, orbit_diagram_args);
  const CLI::App* continuation = add_continue(app, continue_args);
  const CLI::App* basins = add_basins(app, basins_args);
  const CLI::App* restitution = add_restitution(app, restitution_args);
  add_keys(app, keys_toml);
  try {
    check_command_name(app, argc, argv);
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return parse_error(app, e);
  }
  if (run->parsed()) return cli::run_command(run_args, std::cout);
  if (sweep->parsed()) return cli::sweep_command(sweep_args, std::cout);
  if (accuracy->parsed()) return cli::accuracy_command(accuracy_args, std::cout);
  if (optimise->parsed()) return cli::optimise_command(optimise_args, std::cout);
  if (orbit_diagram->parsed()) return cli::orbit_diagram_command(orbit_diagram_args, std::cout);
  if (continuation->parsed()) return cli::continue_command(continue_args, std::cout);
  if (basins->parsed()) return cli::basins_command(basins_args, std::cout);
  if (restitution->parsed()) return cli::restitution_command(restitution_args, std::cout);
  return cli::keys_command(keys_toml, std::cout);
}

// The campaign commands honour SIGINT, SIGTERM and SIGUSR1 from the first instant (a final
// checkpoint, then exit 3): their handlers go in before anything else runs.
// `run --census` is one under an MPI launcher (its initial states go to the farm).
bool is_campaign(int argc, char** argv) {
  if (argc < 2) return false;
  const std::string_view command = argv[1];
  if (command == "run" && launched_by_mpi())
    for (int i = 2; i < argc; ++i)
      if (std::string_view(argv[i]) == "--census") return true;
  return command == "sweep" || command == "optimise" || command == "basins" || command == "orbit-diagram";
}

// Without a launcher (no mpirun, no srun) vibromap is an MPI singleton on one node: Open MPI
// then needs no network transport and no X display probe, which are what can make its start-up
// take seconds (the TCP transport grows with the number of network interfaces; hwloc's GL
// plugin tries displays :0-:9). A value already set in the environment wins. (Under a launcher
// the launcher's environment decides: jobs/demo/run.sh and jobs/cluster/sweep.slurm set it.)
void single_node_mpi_defaults() {
  if (launched_by_mpi()) return;
  ::setenv("OMPI_MCA_pml", "ob1", 0);
  ::setenv("OMPI_MCA_btl", "self,vader", 0);
  ::setenv("HWLOC_COMPONENTS", "-gl,-opencl", 0);
}

}  // namespace

int main(int argc, char** argv) {
  if (is_campaign(argc, argv)) {
    install_stop_handlers();
    single_node_mpi_defaults();
  }
  // A file-size limit (ulimit -f, a batch system's) must fail a write with EFBIG, which the
  // I/O layer reports as one line, not kill the process with SIGXFSZ.
  std::signal(SIGXFSZ, SIG_IGN);
  try {
    return dispatch(argc, argv);
  } catch (const QuietExit& e) {
    return e.code;
  } catch (const Cancelled&) {  // the farm turns these into a stopped run; this is the backstop
    return stopped_outside_a_farm();
  } catch (const ItemStopped&) {
    return stopped_outside_a_farm();
  } catch (const std::exception& e) {
    return report(e.what(), exit_code_of(std::current_exception()));
  } catch (...) {
    return report("unknown error", ExitCode::internal);
  }
}
