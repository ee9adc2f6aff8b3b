// `vibromap optimise`: a scene's [optimise] on all MPI ranks; starts and best points on stdout.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "command.hpp"
#include "commands.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/report.hpp"
#include "vibromap/io/scene/keys.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/campaigns/multistart/optimise_run.hpp"
#include "vibromap/parallel/mpi_session.hpp"
#include "vibromap/parallel/signals.hpp"
#include "vibromap/core/optimise/point_objective.hpp"

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

constexpr double kAgreeTol = 1e-6;  // relative k_con difference under which the two re-solves agree

std::string stem_path(const std::string& output) {
  const std::filesystem::path p(output);
  return (p.parent_path() / p.stem()).string();
}

std::string default_output(const std::string& scene_path) {
  return std::filesystem::path(scene_path).stem().string() + "_optimise.h5";
}

// One algorithm's starts taken together (every algorithm runs from the same seeds).
struct AlgorithmSummary {
  Algorithm algorithm = Algorithm::bobyqa;
  int starts = 0;
  long evaluations = 0;
  double wall_s = 0.0;                                         // sum over its starts, s
  double best = std::numeric_limits<double>::quiet_NaN();      // best objective (quantity), NaN: none feasible
};

std::vector<AlgorithmSummary> by_algorithm(const OptimiseReport& r, const OptimiseOptions& o) {
  std::vector<AlgorithmSummary> out;
  for (const Algorithm a : o.algorithms) {
    AlgorithmSummary sum{a};
    double best_value = std::numeric_limits<double>::infinity();
    for (const StartRecord& s : r.starts) {
      if (s.spec.algorithm != a) continue;
      ++sum.starts;
      sum.evaluations += static_cast<long>(s.result.evaluations.size());
      sum.wall_s += s.result.wall_s;
      if (s.result.best) best_value = std::min(best_value, s.result.evaluations[*s.result.best].result.value);
    }
    if (std::isfinite(best_value)) sum.best = objective_sense(o.objective) * best_value;
    out.push_back(sum);
  }
  return out;
}

bool solves_agree(const VerifiedPoint& v) {
  return v.integrate.regime == v.shooting.regime && v.integrate.stable == v.shooting.stable &&
         std::abs(v.integrate.k_con - v.shooting.k_con) <= kAgreeTol * std::abs(v.integrate.k_con);
}

void write_solve_json(JsonWriter& w, const PointSummary& s) {
  w.begin_object().field("status", to_string(s.status)).field("regime", s.regime.label());
  write_stable_json(w.key("stable"), s.stable);
  w.field("k_con", s.k_con).field("T_con", s.T_con).field("F_max", s.F_max).field("z_ratio", s.z_ratio);
  w.field("max_multiplier", max_multiplier(s)).field("periods", s.periods).field("wall_s", s.wall_s).end_object();
}

// The lowest re-checked fraction that passes the soft check.
double soft_threshold(const SoftCheck& c, const OptimiseOptions& o) {
  return o.min_soft_fraction - kSoftCheckSigmas * c.fraction_stderr;
}

void write_soft_check_json(JsonWriter& w, const VerifiedPoint& v, const OptimiseOptions& o) {
  w.field("soft_fraction", v.soft_fraction).key("soft_check");
  if (!v.soft_check) {
    w.null();
    return;
  }
  const SoftCheck& c = *v.soft_check;
  w.begin_object().field("status", to_string(c.census.status)).field("initial_conditions", c.census.K);
  w.field("seed", c.seed).field("soft_fraction", c.fraction).field("soft_fraction_stderr", c.fraction_stderr);
  w.field("threshold", soft_threshold(c, o)).field("passed", c.passed).key("orbit_attractor");
  if (c.orbit_attractor < 0) {
    w.null();
  } else {
    w.value(c.orbit_attractor);
  }
  w.field("orbit_fraction", c.orbit_fraction).field("wall_s", c.census.wall_s).key("attractors").begin_array();
  for (const Attractor& a : c.census.attractors) {
    w.begin_object().field("regime", a.regime.label()).field("k_con", a.k_con).field("fraction", a.fraction);
    w.field("fraction_stderr", a.fraction_stderr).field("hertz_valid", a.hertz_valid);
    write_stable_json(w.key("stable"), a.stable).field("soft", a.soft).end_object();
  }
  w.end_array().end_object();
}

// A start's algorithm, and its law when the law is free.
std::string start_label(const StartSpec& s) {
  return s.law ? to_string(s.algorithm) + " " + to_string(*s.law) : to_string(s.algorithm);
}

