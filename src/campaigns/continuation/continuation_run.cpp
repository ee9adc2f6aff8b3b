// The continuation campaign: see continuation_run.hpp.

#include "vibromap/campaigns/continuation/continuation_run.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "vibromap/core/text.hpp"
#include "vibromap/io/branch_file.hpp"
#include "vibromap/io/output_file.hpp"
#include "vibromap/io/scene/keys.hpp"

namespace vibromap {
namespace {

std::string short_number(double x) {  // 12 digits: 7.23, for messages (as the command's)
  std::ostringstream os;
  os << std::setprecision(12) << x;
  return os.str();
}

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
    throw SceneError(cat(scene.path, ": at ", key, " = ", short_number(from), " neither the motion from rest nor ",
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
    throw SceneError(cat(scene.path, ": continue needs a Newton tolerance below ", short_number(kMaxContinuationTol),
                         "; analysis.newton_tol gives ", short_number(tol), " (when 0: 10 solver.rtol)"));
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
  return co;
}

// Every point's cycle measured, and the branch file's data of them.
void measure_branches(const PointAt& at, ContinuationReport& report, BranchData& data) {
  for (const Branch& branch : report.branches) {
    report.measured.emplace_back();
    data.cycles.emplace_back();
    for (const BranchPoint& q : branch.points) {
      const auto [p, o] = at(q.param);
      report.measured.back().push_back({q, measure_orbit(p, o, q.y, branch.n)});
      const PointSummary& m = report.measured.back().back().orbit;
      data.cycles.back().push_back({m.T_con, m.k_con, m.F_max, static_cast<int>(m.impacts.size())});
    }
  }
}

}  // namespace

ContinuationReport run_continuation(const Scene& scene, const Axis& axis, const ContinuationConfig& config) {
  if (!config.output.empty()) check_output(config.output, {.overwrite = config.overwrite});
  const PointSetter set = point_setter(axis.key);
  const PointAt at = [&](double lambda) {
    std::pair<Parameters, PointOptions> point{scene.params, scene.options};
    set(point.first, point.second, lambda);
    return point;
  };
  const double tol = corrector_tolerance(scene, at, config.from);
  const PointSummary start = start_orbit(scene, at, axis.key, config.from);
  const ContinuationOptions co = continuation_options(start, config, tol);
  ContinuationReport report;
  report.n = co.n;
  report.start_regime = start.regime.label();
  report.branches = continue_branches(at, config.from, config.to, start.final_state, co);
  BranchData data{axis, report.branches, {}, scene.text};
  measure_branches(at, report, data);
  if (!config.output.empty()) write_branch(config.output, data);
  return report;
}

}  // namespace vibromap
