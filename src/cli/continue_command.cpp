// `vibromap continue`: the arguments and the printing; the campaign is
// campaigns/continuation/continuation_run.hpp (see commands.hpp).

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <ostream>
#include <sstream>

#include "command.hpp"
#include "commands.hpp"
#include "vibromap/campaigns/continuation/continuation_run.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/report.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap::cli {

// `vibromap continue SCENE --param KEY --from A --to B [--format table|json] [--set ...]`: the
// periodic orbit the scene's point settles into from rest at KEY = A, followed to B by
// pseudo-arclength continuation (core/analysis/continuation.hpp). One process.
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
};
int continue_command(const ContinueArgs& args, std::ostream& out);

namespace {

using Measured = MeasuredPoint;  // a branch point and its orbit, measured as `run` measures it

void multipliers_json(JsonWriter& w, const std::vector<std::complex<double>>& mu) {
  w.key("multipliers").begin_array();
  for (const auto& m : mu) w.begin_array().value(m.real()).value(m.imag()).end_array();
  w.end_array();
}

double largest(const std::vector<std::complex<double>>& mu) { return mu.empty() ? NAN : std::abs(mu.front()); }

void points_json(JsonWriter& w, const std::vector<Measured>& points) {
  w.key("points").begin_array();
  for (const Measured& m : points) {
    w.begin_object().field("param", m.point.param).field("stable", m.point.stable);
    multipliers_json(w, m.point.multipliers);
    w.field("T_con", m.orbit.T_con).field("k_con", m.orbit.k_con).field("F_max", m.orbit.F_max);
    w.field("impacts", static_cast<long>(m.orbit.impacts.size()));
    w.field("x1_max", m.point.x1_max).field("x2_max", m.point.x2_max).field("clearance_min", m.point.clearance_min);
    w.field("regime", m.orbit.regime.label());
    write_state_json(w.key("y"), m.point.y);
    w.key("strobe_x1").begin_array();
    for (const Eigen::Vector4d& x : m.point.strobe) w.value(x[0]);
    w.end_array().end_object();
  }
  w.end_array();
}

void bifurcations_json(JsonWriter& w, const std::vector<Bifurcation>& bifurcations) {
  w.key("bifurcations").begin_array();
  for (const Bifurcation& b : bifurcations) {
    w.begin_object().field("type", to_string(b.type)).field("param", b.at.param);
    multipliers_json(w, b.at.multipliers);
    write_state_json(w.key("y"), b.at.y);
    w.end_object();
  }
  w.end_array();
}

void bifurcations_table(std::ostream& out, const std::string& key, const std::vector<Bifurcation>& bifurcations) {
  for (const Bifurcation& b : bifurcations)
    out << "  " << std::setw(16) << to_string(b.type) << "  " << key << " = " << std::setprecision(10) << b.at.param
        << "  max|mu| " << std::setprecision(6) << largest(b.at.multipliers) << "\n";
}

double born_at_param(const std::vector<Branch>& branches, const Branch& s) {
  return branches[static_cast<std::size_t>(s.parent)].bifurcations[static_cast<std::size_t>(s.born_at)].at.param;
}

// One line per branch: its period, first and last key value, points and why it stopped.
void branches_table(std::ostream& out, const std::vector<Branch>& branches, bool points_shown) {
  out << "\n  " << std::setw(6) << "branch" << "  " << std::setw(6) << "period" << "  " << std::setw(16) << "from"
      << "  " << std::setw(16) << "to" << "  " << std::setw(6) << "points" << "  stopped"
      << (points_shown ? "" : "   (every point: --points, or --format json)") << "\n";
  for (std::size_t i = 0; i < branches.size(); ++i) {
    const Branch& b = branches[i];
    const double first = b.points.empty() ? NAN : b.points.front().param;
    const double last = b.points.empty() ? NAN : b.points.back().param;
    out << "  " << std::setw(6) << i << "  " << std::setw(4) << b.n << " T  " << std::setprecision(10) << std::setw(16)
        << first << "  " << std::setw(16) << last << "  " << std::setw(6) << b.points.size() << "  " << b.stop << "\n";
  }
}

void points_table(std::ostream& out, const std::vector<Branch>& branches,
                  const std::vector<std::vector<Measured>>& measured) {
  for (std::size_t i = 0; i < branches.size(); ++i) {
    out << "\n  branch " << i << " (period " << branches[i].n << " T)\n  " << std::setw(14) << "param" << "  stable  "
        << std::setw(9) << "max|mu|" << "  " << std::setw(8) << "regime" << "  " << std::setw(10) << "k_con" << "  "
        << std::setw(11) << "F_max (N)" << "\n";
    for (const Measured& m : measured[i])
      out << "  " << std::setw(14) << std::setprecision(8) << m.point.param << "  " << std::setw(6)
          << (m.point.stable ? "yes" : "no") << "  " << std::setw(9) << std::setprecision(5)
          << largest(m.point.multipliers) << "  " << std::setw(8) << m.orbit.regime.label() << "  " << std::setw(10)
          << m.orbit.k_con << "  " << std::setw(11) << m.orbit.F_max << "\n";
  }
}

// The table output: the first branch and its bifurcations, the switched branches and theirs, a
// summary line per branch, and every point only with --points.
void print_table(std::ostream& out, const ContinueArgs& args, const std::string& key, int n,
                 const std::string& start_regime, const std::vector<Branch>& branches,
                 const std::vector<std::vector<Measured>>& measured) {
  const Branch& branch = branches.front();
  out << "branch         " << key << " from " << short_number(args.from) << " to " << short_number(args.to) << ", period "
      << n << " T (" << start_regime << " at the start)\n"
      << "points         " << branch.points.size() << "; " << branch.stop << "\n"
      << "bifurcations   " << branch.bifurcations.size() << "\n";
  if (!args.output.empty()) out << "file           " << args.output << "\n";
  bifurcations_table(out, key, branch.bifurcations);
  for (std::size_t i = 1; i < branches.size(); ++i) {
    const Branch& s = branches[i];
    out << "switched       branch " << i << ": period " << s.n << " T, born at the period doubling " << key << " = "
        << std::setprecision(10) << born_at_param(branches, s) << " of branch " << s.parent << "; " << s.points.size()
        << " points; " << s.stop << "\n";
    bifurcations_table(out, key, s.bifurcations);
  }
  branches_table(out, branches, args.points);
  if (args.points) points_table(out, branches, measured);
}

void print_json(std::ostream& out, const std::string& key, const ContinuationReport& report) {
  const std::vector<Branch>& branches = report.branches;
  const Branch& branch = branches.front();
  JsonWriter w(out);
  w.begin_object().field("key", key).field("n", report.n).field("stop", branch.stop);
  points_json(w, report.measured.front());
  bifurcations_json(w, branch.bifurcations);
  w.key("branches").begin_array();
  for (std::size_t i = 1; i < branches.size(); ++i) {
    const Branch& s = branches[i];
    w.begin_object().field("n", s.n).field("parent", s.parent).field("born_at", s.born_at);
    w.field("born_at_param", born_at_param(branches, s));
    w.field("stop", s.stop);
    points_json(w, report.measured[i]);
    bifurcations_json(w, s.bifurcations);
    w.end_object();
  }
  w.end_array().end_object();
  out << "\n";
}

}  // namespace

