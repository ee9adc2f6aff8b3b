// `vibromap continue`: the arguments and the printing; the campaign is
// campaigns/continuation/continuation_run.hpp (see commands.hpp).

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>

#include "command.hpp"
#include "commands.hpp"
#include "vibromap/campaigns/continuation/continuation_run.hpp"
#include "vibromap/campaigns/continuation/curve_run.hpp"
#include "vibromap/core/integrate/cancel.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/report.hpp"
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
  std::vector<std::string> curves;  // --curve KIND (issue #31): curves in (param, param2)
  std::string param2;
  double from2 = NAN, to2 = NAN;  // NaN: not given
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
  out << "branch         " << key << " from " << number(args.from, 12) << " to " << number(args.to, 12) << ", period "
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

void curves_json(JsonWriter& w, const CurvesReport& r);

void print_json(std::ostream& out, const std::string& key, const ContinuationReport& report,
                const CurvesReport* curves = nullptr) {
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
  w.end_array();
  if (curves) curves_json(w, *curves);
  w.end_object();
  out << "\n";
}

void curves_json(JsonWriter& w, const CurvesReport& r) {
  w.key("curves").begin_array();
  for (const MeasuredCurve& mc : r.curves) {
    const Curve& c = mc.curve;
    w.begin_object().field("kind", c.spec.label).field("n", c.n).field("stop", c.stop).field("start", c.start);
    if (!c.grazing.empty()) w.field("grazing", c.grazing);
    w.key("codim2").begin_array();
    for (const Codim2Point& x : c.codim2)
      w.begin_object().field("param", x.param).field("param2", x.param2).field("kind", x.kind).end_object();
    w.end_array();
    w.key("points").begin_array();
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const CurvePoint& q = c.points[i];
      const PointSummary& m = mc.orbits[i];
      w.begin_object().field("param", q.param).field("param2", q.param2);
      w.field("T_con", m.T_con).field("k_con", m.k_con).field("z_ratio", m.z_ratio).field("F_max", m.F_max);
      w.field("impacts", static_cast<long>(m.impacts.size())).field("stable", q.stable);
      multipliers_json(w, q.multipliers);
      w.field("residual", q.residual).field("orbit_residual", q.orbit_residual);
      write_state_json(w.key("y"), q.y);
      w.end_object();
    }
    w.end_array().end_object();
  }
  w.end_array();
  w.key("skipped").begin_array();
  for (const std::string& s : r.skipped) w.value(s);
  w.end_array();
}

