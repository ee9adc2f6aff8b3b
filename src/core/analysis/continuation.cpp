#include "vibromap/core/analysis/continuation.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Dense>

#include "vibromap/core/analysis/orbit_extent.hpp"
#include "vibromap/core/analysis/shooting.hpp"
#include "vibromap/core/integrate/integrator.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap {

std::string validate(const ContinuationOptions& o) {
  if (o.n < 1 || o.n > 1000) return "n must be in [1, 1000]";
  if (!(o.ds_min > 0.0 && o.ds_min <= o.ds && o.ds <= o.ds_max && o.ds_max <= 1.0))
    return "steps must satisfy 0 < ds_min <= ds <= ds_max <= 1";
  if (o.max_points < 2) return "max_points must be >= 2";
  if (o.max_corrections < 1) return "max_corrections must be >= 1";
  if (!(o.tol > 0.0 && o.tol < 1e-2)) return "tol must be in (0, 0.01)";
  if (!(o.locate_tol > 0.0 && o.locate_tol < 0.1)) return "locate_tol must be in (0, 0.1)";
  return {};
}

std::string to_string(BifurcationType t) {
  switch (t) {
    case BifurcationType::fold: return "fold";
    case BifurcationType::period_doubling: return "period-doubling";
    case BifurcationType::neimark_sacker: return "neimark-sacker";
    case BifurcationType::grazing: break;
  }
  return "grazing";
}

namespace {

using Vector5d = Eigen::Matrix<double, 5, 1>;

// A point whose closest approach is within this many motion scales of zero is at a grazing.
constexpr double kGrazingTolerance = 1e-6;
using Matrix5d = Eigen::Matrix<double, 5, 5>;

// G and its Jacobian at one point z = (y scaled by the motion's scale, l): lambda = from + l span.
struct Eval {
  Eigen::Vector4d F = Eigen::Vector4d::Zero();   // (P^n(y) - y) / unit
  Eigen::Matrix4d Jy = Eigen::Matrix4d::Zero();  // dF/dy_scaled
  Eigen::Vector4d Jl = Eigen::Vector4d::Zero();  // dF/dl (forward difference)
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();  // monodromy dP^n/dy
};

class Problem {
 public:
  Problem(const PointAt& point_at, double from, double to, const ContinuationOptions& o)
      : point_at_(point_at), from_(from), span_(to - from), o_(o) {
    const auto [p, opt] = point_at_(from);
    const StateScale scale{Model(p)};
    unit_ = Eigen::Array4d(scale.length(), scale.length(), scale.speed(), scale.speed());
  }

  double lambda(double l) const { return from_ + l * span_; }
  State state(const Vector5d& z) const { return (z.head<4>().array() * unit_).matrix(); }
  Vector5d scaled(const State& y, double l) const {
    Vector5d z;
    z.head<4>() = (y.array() / unit_).matrix();
    z[4] = l;
    return z;
  }

  std::optional<Eval> eval(const Vector5d& z) {
    Eval e;
    const State y = state(z);
    State image;
    {
      const auto [p, opt] = point_at_(lambda(z[4]));
      if (period_map(Model(p), opt.integrator, y, o_.n, image, e.M, counters) != IntegrationStatus::ok) return std::nullopt;
    }
    const Eigen::Matrix4d D = unit_.matrix().asDiagonal();
    const Eigen::Matrix4d Dinv = unit_.inverse().matrix().asDiagonal();
    e.F = ((image - y).array() / unit_).matrix();
    e.Jy = Dinv * (e.M - Eigen::Matrix4d::Identity()) * D;
    const auto [p2, opt2] = point_at_(lambda(z[4] + kDl));
    const Model m2(p2);
    const auto integ = make_integrator(m2, opt2.integrator);
    State u = y;
    integ->reset(u);
    Observer none;
    for (int i = 0; i < o_.n; ++i)
      if (integ->advance_period(u, none) != IntegrationStatus::ok) return std::nullopt;
    counters += integ->counters();
    e.Jl = ((u - image).array() / unit_).matrix() / kDl;
    return e;
  }

  // Newton on [G(z) = 0, t.(z - z_pred) = 0] from z_pred.
  std::optional<std::pair<Vector5d, Eval>> correct(const Vector5d& z_pred, const Vector5d& t, int* iterations = nullptr) {
    Vector5d z = z_pred;
    for (int it = 0; it <= o_.max_corrections; ++it) {
      const std::optional<Eval> e = eval(z);
      if (!e) return std::nullopt;
      if (e->F.cwiseAbs().maxCoeff() <= o_.tol) {
        if (iterations) *iterations = it;
        return std::make_pair(z, *e);
      }
      Matrix5d A;
      A.topLeftCorner<4, 4>() = e->Jy;
      A.topRightCorner<4, 1>() = e->Jl;
      A.bottomRows<1>() = t.transpose();
      Vector5d r;
      r.head<4>() = e->F;
      r[4] = t.dot(z - z_pred);
      const Vector5d dz = A.fullPivLu().solve(-r);
      if (!dz.allFinite() || dz.norm() > 0.5) return std::nullopt;  // far from the predictor: a smaller step
      z += dz;
    }
    return std::nullopt;
  }