void write_best_json(JsonWriter& w, const OptimiseReport& r, const VerifiedPoint& v, const OptimiseOptions& o) {
  const PointSummary& s = v.integrate;
  w.begin_object().key("params").begin_object();
  for (const std::string_view name : {"m2", "k2", "omega2", "E1", "E2", "R1", "R2"})
    w.field(name, get_parameter(v.params, name));
  w.end_object().field("k_con", s.k_con).field("T_con", s.T_con).field("F_max", s.F_max).field("regime", s.regime.label());
  write_stable_json(w.key("stable"), s.stable);
  w.field("z_ratio", s.z_ratio).field("hertz_valid", s.hertz_valid).field("soft", s.soft);
  w.field("objective_found", objective_sense(o.objective) * v.value).field("start", v.start);
  w.field("algorithm", to_string(r.starts.at(static_cast<std::size_t>(v.start)).spec.algorithm));
  w.field("law", to_string(v.params.law)).field("restitution", v.params.restitution);
  w.key("set").begin_array();
  for (const std::string& arg : optimised_overrides(v.params, o)) w.value(arg);
  w.end_array().key("integrate");
  write_solve_json(w, v.integrate);
  w.key("shooting");
  write_solve_json(w, v.shooting);
  w.field("agree", solves_agree(v));
  write_soft_check_json(w, v, o);
  w.end_object();
}

void write_starts_json(JsonWriter& w, const OptimiseReport& r, const OptimiseOptions& o) {
  w.key("starts").begin_array();
  for (const StartRecord& s : r.starts) {
    const LocalResult& lr = s.result;
    w.begin_object().field("start", s.spec.index).field("seed", s.spec.seed).field("algorithm", to_string(s.spec.algorithm));
    if (s.spec.law) w.field("law", to_string(*s.spec.law));
    w.field("evaluations", lr.evaluations.size()).field("cache_hits", lr.cache_hits).field("calls", lr.calls);
    w.key("best_objective");
    if (lr.best) {
      w.value(objective_sense(o.objective) * lr.evaluations[*lr.best].result.value);
    } else {
      w.null();
    }
    w.field("stop", lr.stop).field("nlopt_code", lr.nlopt_code).field("rank", s.rank).field("wall_s", lr.wall_s).end_object();
  }
  w.end_array();
}

void write_algorithms_json(JsonWriter& w, const OptimiseReport& r, const OptimiseOptions& o) {
  w.key("algorithms").begin_array();
  for (const AlgorithmSummary& a : by_algorithm(r, o)) {
    w.begin_object().field("algorithm", to_string(a.algorithm)).field("starts", a.starts);
    w.field("evaluations", a.evaluations).field("best_objective", a.best).field("wall_s", a.wall_s).end_object();
  }
  w.end_array();
}

void print_json(std::ostream& out, const OptimiseRun& run, const OptimiseOptions& o, const std::string& output) {
  const OptimiseReport& r = run.report;
  JsonWriter w(out);
  w.begin_object().field("output", output).field("seeds_from", r.seeds_from).field("trajectory", r.trajectory_file);
  w.field("objective", to_string(o.objective)).field("quantity", objective_quantity(o.objective));
  w.field("regime", o.regime ? o.regime->label() : std::string("any")).field("stability", to_string(o.stability));
  w.field("hertz_valid", o.hertz_valid).field("min_soft_fraction", o.min_soft_fraction);
  w.field("soft_check_initial_conditions", o.soft_check_initial_conditions);
  w.field("ranks", r.ranks).field("seeds", r.seeds.size()).field("evaluations", r.evaluations());
  w.field("starts_resumed", run.starts_resumed).field("sweep_cells_computed", run.sweep.items_computed);
  w.field("wall_s", r.wall_s).field("sweep_wall_s", r.sweep_wall_s).field("optimise_wall_s", r.optimise_wall_s);
  w.field("verify_wall_s", r.verify_wall_s);
  write_starts_json(w, r, o);
  write_algorithms_json(w, r, o);
  w.key("best").begin_array();
  for (const VerifiedPoint& v : r.best) write_best_json(w, r, v, o);
  w.end_array().end_object();
  out << "\n";
}

// A cell of the starts' tables: padded to `width`, then one space.
std::string cell(const std::string& s, std::size_t width) { return pad_right(s, width) + " "; }

