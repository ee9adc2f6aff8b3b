// The continuation campaign: see continuation_run.hpp.

#include "vibromap/campaigns/continuation/continuation_run.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "vibromap/core/integrate/cancel.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/branch_file.hpp"
#include "vibromap/io/output_file.hpp"
#include "vibromap/io/scene/keys.hpp"
#include "vibromap/parallel/signals.hpp"

namespace vibromap {
namespace {

constexpr double kMaxContinuationTol = 1e-2;  // validate(ContinuationOptions): tol in (0, 0.01)

bool is_periodic(const PointSummary& s) {
  return s.status == SolveStatus::ok &&
         (s.regime.kind == RegimeKind::periodic || s.regime.kind == RegimeKind::no_contact);
}

// The orbit at KEY = from: the motion from rest (analysis.steady), or where that is not periodic
// the one shooting finds; SceneError when neither is periodic.
PointSummary start_orbit(const Scene& scene, const PointAt& at, const std::string& key, double from) {
  auto [p0, o0] = at(from);
  PointSummary start = solve_point(p0, o0);
  if (!is_periodic(start) && o0.analysis.steady == SteadyMethod::follow) {
    o0.analysis.steady = SteadyMethod::shooting;
    start = solve_point(p0, o0);
  }
  if (!is_periodic(start))
    throw SceneError(cat(scene.path, ": at ", key, " = ", number(from, 12), " neither the motion from rest nor ",
                         "shooting gives a periodic orbit (", start.regime.label(), ", ", to_string(start.status),
                         "); start elsewhere (--from)"));
  return start;
}

// The corrector's tolerance on the scaled residual |P^n(y) - y| of a point: the scene's Newton
// tolerance at KEY = from (analysis.newton_tol; 0: 10 solver.rtol, 1e-9 at the defaults), the
// same residual in the same scale (StateScale) as shooting's. SceneError, before any solve,
// when it is not below the 0.01 continuation allows.
double corrector_tolerance(const Scene& scene, const PointAt& at, double from) {
  const double tol = newton_tolerance(at(from).second);
  if (!(tol < kMaxContinuationTol))
    throw SceneError(cat(scene.path, ": continue needs a Newton tolerance below ", number(kMaxContinuationTol, 12),
                         "; analysis.newton_tol gives ", number(tol, 12), " (when 0: 10 solver.rtol)"));
  return tol;
}

ContinuationOptions continuation_options(const PointSummary& start, const ContinuationConfig& config, double tol) {
  ContinuationOptions co;
  co.n = std::max(start.regime.n, 1);  // a motion without contact repeats every period
  co.tol = tol;
  co.ds_max = config.ds_max;
  co.ds = std::min(co.ds, co.ds_max);
  co.max_points = config.max_points;
  if (const std::string err = validate(co); !err.empty()) throw SceneError("--ds-max/--max-points: " + err);
  co.pd_depth = config.pd_depth;
  co.stop = &stop_flag();  // a stop signal ends the branch before its next point
  return co;
}

// Every point's cycle measured.
void measure_branches(const PointAt& at, ContinuationReport& report) {
  for (const Branch& branch : report.branches) {
    report.measured.emplace_back();
    for (const BranchPoint& q : branch.points) {
      const auto [p, o] = at(q.param);
      report.measured.back().push_back({q, measure_orbit(p, o, q.y, branch.n)});
    }
  }
}

// The branch file's data of a report (physical).
BranchData branch_data(const Axis& axis, const ContinuationReport& report, const std::string& text) {
  BranchData data{axis, report.branches, {}, text};
  for (const std::vector<MeasuredPoint>& branch : report.measured) {
    data.cycles.emplace_back();
    for (const MeasuredPoint& q : branch) {
      const PointSummary& m = q.orbit;
      data.cycles.back().push_back({m.T_con, m.k_con, m.F_max, static_cast<int>(m.impacts.size())});
    }
  }
  return data;
}

}  // namespace

std::string name_stop_signal(std::string stop, int signal) {
  const std::string from = kStoppedOnRequest;
  if (const std::size_t at = stop.find(from); at != std::string::npos && signal != 0)
    stop.replace(at, from.size(), "stopped by " + signal_name(signal));
  return stop;
}

KeyScale key_scale(double from, double to, double anchor) {
  const double lo = std::min(from, to), hi = std::max(from, to);
  return {.log = lo > 0.0 && hi >= kLogSpan * lo, .from = from, .to = to, .anchor = anchor};
}

double KeyScale::engine(double value) const { return log ? std::log(value) : value; }

double KeyScale::physical(double u) const {
  if (!log) return u;
  for (const double v : {from, to, anchor})
    if (u == std::log(v)) return v;
  return std::exp(u);
}

void to_physical(ContinuationReport& report, const KeyScale& scale) {
  if (!scale.log) return;
  for (Branch& b : report.branches) {
    for (BranchPoint& p : b.points) p.param = scale.physical(p.param);
    for (Bifurcation& x : b.bifurcations) x.at.param = scale.physical(x.at.param);
  }
  for (std::vector<MeasuredPoint>& m : report.measured)
    for (MeasuredPoint& p : m) p.point.param = scale.physical(p.point.param);
}

ContinuationReport continue_scaled(const Scene& scene, const Axis& axis, const ContinuationConfig& config,
                                   const KeyScale& scale) {
  const Key key = Key::at(axis.key);
  const PointAt at_value = [&](double lambda) {
    std::pair<Parameters, PointOptions> point{scene.params, scene.options};
    point.second.analysis.trajectory_periods = 0;  // continue keeps no trajectory (run --trajectory does)
    key.set(point.first, point.second, lambda);
    return point;
  };
  const PointAt at = scale.log ? PointAt([&](double u) { return at_value(scale.physical(u)); }) : at_value;
  const double tol = corrector_tolerance(scene, at_value, config.from);
  const PointSummary start = [&] {
    // The start may integrate for long (a transient of analysis.max_periods): a stop signal
    // cancels it, and Cancelled reaches the command (no point found, nothing written).
    const CancelScope scope(&stop_flag());
    return start_orbit(scene, at_value, axis.key, config.from);
  }();
  const ContinuationOptions co = continuation_options(start, config, tol);
  ContinuationReport report;
  report.n = co.n;
  report.start_regime = start.regime.label();
  report.branches = continue_branches(at, scale.engine(config.from), scale.engine(config.to), start.final_state, co);
  measure_branches(at, report);
  return report;
}

void write_branch_file(const std::string& path, const Axis& axis, const ContinuationReport& report,
                       const std::string& scene_text) {
  write_branch(path, branch_data(axis, report, scene_text));
}

ContinuationReport run_continuation(const Scene& scene, const Axis& axis, const ContinuationConfig& config) {
  if (!config.output.empty()) check_output(config.output, {.overwrite = config.overwrite});
  const KeyScale scale = key_scale(config.from, config.to, config.from);
  ContinuationReport report = continue_scaled(scene, axis, config, scale);
  to_physical(report, scale);
  report.stop_signal = stop_signal();
  for (Branch& b : report.branches) b.stop = name_stop_signal(b.stop, report.stop_signal);
  if (!config.output.empty()) write_branch_file(config.output, axis, report, scene.text);
  return report;
}

}  // namespace vibromap
