// Curves in two parameters: see curve_run.hpp.

#include "vibromap/campaigns/continuation/curve_run.hpp"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "vibromap/core/text.hpp"
#include "vibromap/io/curve_file.hpp"
#include "vibromap/io/output_file.hpp"
#include "vibromap/io/scene/keys.hpp"
#include "vibromap/parallel/signals.hpp"

namespace vibromap {
namespace {

// A point of a branch a curve starts from.
struct Start {
  int n = 1;
  double param = 0.0;
  Eigen::Vector4d y = Eigen::Vector4d::Zero();
};

// Every located bifurcation of the spec's type starts a curve (grazings of every kind: the
// condition tracks the approach that touches, curve_continuation.hpp).
std::vector<Start> bifurcation_starts(const ContinuationReport& r, const CurveSpec& spec) {
  BifurcationType type = BifurcationType::fold;
  if (spec.kind == CurveKind::period_doubling) type = BifurcationType::period_doubling;
  if (spec.kind == CurveKind::neimark_sacker) type = BifurcationType::neimark_sacker;
  if (spec.kind == CurveKind::grazing) type = BifurcationType::grazing;
  std::vector<Start> out;
  for (const Branch& b : r.branches)
    for (const Bifurcation& x : b.bifurcations) {
      if (x.type != type) continue;
      out.push_back({b.n, x.at.param, x.at.y});
    }
  return out;
}

std::vector<Start> level_starts(const PointAt2& at, const CurveBox& box, const CurveSpec& spec, double q0,
                                const ContinuationReport& r, const CurveOptions& co, const KeyScale& sp,
                                std::vector<std::string>& skipped) {
  std::vector<Start> out;
  for (std::size_t k = 0; k < r.branches.size(); ++k) {
    const std::vector<MeasuredPoint>& m = r.measured[k];
    for (std::size_t i = 1; i < m.size(); ++i) {
      const PointSummary &a = m[i - 1].orbit, &b = m[i].orbit;
      if (a.status != SolveStatus::ok || b.status != SolveStatus::ok || a.impacts.empty() || b.impacts.empty()) continue;
      const double va = level_value(spec.quantity, a), vb = level_value(spec.quantity, b);
      if (!((va - spec.value) * (vb - spec.value) < 0.0)) continue;
      const auto p = locate_level(at, box, spec, r.branches[k].n, q0, m[i - 1].point, va, m[i].point, vb, co);
      if (p) out.push_back({r.branches[k].n, p->param, p->y});
      else skipped.push_back(cat(spec.label, " between ", number(sp.physical(m[i - 1].point.param), 12), " and ",
                                 number(sp.physical(m[i].point.param), 12), ": not located (Newton does not converge)"));
    }
  }
  return out;
}

// Whether (P, Q) lies on a curve of the same kind and period already found (within 1e-3 of the
// box, scaled, of one of its segments).
bool on_known_curve(const std::vector<MeasuredCurve>& curves, const CurveSpec& spec, int n, const CurveBox& box,
                    double P, double Q) {
  const auto scaled = [&](double p, double q) {
    return Eigen::Vector2d((p - box.from) / (box.to - box.from), (q - box.from2) / (box.to2 - box.from2));
  };
  const Eigen::Vector2d x = scaled(P, Q);
  for (const MeasuredCurve& c : curves) {
    if (c.curve.spec.label != spec.label || c.curve.n != n) continue;
    for (std::size_t i = 0; i < c.curve.points.size(); ++i) {
      const Eigen::Vector2d a = scaled(c.curve.points[i].param, c.curve.points[i].param2);
      const Eigen::Vector2d b = i + 1 < c.curve.points.size()
                                    ? scaled(c.curve.points[i + 1].param, c.curve.points[i + 1].param2)
                                    : a;
      const double len2 = (b - a).squaredNorm();
      const double s = len2 > 0.0 ? std::clamp((x - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
      if ((a + s * (b - a) - x).norm() < 1e-3) return true;
    }
  }
  return false;
}

CurveOptions curve_options(const Scene& scene, const ContinuationConfig& config, const CurveSpec& spec) {
  CurveOptions co;
  co.base.ds_max = config.ds_max;
  co.base.ds = std::min(co.base.ds, co.base.ds_max);
  co.base.max_points = config.max_points;
  co.base.tol = newton_tolerance(scene.options);  // the scene's own (10 rtol by default)
  co.condition_tol = spec.kind == CurveKind::grazing ? 1e-10 : 1e-9;
  co.base.stop = &stop_flag();  // a stop signal ends the curve before its next point
  return co;
}

// A curve's points and codimension-two points in the keys' own units.
void to_physical(Curve& c, const KeyScale& sp, const KeyScale& sq) {
  for (CurvePoint& p : c.points) p.param = sp.physical(p.param), p.param2 = sq.physical(p.param2);
  for (Codim2Point& p : c.codim2) p.param = sp.physical(p.param), p.param2 = sq.physical(p.param2);
}

void write_curve_file(const std::string& path, const Axis& axis, const Axis& axis2, const CurvesReport& report,
                      const std::string& text) {
  CurveFileData data{axis, axis2, {}, {}, text};
  for (const MeasuredCurve& c : report.curves) {
    data.curves.push_back(c.curve);
    data.cycles.emplace_back();
    for (const PointSummary& m : c.orbits)
      data.cycles.back().push_back({m.T_con, m.k_con, m.z_ratio, m.F_max, static_cast<int>(m.impacts.size())});
  }
  write_curves(path, data);
}

// The stop signal that ended the run early, named in every stop reason it cut short.
void name_stops(CurvesReport& report) {
  report.branch.stop_signal = stop_signal();
  const int signal = report.branch.stop_signal;
  for (Branch& b : report.branch.branches) b.stop = name_stop_signal(b.stop, signal);
  for (MeasuredCurve& c : report.curves) c.curve.stop = name_stop_signal(c.curve.stop, signal);
  for (std::string& s : report.skipped) s = name_stop_signal(s, signal);
}

}  // namespace

CurvesReport run_curves(const Scene& scene, const Axis& axis, const Axis& axis2, const ContinuationConfig& config,
                        const CurveConfig& curves) {
  const auto t0 = std::chrono::steady_clock::now();
  CurvesReport report;
  report.q0 = Key::at(axis2.key).value(scene.params);
  if (!(curves.from2 < curves.to2))
    throw SceneError(cat("--from2 ", number(curves.from2, 12), " --to2 ", number(curves.to2, 12),
                         ": need --from2 < --to2"));
  if (!(report.q0 >= curves.from2 && report.q0 <= curves.to2))
    throw SceneError(cat("--param2 ", axis2.key, ": the scene's value ", number(report.q0, 12), " is outside [",
                         number(curves.from2, 12), ", ", number(curves.to2, 12), "]"));
  if (!config.output.empty()) check_output(config.output, {.overwrite = config.overwrite});
  // P and Q each in the units key_scale gives (ln for decades); mapped back at the end.
  const KeyScale sp = key_scale(config.from, config.to, config.from);
  const KeyScale sq = key_scale(curves.from2, curves.to2, report.q0);
  ContinuationConfig branch_config = config;
  branch_config.output.clear();
  report.branch = continue_scaled(scene, axis, branch_config, sp);
  const Key key = Key::at(axis.key), key2 = Key::at(axis2.key);
  const PointAt2 at = [&](double P, double Q) {
    std::pair<Parameters, PointOptions> point{scene.params, scene.options};
    point.second.analysis.trajectory_periods = 0;  // as for the branch: no trajectory kept
    key2.set(point.first, point.second, sq.physical(Q));
    key.set(point.first, point.second, sp.physical(P));
    return point;
  };
  const CurveBox box{sp.engine(config.from), sp.engine(config.to), sq.engine(curves.from2), sq.engine(curves.to2),
                     axis.key, axis2.key, sp.log, sq.log};
  const double q0 = sq.engine(report.q0);
  for (const CurveSpec& spec : curves.specs) {
    const CurveOptions co = curve_options(scene, config, spec);
    if (stop_requested(co.base)) break;  // stopped: no further curve is started
    const std::vector<Start> starts =
        spec.kind == CurveKind::level ? level_starts(at, box, spec, q0, report.branch, co, sp, report.skipped)
                                      : bifurcation_starts(report.branch, spec);
    for (const Start& s : starts) {
      if (stop_requested(co.base)) break;
      if (on_known_curve(report.curves, spec, s.n, box, s.param, q0)) continue;
      MeasuredCurve mc{continue_curve(at, box, spec, s.n, s.param, q0, s.y, co), {}};
      if (mc.curve.points.empty()) {
        report.skipped.push_back(cat(spec.label, " at ", number(sp.physical(s.param), 12), ": ", mc.curve.stop));
        continue;
      }
      for (const CurvePoint& q : mc.curve.points) {
        const auto [p, o] = at(q.param, q.param2);
        mc.orbits.push_back(measure_orbit(p, o, q.y, s.n));
      }
      report.curves.push_back(std::move(mc));
    }
  }
  to_physical(report.branch, sp);
  for (MeasuredCurve& c : report.curves) to_physical(c.curve, sp, sq);
  name_stops(report);
  // Stopped before any curve: the file named holds what was found, the branch so far.
  report.branch_file = report.curves.empty() && report.branch.stop_signal != 0;
  if (!config.output.empty() && report.branch_file) write_branch_file(config.output, axis, report.branch, scene.text);
  else if (!config.output.empty()) write_curve_file(config.output, axis, axis2, report, scene.text);
  report.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return report;
}

}  // namespace vibromap
