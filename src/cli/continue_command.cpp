// `vibromap continue`: see commands.hpp and include/vibromap/core/analysis/continuation.hpp.

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "commands.hpp"
#include "vibromap/core/analysis/continuation.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/output_file.hpp"
#include "vibromap/io/branch_file.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/scene/keys.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap::cli {
namespace {

// What continue prints of a branch point: the orbit measured as `run` measures it.
struct Measured {
  BranchPoint point;
  PointSummary orbit;
};

void multipliers_json(JsonWriter& w, const std::vector<std::complex<double>>& mu) {
  w.key("multipliers").begin_array();
  for (const auto& m : mu) w.begin_array().value(m.real()).value(m.imag()).end_array();
  w.end_array();
}

double largest(const std::vector<std::complex<double>>& mu) { return mu.empty() ? NAN : std::abs(mu.front()); }

void state_json(JsonWriter& w, const char* name, const Eigen::Vector4d& y) {
  w.key(name).begin_array();
  for (int i = 0; i < 4; ++i) w.value(y[i]);
  w.end_array();
}

void points_json(JsonWriter& w, const std::vector<Measured>& points) {
  w.key("points").begin_array();
  for (const Measured& m : points) {
    w.begin_object().field("param", m.point.param).field("stable", m.point.stable);
    multipliers_json(w, m.point.multipliers);
    w.field("T_con", m.orbit.T_con).field("k_con", m.orbit.k_con).field("F_max", m.orbit.F_max);
    w.field("impacts", static_cast<long>(m.orbit.impacts.size()));
    w.field("x1_max", m.point.x1_max).field("x2_max", m.point.x2_max).field("clearance_min", m.point.clearance_min);
    w.field("regime", m.orbit.regime.label());
    state_json(w, "y", m.point.y);
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
    state_json(w, "y", b.at.y);
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
  const Scene& scene = ps.scene;
  if (!args.output.empty()) check_output(args.output, {.overwrite = args.overwrite});
  const std::string& key = ps.axis.key;
  const PointSetter set = point_setter(key);
  const PointAt at = [&](double lambda) {
    std::pair<Parameters, PointOptions> point{scene.params, scene.options};
    set(point.first, point.second, lambda);
    return point;
  };
  // The start: the motion from rest at KEY = from (analysis.steady); where that is not periodic,
  // a branch may still start from the stable orbit shooting finds there (continuation follows
  // orbits that exist, reached from rest or not).
  auto [p0, o0] = at(args.from);
  const auto is_periodic = [](const PointSummary& s) {
    return s.status == SolveStatus::ok &&
           (s.regime.kind == RegimeKind::periodic || s.regime.kind == RegimeKind::no_contact);
  };
  PointSummary start = solve_point(p0, o0);
  if (!is_periodic(start) && o0.analysis.steady == SteadyMethod::follow) {
    o0.analysis.steady = SteadyMethod::shooting;
    start = solve_point(p0, o0);
  }
  if (!is_periodic(start))
    throw SceneError(cat(args.scene, ": at ", key, " = ", short_number(args.from), " neither the motion from rest nor ",
                         "shooting gives a periodic orbit (", start.regime.label(), ", ", to_string(start.status),
                         "); start elsewhere (--from)"));
  ContinuationOptions co;
  co.n = std::max(start.regime.n, 1);  // a motion without contact repeats every period
  co.ds_max = args.ds_max;
  co.ds = std::min(co.ds, co.ds_max);
  co.max_points = args.max_points;
  if (const std::string err = validate(co); !err.empty()) throw SceneError("--ds-max/--max-points: " + err);
  co.pd_depth = args.pd_depth;
  const std::vector<Branch> branches = continue_branches(at, args.from, args.to, start.final_state, co);
  std::vector<std::vector<Measured>> measured;
  BranchData data{ps.axis, branches, {}, scene.text};
  for (const Branch& branch : branches) {
    measured.emplace_back();
    data.cycles.emplace_back();
    for (const BranchPoint& q : branch.points) {
      const auto [p, o] = at(q.param);
      measured.back().push_back({q, measure_orbit(p, o, q.y, branch.n)});
      const PointSummary& m = measured.back().back().orbit;
      data.cycles.back().push_back({m.T_con, m.k_con, m.F_max, static_cast<int>(m.impacts.size())});
    }
  }
  if (!args.output.empty()) write_branch(args.output, data);
  const Branch& branch = branches.front();
  if (args.format == "json") {
    JsonWriter w(out);
    w.begin_object().field("key", key).field("n", co.n).field("stop", branch.stop);
    points_json(w, measured.front());
    bifurcations_json(w, branch.bifurcations);
    w.key("branches").begin_array();
    for (std::size_t i = 1; i < branches.size(); ++i) {
      const Branch& s = branches[i];
      w.begin_object().field("n", s.n).field("parent", s.parent).field("born_at", s.born_at);
      w.field("born_at_param", born_at_param(branches, s));
      w.field("stop", s.stop);
      points_json(w, measured[i]);
      bifurcations_json(w, s.bifurcations);
      w.end_object();
    }
    w.end_array().end_object();
    out << "\n";
    return code(ExitCode::ok);
  }
  print_table(out, args, key, co.n, start.regime.label(), branches, measured);
  return code(ExitCode::ok);
}

}  // namespace vibromap::cli