void print_starts_table(std::ostream& out, const OptimiseReport& r, const OptimiseOptions& o) {
  const std::string q = objective_quantity(o.objective);
  const int label = o.laws.empty() ? 20 : 40;
  out << cell("start", 6) << cell("seed", 5) << cell(o.laws.empty() ? "algorithm" : "algorithm law", label)
      << cell("evals", 6) << cell("hits", 6)
      << cell("best " + q, 12) << cell("stop", 18) << "wall s\n";
  for (const StartRecord& s : r.starts) {
    const LocalResult& lr = s.result;
    const std::string best = lr.best ? number(objective_sense(o.objective) * lr.evaluations[*lr.best].result.value) : "-";
    out << cell(std::to_string(s.spec.index), 6) << cell(std::to_string(s.spec.seed), 5)
        << cell(start_label(s.spec), label) << cell(std::to_string(lr.evaluations.size()), 6)
        << cell(std::to_string(lr.cache_hits), 6) << cell(best, 12) << cell(lr.stop, 18) << number(lr.wall_s, 3) << "\n";
  }
}

// With the law free: the best objective each law reached, from the same seeds and algorithms.
void print_laws_table(std::ostream& out, const OptimiseReport& r, const OptimiseOptions& o) {
  if (o.laws.empty()) return;
  out << "\nper contact law, from the same seeds and algorithms:\n"
      << cell("law", 22) << cell("starts", 7) << "best " << objective_quantity(o.objective) << "\n";
  for (const ContactLawKind law : o.laws) {
    int starts = 0;
    double best = std::numeric_limits<double>::infinity();
    for (const StartRecord& s : r.starts) {
      if (s.spec.law != law) continue;
      ++starts;
      if (s.result.best) best = std::min(best, s.result.evaluations[*s.result.best].result.value);
    }
    out << cell(to_string(law), 22) << cell(std::to_string(starts), 7)
        << (std::isfinite(best) ? number(objective_sense(o.objective) * best) : std::string("- (none feasible)")) << "\n";
  }
}

void print_algorithms_table(std::ostream& out, const OptimiseReport& r, const OptimiseOptions& o) {
  out << "\nper algorithm, from the same seeds:\n"
      << cell("algorithm", 20) << cell("starts", 7) << cell("best " + objective_quantity(o.objective), 12)
      << cell("evaluations", 12) << "wall s (sum of its starts)\n";
  for (const AlgorithmSummary& a : by_algorithm(r, o)) {
    out << cell(to_string(a.algorithm), 20) << cell(std::to_string(a.starts), 7)
        << cell(std::isnan(a.best) ? "-" : number(a.best), 12) << cell(std::to_string(a.evaluations), 12)
        << number(a.wall_s, 3) << "\n";
  }
}

// A best point's soft fraction: the optimiser's census, the re-check, its verdict, and the
// soft attractors (which the optimised orbit is among them, when it is).
void print_soft_check(std::ostream& out, const VerifiedPoint& v, const OptimiseOptions& o) {
  if (!v.soft_check) return;
  const SoftCheck& c = *v.soft_check;
  out << "soft fraction  " << number(v.soft_fraction, 4) << " (optimiser's census); re-check of "
      << c.census.K << " other initial states: " << number(c.fraction, 4) << " +- " << number(c.fraction_stderr, 2);
  if (c.census.status != SolveStatus::ok) {
    out << "  FAILS THE SOFT CHECK: the census failed (" << c.census.message << ")\n    ";
  } else if (c.passed) {
    out << "  passes (>= " << number(o.min_soft_fraction) << " - 3 stderr = " << number(soft_threshold(c, o), 4)
        << ")\n    ";
  } else {
    out << "  FAILS THE SOFT CHECK (< " << number(o.min_soft_fraction) << " - 3 stderr = "
        << number(soft_threshold(c, o), 4) << ")\n    ";
  }
  out << "soft attractors:";
  bool any = false;
  for (std::size_t i = 0; i < c.census.attractors.size(); ++i) {
    const Attractor& a = c.census.attractors[i];
    if (!a.soft) continue;
    out << (any ? ";" : "") << " " << a.regime.label() << " k_con " << number(a.k_con) << " fraction "
        << number(a.fraction, 4) << (static_cast<int>(i) == c.orbit_attractor ? " (the optimised orbit)" : "");
    any = true;
  }
  if (!any) out << " none";
  if (c.orbit_attractor < 0) {
    out << "; the optimised orbit is not among the census's attractors";
  } else if (!c.census.attractors[static_cast<std::size_t>(c.orbit_attractor)].soft) {
    out << "; the optimised orbit (fraction " << number(c.orbit_fraction, 4) << ") is not soft";
  }
  out << "\n    ";
}