// The range of one coordinate of a curve's points.
std::string range_of(const Curve& c, bool second) {
  if (c.points.empty()) return "-";
  double lo = INFINITY, hi = -INFINITY;
  for (const CurvePoint& q : c.points) {
    const double x = second ? q.param2 : q.param;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  std::ostringstream os;
  os << std::setprecision(7) << lo << " .. " << hi;
  return os.str();
}

// One paragraph per curve: kind, points, the ranges of both keys, the worst residual, why it
// stopped, and its codimension-two points.
void curves_table(std::ostream& out, const std::string& key, const std::string& key2, const CurvesReport& r) {
  out << "\ncurves         " << r.curves.size() << " in (" << key << ", " << key2 << "), started at " << key2 << " = "
      << number(r.q0, 12) << " (" << std::setprecision(3) << std::fixed << r.wall_s << " s in all)\n"
      << std::defaultfloat;
  for (std::size_t i = 0; i < r.curves.size(); ++i) {
    const Curve& c = r.curves[i].curve;
    double worst = 0.0;
    for (const CurvePoint& q : c.points) worst = std::max(worst, q.residual);
    out << "  curve " << i << "  " << c.spec.label << " (period " << c.n << " T): " << c.points.size() << " points, "
        << key << " " << range_of(c, false) << ", " << key2 << " " << range_of(c, true) << ", worst residual "
        << std::setprecision(2) << worst << ", from the point located at " << key << " = " << std::setprecision(10)
        << c.points[static_cast<std::size_t>(c.start)].param << std::setprecision(6) << "\n    stop: " << c.stop << "\n";
    if (!c.grazing.empty()) out << "    grazing: " << c.grazing << "\n";
    for (const Codim2Point& x : c.codim2)
      out << "    codim-2: " << x.kind << " at " << key << " = " << std::setprecision(10) << x.param << ", " << key2
          << " = " << x.param2 << std::setprecision(6) << "\n";
  }
  for (const std::string& s : r.skipped) out << "  not followed: " << s << "\n";
}

// The --curve options: KIND parsed, --param2/--from2/--to2 given with it (and only with it).
std::vector<CurveSpec> curve_specs(const ContinueArgs& args) {
  const bool has_from2 = !std::isnan(args.from2), has_to2 = !std::isnan(args.to2);
  const bool any2 = !args.param2.empty() || has_from2 || has_to2;
  if (args.curves.empty()) {
    if (any2) throw SceneError("--param2/--from2/--to2: only with --curve KIND");
    return {};
  }
  if (args.param2.empty() || !has_from2 || !has_to2)
    throw SceneError("--curve: needs --param2 KEY --from2 C --to2 D (the second key and its range)");
  if (!(std::isfinite(args.from2) && std::isfinite(args.to2) && args.from2 < args.to2))
    throw SceneError(cat("--from2 ", number(args.from2, 12), " --to2 ", number(args.to2, 12),
                         ": need finite values with --from2 < --to2"));
  if (args.param2 == args.param) throw SceneError(cat("--param2 ", args.param2, ": the same key as --param"));
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
  std::cerr << "vibromap: stopped by " << name << " after " << points << " points: "
            << (args.output.empty() ? "the output above holds" : "the output above and " + args.output + " hold")
            << " the continuation so far (stop: 'stopped by " << name
            << "'); continue has no --resume: run it again to go on\n";
  return code(ExitCode::stopped);
}

int continue_curves(const ContinueArgs& args, const ContinuationConfig& config, std::vector<CurveSpec> specs,
                    std::ostream& out) {
  const auto range = [](double a, double b) {
    return cat("{values=[", number(std::min(a, b), 17), ",", number(std::max(a, b), 17), "]}");
  };
  const ParamScene2 ps = scene_with_params([&](const auto& sets) { return load_scene(args.scene, sets); }, args.sets,
                                           args.param, range(args.from, args.to), args.param2,
                                           range(args.from2, args.to2));
  const CurvesReport r = run_curves(ps.scene, ps.axis, ps.axis2, config, {std::move(specs), args.from2, args.to2});
  if (args.format == "json") {
    print_json(out, ps.axis.key, r.branch, &r);
  } else {
    print_table(out, args, ps.axis.key, r.branch.n, r.branch.start_regime, r.branch.branches, r.branch.measured);
    curves_table(out, ps.axis.key, ps.axis2.key, r);
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
  const ParamScene ps = scene_with_param([&](const auto& sets) { return load_scene(args.scene, sets); }, args.sets,
                                         args.param,
                                         cat("{values=[", number(std::min(args.from, args.to), 17), ",",
                                             number(std::max(args.from, args.to), 17), "]}"));
  const ContinuationReport report = run_continuation(ps.scene, ps.axis, config);
  if (args.format == "json") {
    print_json(out, ps.axis.key, report);
  } else {
    print_table(out, args, ps.axis.key, report.n, report.start_regime, report.branches, report.measured);
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
      "no --resume (run it again). A stop while the start orbit is solved writes nothing.";
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
                    "Branch file to write (HDF5; postprocess/vmpy plot_branch draws it); with --curve, the curve file");
  c->add_flag("--overwrite", args->overwrite, "Replace an existing branch file");
  c->add_flag("--points", args->points,
              "Table: print every point of every branch too (by default a summary: branches and bifurcations)");
  c->add_option("--curve", args->curves,
                "Also follow every KIND point of the branch in (KEY, KEY2): fold, period-doubling, neimark-sacker, "
                "grazing or level:NAME=VALUE (NAME k_con, T_con, F_max, z_ratio); may be repeated")
      ->type_name("KIND");
  c->add_option("--param2", args->param2, "With --curve: the second key (a model parameter: forcing.F0, contact.E1, ...)")
      ->type_name("KEY2");
  c->add_option("--from2", args->from2, "With --curve: the second key's lower end (SI units)")->check(kNumber)->type_name("C");
  c->add_option("--to2", args->to2, "With --curve: its upper end (> C; the scene's value must lie in [C, D])")
      ->check(kNumber)
      ->type_name("D");
  add_format_option(*c, args->format, "Output on stdout: table or json");
  return {.app = c, .footer = continue_footer(), .topic = "the continuation of a periodic orbit",
          .campaign = always_campaign,  // one process, but a stop signal ends it cleanly (continue_exit)
          .run = [args](std::ostream& out) { return continue_command(*args, out); }};
}

}  // namespace vibromap::cli