  // The unit tangent at a point, oriented along `previous`.
  static Vector5d tangent(const Eval& e, const Vector5d& previous) {
    Matrix5d A;
    A.topLeftCorner<4, 4>() = e.Jy;
    A.topRightCorner<4, 1>() = e.Jl;
    A.bottomRows<1>() = previous.transpose();
    Vector5d rhs = Vector5d::Zero();
    rhs[4] = 1.0;
    Vector5d t = A.fullPivLu().solve(rhs);
    return t / t.norm();
  }

  BranchPoint point(const Vector5d& z, const Eval& e) {
    BranchPoint b;
    b.param = lambda(z[4]);
    b.y = Model::to_physical(state(z));
    b.multipliers = floquet_multipliers(e.M);
    b.stable = std::abs(b.multipliers.front()) < 1.0;
    b.residual = e.F.cwiseAbs().maxCoeff();
    const OrbitExtent x = extent(z);
    b.x1_max = x.x1_max;
    b.x2_max = x.x2_max;
    b.clearance_min = x.clearance_min;
    return b;
  }

  OrbitExtent extent(const Vector5d& z) {
    const auto [p, opt] = point_at_(lambda(z[4]));
    return orbit_extent(Model(p), opt.integrator, state(z), o_.n, counters);
  }

  double length_scale() const { return unit_[0]; }

  IntegrationCounters counters;

 private:
  static constexpr double kDl = 1e-7;  // finite-difference step in the scaled parameter
  PointAt point_at_;
  double from_, span_;
  ContinuationOptions o_;
  Eigen::Array4d unit_;
};

// The test functions, each a value whose sign (or count) changes at its bifurcation.
double pd_test(const Eval& e) { return (e.M + Eigen::Matrix4d::Identity()).determinant(); }
int ns_count(const Eval& e) {
  int outside = 0;
  for (const auto& mu : floquet_multipliers(e.M))
    if (std::abs(mu.imag()) > 1e-9 * std::abs(mu) && std::abs(mu) > 1.0) ++outside;
  return outside;
}

// Whether the multipliers at a located point are those of its bifurcation: one at +1 (fold), one
// at -1 (period doubling), a complex pair on the unit circle (Neimark-Sacker), within
// kCriticalMultiplier. A test function also changes sign where the map is not smooth (a grazing
// in the step makes the Jacobian jump); such a change has no critical multiplier and is no
// bifurcation of the smooth theory: it is not reported (the grazing is).
constexpr double kCriticalMultiplier = 1e-2;
bool has_critical_multiplier(BifurcationType type, const std::vector<std::complex<double>>& mu) {
  for (const auto& m : mu) {
    switch (type) {
      case BifurcationType::fold:
        if (std::abs(m - 1.0) <= kCriticalMultiplier) return true;
        break;
      case BifurcationType::period_doubling:
        if (std::abs(m + 1.0) <= kCriticalMultiplier) return true;
        break;
      case BifurcationType::neimark_sacker:
        if (std::abs(m.imag()) > kCriticalMultiplier && std::abs(std::abs(m) - 1.0) <= kCriticalMultiplier) return true;
        break;
      case BifurcationType::grazing: return true;
    }
  }
  return false;
}

}  // namespace