void print_best_table(std::ostream& out, const OptimiseReport& r, const OptimiseOptions& o) {
  out << "\nbest points, re-solved from scratch at rtol " << number(o.verify_rtol) << " (brute force from rest; shooting)"
      << (o.min_soft_fraction > 0.0 ? ", those that pass the soft check first" : "") << ":\n";
  for (std::size_t i = 0; i < r.best.size(); ++i) {
    const VerifiedPoint& v = r.best[i];
    const PointSummary& s = v.integrate;
    out << "#" << i << "  k_con " << number(s.k_con) << "  T_con " << number(s.T_con) << " s  F_max " << number(s.F_max)
        << " N  regime " << s.regime.label() << " " << stability_text(s.stable) << "  (shooting: k_con "
        << number(v.shooting.k_con) << ", " << v.shooting.regime.label() << " " << stability_text(v.shooting.stable)
        << (solves_agree(v) ? ", agrees" : ", DISAGREES") << ")  start " << v.start << "\n    ";
    if (!s.hertz_valid)
      out << "HERTZ-INVALID: z_max/R* = " << number(s.z_ratio, 3)
          << " beyond [analysis] hertz_limit: the force law does not hold there (optimise.hertz_valid = false)\n    ";
    out << "soft " << (s.soft ? "yes" : "no") << " (periodic with impacts, stable, Hertz-valid, k_con <= analysis.soft_kcon)\n    ";
    print_soft_check(out, v, o);
    for (const std::string_view name : {"m2", "k2", "omega2", "E1", "E2", "R1", "R2"})
      out << name << " " << number(get_parameter(v.params, name)) << "  ";
    out << "law " << to_string(v.params.law);
    if (v.params.law != ContactLawKind::hertz) out << " (restitution " << number(v.params.restitution) << ")";
    out << "\n    --set:";
    for (const std::string& arg : optimised_overrides(v.params, o)) out << " " << arg;
    out << "\n";
  }
  if (r.best.empty()) {
    out << "(no start found a feasible point)\n";
    if (o.min_soft_fraction > 0.0 && !o.hertz_valid)
      out << "(min_soft_fraction counts Hertz-valid attractors only: with hertz_valid = true the seeds and the "
             "search keep Hertz theory valid too)\n";
  }
  if (!r.best.empty() && r.best.front().soft_check && !r.best.front().soft_check->passed)
    out << "NO BEST POINT PASSES THE SOFT CHECK: none is shown to hold min_soft_fraction " << number(o.min_soft_fraction)
        << " of the basin\n";
}

void print_table(std::ostream& out, const OptimiseReport& r, const OptimiseOptions& o, const std::string& output) {
  out << "output         " << output << "\n"
      << "objective      " << to_string(o.objective) << ", keeping " << (o.regime ? o.regime->label() : "any regime")
      << " (stability " << to_string(o.stability) << (o.hertz_valid ? ", Hertz theory valid" : "") << ")\n";
  if (o.min_soft_fraction > 0.0)
    out << "robust         soft attractors hold >= " << number(o.min_soft_fraction)
        << " of the basin (a census per feasible point; the best points re-checked)\n";
  out << "seeds          " << r.seeds.size() << " from " << r.seeds_from << "\n"
      << "starts         " << r.starts.size() << " on " << r.ranks << (r.ranks == 1 ? " rank, " : " ranks, ")
      << r.evaluations() << " evaluations\n"
      << "wall time      " << number(r.wall_s, 4) << " s (sweep " << number(r.sweep_wall_s, 4) << ", starts "
      << number(r.optimise_wall_s, 4) << ", re-solves " << number(r.verify_wall_s, 4) << ")\n";
  if (!r.trajectory_file.empty()) out << "trajectory     " << r.trajectory_file << "\n";
  out << "\n";
  print_starts_table(out, r, o);
  print_algorithms_table(out, r, o);
  print_laws_table(out, r, o);
  print_best_table(out, r, o);
}

}  // namespace

std::string optimise_map_path(const std::string& output) { return stem_path(output) + "_map.h5"; }
std::string optimise_trajectory_path(const std::string& output) { return stem_path(output) + "_trajectory.h5"; }

std::string optimise_journal_path(const std::string& output) { return output + ".journal"; }

int optimise_command(const OptimiseArgs& args, std::ostream& out) {
  const MpiSession mpi;
  const Scene scene = load_scene_everywhere(mpi, args.scene, args.sets);
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
  if (args.format == "json") {
    print_json(out, run, *scene.optimise, config.output);
  } else {
    print_table(out, run.report, *scene.optimise, config.output);
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