int continue_command(const ContinueArgs& args, std::ostream& out) {
  if (!(std::isfinite(args.from) && std::isfinite(args.to) && args.from != args.to))
    throw SceneError(cat("--from ", short_number(args.from), " --to ", short_number(args.to), ": need finite, different values"));
  if (!std::isfinite(args.to - args.from))
    throw SceneError(cat("--from ", short_number(args.from), " --to ", short_number(args.to),
                         ": the span B - A must be finite (it scales the key)"));
  const ParamScene ps = scene_with_param([&](const auto& sets) { return load_scene(args.scene, sets); }, args.sets,
                                         args.param,
                                         cat("{values=[", exact_number(std::min(args.from, args.to)), ",",
                                             exact_number(std::max(args.from, args.to)), "]}"));
  ContinuationConfig config;
  config.from = args.from;
  config.to = args.to;
  config.ds_max = args.ds_max;
  config.max_points = args.max_points;
  config.pd_depth = args.pd_depth;
  config.output = args.output;
  config.overwrite = args.overwrite;
  const ContinuationReport report = run_continuation(ps.scene, ps.axis, config);
  if (args.format == "json") {
    print_json(out, ps.axis.key, report);
    return code(ExitCode::ok);
  }
  print_table(out, args, ps.axis.key, report.n, report.start_regime, report.branches, report.measured);
  return code(ExitCode::ok);
}

namespace {

std::string continue_footer() {
  return
      "The scene's point with KEY = A is solved from rest; its periodic orbit (period n T) is\n"
      "followed by pseudo-arclength continuation on the shooting equations P^n(y) - y = 0, the\n"
      "state scaled by the motion's scale and the key by |B - A|, with step-size control. The\n"
      "branch goes through folds (it turns back in the key) and ends when it leaves [A, B]. A\n"
      "point is corrected by Newton until the scaled residual |P^n(y) - y| is at most the scene's\n"
      "analysis.newton_tol (0: 10 solver.rtol, 1e-9 at the defaults), as shooting's. At\n"
      "every point: Floquet multipliers and stability, the orbit's regime, k_con and F_max.\n"
      "Bifurcations are detected and located by bisection along the branch: fold (the branch\n"
      "turns), period-doubling (a multiplier through -1), neimark-sacker (a complex pair through\n"
      "the unit circle), grazing (the number of contacts per cycle changes: an impact appears\n"
      "or vanishes; the map is not smooth there, and the branch goes on across it with the new\n"
      "count). At each period doubling the doubled branch (period 2n T) is switched onto and\n"
      "followed until it leaves [A, B] or rejoins the period-n orbit, to --pd-depth generations.";
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
  add_output_option(*c, "-o,--output", args->output, "Branch file to write (HDF5; postprocess/vmpy plot_branch draws it)");
  c->add_flag("--overwrite", args->overwrite, "Replace an existing branch file");
  c->add_flag("--points", args->points,
              "Table: print every point of every branch too (by default a summary: branches and bifurcations)");
  add_format_option(*c, args->format, "Output on stdout: table or json");
  return {.app = c, .footer = continue_footer(), .topic = "the continuation of a periodic orbit", .campaign = {},
          .run = [args](std::ostream& out) { return continue_command(*args, out); }};
}

}  // namespace vibromap::cli