Branch continue_orbit(const PointAt& point_at, double from, double to, const Eigen::Vector4d& y0,
                      const ContinuationOptions& o) {
  Branch b;
  if (const std::string err = validate(o); !err.empty()) {
    b.stop = err;
    return b;
  }
  if (!(to != from)) {
    b.stop = "the interval is empty (from = to)";
    return b;
  }
  Problem pb(point_at, from, to, o);
  // The start: Newton at lambda = from (the parameter fixed).
  ShootingOptions so;
  so.n = o.n;
  so.tol = o.tol;
  const auto [p0, opt0] = point_at(from);
  const ShootingResult sh = shoot(Model(p0), opt0.integrator, Model::to_internal(y0), so, pb.counters);
  if (!sh.converged) {
    b.stop = "no periodic orbit at the start: " + sh.message;
    b.counters = pb.counters;
    return b;
  }
  Vector5d z = pb.scaled(sh.y, 0.0);
  std::optional<Eval> e = pb.eval(z);
  if (!e) {
    b.stop = "the integration failed at the start";
    return b;
  }
  Vector5d t;
  {
    const Eigen::Vector4d v = e->Jy.fullPivLu().solve(-e->Jl);
    t.head<4>() = v;
    t[4] = 1.0;
    t /= t.norm();
  }
  b.points.push_back(pb.point(z, *e));
  double ds = o.ds;
  while (static_cast<int>(b.points.size()) < o.max_points) {
    int iterations = 0;
    const auto next = pb.correct(z + ds * t, t, &iterations);
    if (!next) {
      ds /= 2.0;
      if (ds >= o.ds_min) continue;
      // Steps that fail down to ds_min: at a grazing the map stops being smooth (an impact
      // appears), and Newton converges up to it from this side only, so the last point is the
      // grazing point to within ds_min. It is marked, and the branch is continued across with
      // steps from ds_min up, each accepted once Newton converges on the far side.
      const BranchPoint& last = b.points.back();
      const double touching = kGrazingTolerance * pb.length_scale();
      if (!(std::abs(last.clearance_min) <= touching)) {
        b.stop = "the step fell below ds_min (Newton does not converge: a nonsmooth point?)";
        break;
      }
      const bool known = std::any_of(b.bifurcations.begin(), b.bifurcations.end(), [&](const Bifurcation& g) {
        return g.type == BifurcationType::grazing && std::abs(g.at.param - last.param) <= 1e-6 * std::abs(to - from);
      });
      if (!known) b.bifurcations.push_back({BifurcationType::grazing, last});
      std::optional<std::pair<Vector5d, Eval>> across;
      double jump = o.ds_min;
      for (; jump <= o.ds_max && !across; jump *= 4.0) {
        const auto far = pb.correct(z + jump * t, t);
        if (far && (pb.extent(far->first).clearance_min > 0.0) != (last.clearance_min > 0.0)) across = far;
      }
      if (!across) {
        b.stop = "grazing: Newton does not converge beyond it";
        break;
      }
      z = across->first;
      e = across->second;
      t = Problem::tangent(*e, t);
      b.points.push_back(pb.point(z, *e));
      ds = std::max(jump, o.ds);
      continue;
    }
    const auto& [z1, e1] = *next;
    const Vector5d t1 = Problem::tangent(e1, t);
    BranchPoint p1 = pb.point(z1, e1);  // its extent once: the grazing test and the branch use it
    // Bifurcations between z and z1: bisection in the arclength s from z along t, on a test
    // `changed(z_m, eval at z_m, tangent at z_m)` that is false at z and true at z1; the point
    // located is the first one found with it true, within locate_tol of the change.
    const auto locate = [&](auto changed, BifurcationType type) {
      double lo = 0.0, hi = ds;
      std::optional<std::pair<Vector5d, Eval>> best = next;
      while ((hi - lo) > o.locate_tol) {
        const double mid = 0.5 * (lo + hi);
        const auto m = pb.correct(z + mid * t, t);
        if (!m) break;
        if (changed(m->first, m->second, Problem::tangent(m->second, t))) {
          hi = mid;
          best = m;
        } else {
          lo = mid;
        }
      }
      BranchPoint at = pb.point(best->first, best->second);
      if (type != BifurcationType::grazing && !has_critical_multiplier(type, at.multipliers)) return;
      b.bifurcations.push_back({type, at});
    };
    if ((t[4] > 0.0) != (t1[4] > 0.0))
      locate([&](const Vector5d&, const Eval&, const Vector5d& tm) { return (tm[4] > 0.0) != (t[4] > 0.0); },
             BifurcationType::fold);
    const double pd0 = pd_test(*e);
    if ((pd0 > 0.0) != (pd_test(e1) > 0.0))
      locate([&](const Vector5d&, const Eval& em, const Vector5d&) { return (pd_test(em) > 0.0) != (pd0 > 0.0); },
             BifurcationType::period_doubling);
    const int ns0 = ns_count(*e);
    if (ns0 != ns_count(e1))
      locate([&](const Vector5d&, const Eval& em, const Vector5d&) { return ns_count(em) != ns0; },
             BifurcationType::neimark_sacker);
    const bool apart0 = b.points.back().clearance_min > 0.0;
    if (apart0 != (p1.clearance_min > 0.0))
      locate([&](const Vector5d& zm, const Eval&, const Vector5d&) { return (pb.extent(zm).clearance_min > 0.0) != apart0; },
             BifurcationType::grazing);
    if (z1[4] < -1e-12 || z1[4] > 1.0 + 1e-12) {
      // The branch leaves the interval: its last point is at the end it crosses, corrected
      // with the parameter fixed there.
      const double end = z1[4] > 1.0 ? 1.0 : 0.0;
      Vector5d fixed = Vector5d::Zero();
      fixed[4] = 1.0;
      const double s = (end - z[4]) / (z1[4] - z[4]);
      Vector5d z_end = z + s * (z1 - z);
      z_end[4] = end;
      if (const auto last = pb.correct(z_end, fixed)) b.points.push_back(pb.point(last->first, last->second));
      b.stop = end == 1.0 ? "reached the end of the interval" : "came back to the start of the interval";
      break;
    }
    z = z1;
    e = e1;
    t = t1;
    b.points.push_back(std::move(p1));
    if (iterations <= 3) ds = std::min(1.5 * ds, o.ds_max);
  }
  if (b.stop.empty()) b.stop = "max_points reached";
  b.counters = pb.counters;
  return b;
}

}  // namespace vibromap
