// `vibromap continue`: the arguments and the exit; the campaign is
// campaigns/continuation/continuation_run.hpp, the output io/branch_output.hpp.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <ostream>

#include "command.hpp"
#include "commands.hpp"
#include "vibromap/campaigns/continuation/continuation_run.hpp"
#include "vibromap/campaigns/continuation/curve_run.hpp"
#include "vibromap/core/integrate/cancel.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/branch_output.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/parallel/signals.hpp"

namespace vibromap::cli {

// `vibromap continue SCENE --param KEY --from A --to B [--format table|json] [--set ...]`: the
// periodic orbit the scene's point settles into from rest at KEY = A, followed to B by
// pseudo-arclength continuation (core/analysis/continuation/continuation.hpp). One process.
struct ContinueArgs {
  std::string scene;
  std::vector<std::string> sets;
  std::string param;
  double from = 0.0, to = 0.0;
  double ds_max = 0.05;          // largest step along the branch (scaled arclength)
  int max_points = 5000;         // per branch
  int pd_depth = 1;              // period-doubling generations switched onto (0: none)
  std::string output;            // branch file (HDF5); empty: none
  bool overwrite = false;        // replace an existing branch file
  bool points = false;           // table: every point of every branch too (json always has them)
  std::string format = "table";
  std::vector<std::string> curves;  // --curve KIND: curves in (param, param2)
  std::string param2;
  double from2 = NAN, to2 = NAN;
  bool has_param2 = false, has_from2 = false, has_to2 = false;  // given (a given value may be empty or
                                                                // non-finite: refused as such)
};
int continue_command(const ContinueArgs& args, std::ostream& out);

namespace {

// What the table says besides the report: the key, its range as asked, the file, --points.
BranchTable branch_table(const ContinueArgs& args, const std::string& key) {
  return {.key = key, .from = args.from, .to = args.to, .file = args.output, .points = args.points};
}

// The --curve options: KIND parsed, --param2/--from2/--to2 given with it (and only with it).
std::vector<CurveSpec> curve_specs(const ContinueArgs& args) {
  const bool any2 = args.has_param2 || args.has_from2 || args.has_to2;
  if (args.curves.empty()) {
    if (any2) throw SceneError("--param2/--from2/--to2: only with --curve KIND");
    return {};
  }
  if (!args.has_param2 || !args.has_from2 || !args.has_to2)
    throw SceneError("--curve: needs --param2 KEY --from2 C --to2 D (the second key and its range)");
  if (args.param2.empty()) throw SceneError("--param2 '': names no key (the second key: forcing.F0, contact.E1, ...)");
  for (const auto& [option, value] : {std::pair{"--from2", args.from2}, std::pair{"--to2", args.to2}})
    if (!std::isfinite(value))
      throw SceneError(cat(option, " ", number(value, 12), ": not a finite number (an end of --param2's range)"));
  if (!(args.from2 < args.to2))
    throw SceneError(cat("--from2 ", number(args.from2, 12), " --to2 ", number(args.to2, 12),
                         ": need finite values with --from2 < --to2"));
  if (!std::isfinite(args.to2 - args.from2))
    throw SceneError(cat("--from2 ", number(args.from2, 12), " --to2 ", number(args.to2, 12),
                         ": the span D - C must be finite (it scales the key)"));
  std::vector<CurveSpec> specs;
  for (const std::string& text : args.curves) {
    std::string error;
    const std::optional<CurveSpec> spec = parse_curve_spec(text, error);
    if (!spec) throw SceneError("--curve " + error);  // "--curve KIND: what is wrong"
    specs.push_back(*spec);
  }
  return specs;
}

// The exit of a run: ExitCode::ok, or when a stop signal ended it early (continuation_run.hpp)
// one line on stderr saying what was kept, and ExitCode::stopped.
int continue_exit(const ContinueArgs& args, const ContinuationReport& r, const CurvesReport* curves = nullptr) {
  if (r.stop_signal == 0) return code(ExitCode::ok);
  std::size_t points = 0;
  for (const Branch& b : r.branches) points += b.points.size();
  if (curves)
    for (const MeasuredCurve& c : curves->curves) points += c.curve.points.size();
  const std::string name = signal_name(r.stop_signal);
  const bool branch_file = curves && curves->branch_file && !args.output.empty();
  std::cerr << "vibromap: stopped by " << name << " after " << points << " points"
            << (curves && curves->curves.empty() ? ", before the first curve" : "") << ": "
            << (args.output.empty() ? "the output above holds" : "the output above and " + args.output + " hold")
            << " the continuation so far" << (branch_file ? " (" + args.output + ": a branch file, the branch so far)" : "")
            << " (stop: 'stopped by " << name << "'); continue has no --resume: run it again to go on\n";
  return code(ExitCode::stopped);
}

// The axis of --param (or --param2) over [lo, hi]: a parameter key, both ends checked against it.
CommandAxis param_axis(const std::string& option, const std::string& name, double a, double b) {
  return command_axis(cat(option, " ", clip(name)), name, {std::min(a, b), std::max(a, b)}, AxisScale::lin, true);
}

Scene load_continue_scene(const ContinueArgs& args, const std::vector<std::string>& sets,
                          const std::vector<CommandAxis>& axes) {
  return load_scene(args.scene, sets, axes);
}

int continue_curves(const ContinueArgs& args, const ContinuationConfig& config, std::vector<CurveSpec> specs,
                    std::ostream& out) {
  const SceneLoader load = [&](const auto& sets, const auto& axes) { return load_continue_scene(args, sets, axes); };
  const ParamScene2 ps = scene_with_params(load, args.sets, param_axis("--param", args.param, args.from, args.to),
                                           param_axis("--param2", args.param2, args.from2, args.to2));
  const CurvesReport r = run_curves(ps.scene, ps.axis, ps.axis2, config, {std::move(specs), args.from2, args.to2});
  if (args.format == "json") {
    write_branch_json(out, ps.axis.key, r.branch, &r);
  } else {
    write_branch_table(out, r.branch, branch_table(args, ps.axis.key));
    write_curves_table(out, ps.axis.key, ps.axis2.key, r);
  }
  out.flush();
  return continue_exit(args, r.branch, &r);
}

int continue_branch_or_curves(const ContinueArgs& args, std::ostream& out) {
  if (!(std::isfinite(args.from) && std::isfinite(args.to) && args.from != args.to))
    throw SceneError(cat("--from ", number(args.from, 12), " --to ", number(args.to, 12), ": need finite, different values"));
  if (!std::isfinite(args.to - args.from))
    throw SceneError(cat("--from ", number(args.from, 12), " --to ", number(args.to, 12),
                         ": the span B - A must be finite (it scales the key)"));
  std::vector<CurveSpec> specs = curve_specs(args);
  ContinuationConfig config;
  config.from = args.from;
  config.to = args.to;
  config.ds_max = args.ds_max;
  config.max_points = args.max_points;
  config.pd_depth = args.pd_depth;
  config.output = args.output;
  config.overwrite = args.overwrite;
  if (!specs.empty()) return continue_curves(args, config, std::move(specs), out);
  const SceneLoader load = [&](const auto& sets, const auto& axes) { return load_continue_scene(args, sets, axes); };
  const ParamScene ps = scene_with_param(load, args.sets, param_axis("--param", args.param, args.from, args.to));
  const ContinuationReport report = run_continuation(ps.scene, ps.axis, config);
  if (args.format == "json") {
    write_branch_json(out, ps.axis.key, report);
  } else {
    write_branch_table(out, report, branch_table(args, ps.axis.key));
  }
  out.flush();
  return continue_exit(args, report);
}

}  // namespace

// A stop signal while the start orbit was solved (continuation_run.hpp): one line, exit 3.
int continue_command(const ContinueArgs& args, std::ostream& out) {
  try {
    return continue_branch_or_curves(args, out);
  } catch (const Cancelled&) {
    std::cerr << "vibromap: stopped by " << signal_name(stop_signal()) << " while solving the start orbit at "
              << args.param << " = " << number(args.from, 12) << ": no point found, nothing written\n";
    return code(ExitCode::stopped);
  }
}

namespace {

std::string continue_footer() {
  return
      "The scene's point with KEY = A is solved from rest; its periodic orbit (period n T) is\n"
      "followed by pseudo-arclength continuation on the shooting equations P^n(y) - y = 0, the\n"
      "state scaled by the motion's scale and the key by |B - A|, with step-size control. A key\n"
      "whose ends are both positive and B/A or A/B >= 100 is continued in ln KEY, scaled by\n"
      "|ln(B/A)|, so that every decade gets its steps (the same rule for KEY2 over [C, D]); all\n"
      "values printed and written stay in the key's own units. The branch goes through folds\n"
      "(it turns back in the key) and ends when it leaves [A, B]. A\n"
      "point is corrected by Newton until the scaled residual |P^n(y) - y| is at most the scene's\n"
      "analysis.newton_tol (0: 10 solver.rtol, 1e-9 at the defaults), as shooting's. At\n"
      "every point: Floquet multipliers and stability, the orbit's regime, k_con and F_max.\n"
      "Bifurcations are detected and located by bisection along the branch: fold (the branch\n"
      "turns), period-doubling (a multiplier through -1), neimark-sacker (a complex pair through\n"
      "the unit circle), grazing (the number of contacts per cycle changes: an impact appears\n"
      "or vanishes; the map is not smooth there, and the branch goes on across it with the new\n"
      "count). At each period doubling the doubled branch (period 2n T) is switched onto and\n"
      "followed until it leaves [A, B] or rejoins the period-n orbit, to --pd-depth generations.\n"
      "\n"
      "With --curve KIND --param2 KEY2 --from2 C --to2 D, every KIND point on the branch (at the\n"
      "scene's KEY2) is then followed as a curve in (KEY, KEY2) while KEY2 stays in [C, D] and KEY in\n"
      "[A, B], both ways: pseudo-arclength on the extended system P^n(y) - y = 0, g = 0, with g\n"
      "det(M - I) (fold), det(M + I) (period-doubling), |mu|^2 - 1 of the complex pair nearest the\n"
      "unit circle (neimark-sacker), the signed clearance of the approach that touches (grazing:\n"
      "a closest approach's gap, or minus a contact's peak penetration), or NAME - VALUE\n"
      "(level:NAME=VALUE, NAME one of k_con, T_con, F_max, z_ratio; level points are located on the\n"
      "branch where NAME crosses VALUE). Along each curve the other kinds' test functions are\n"
      "watched and their changes located (codimension-two points). The table gives one summary per\n"
      "curve, --format json adds `curves` (every point), -o writes the curve file instead of the\n"
      "branch file (docs/file-formats.md).\n"
      "\n"
      "SIGINT, SIGTERM or SIGUSR1 end the run before its next point: the points found so far are\n"
      "printed and written (-o, a whole file), the branch or curve cut short with stop 'stopped by\n"
      "SIGTERM' (the signal's name), and the exit code is 3 with one line on stderr; continue has\n"
      "no --resume (run it again). A stop while the start orbit is solved writes nothing; with\n"
      "--curve, a stop before the first curve writes the branch so far to -o's file (a branch file).";
}

}  // namespace

Command declare_continue(CLI::App& app) {
  auto args = std::make_shared<ContinueArgs>();
  CLI::App* c = app.add_subcommand("continue", "Follow a periodic orbit in one key: branch, stability, bifurcations");
  add_scene_options(*c, args->scene, args->sets, "Scene file (TOML)");
  c->add_option("-p,--param", args->param, "The scene key to follow the orbit in: forcing.omega, omega, m2, ...")
      ->required()
      ->type_name("KEY");
  c->add_option("--from", args->from, "Start value of the key (SI units): the orbit from rest there is followed")
      ->check(kNumber)
      ->required()
      ->type_name("A");
  c->add_option("--to", args->to, "End value (either side of A)")->check(kNumber)->required()->type_name("B");
  c->add_option("--ds-max", args->ds_max, "Largest step along the branch (scaled arclength)")
      ->check(kNumber)
      ->capture_default_str();
  c->add_option("--max-points", args->max_points, "Points on each branch at most (2..1000000)")
      ->check(kNumber)
      ->capture_default_str();
  c->add_option("--pd-depth", args->pd_depth,
                "Period-doubling generations to switch onto: 0 none, 1 the doubled branches of the first, 2 also theirs, ...")
      ->check(kNumber & CLI::Range(0, 8))
      ->capture_default_str();
  add_output_option(*c, "-o,--output", args->output,
                    "Branch file to write (HDF5; vibromap-post plot_branch draws it); with --curve, the curve file");
  c->add_flag("--overwrite", args->overwrite, "Replace an existing branch file");
  c->add_flag("--points", args->points,
              "Table: print every point of every branch too (by default a summary: branches and bifurcations)");
  c->add_option("--curve", args->curves,
                "Also follow every KIND point of the branch in (KEY, KEY2): fold, period-doubling, neimark-sacker, "
                "grazing or level:NAME=VALUE (NAME k_con, T_con, F_max, z_ratio); may be repeated")
      ->type_name("KIND");
  c->add_option("--param2", args->param2, "With --curve: the second key (a model parameter: forcing.F0, contact.E1, ...)")
      ->type_name("KEY2")
      ->each([args](const std::string&) { args->has_param2 = true; });
  c->add_option("--from2", args->from2, "With --curve: the second key's lower end (SI units)")
      ->check(kNumber)
      ->type_name("C")
      ->each([args](const std::string&) { args->has_from2 = true; });
  c->add_option("--to2", args->to2, "With --curve: its upper end (> C; the scene's value must lie in [C, D])")
      ->check(kNumber)
      ->type_name("D")
      ->each([args](const std::string&) { args->has_to2 = true; });
  add_format_option(*c, args->format, "Output on stdout: table or json");
  return {.app = c, .footer = continue_footer(), .topic = "the continuation of a periodic orbit",
          .campaign = always_campaign,  // one process, but a stop signal ends it cleanly (continue_exit)
          .run = [args](std::ostream& out) { return continue_command(*args, out); }};
}

}  // namespace vibromap::cli
