#include "vibromap/core/analysis/continuation.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "vibromap/core/analysis/orbit_extent.hpp"
#include "vibromap/core/analysis/shooting.hpp"
#include "vibromap/core/integrate/integrator.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap {

std::string validate(const ContinuationOptions& o) {
  if (o.n < 1 || o.n > 1000) return "n must be in [1, 1000]";
  if (!(o.ds_min > 0.0 && o.ds_min <= o.ds && o.ds <= o.ds_max && o.ds_max <= 1.0))
    return "steps must satisfy 0 < ds_min <= ds <= ds_max <= 1";
  if (o.max_points < 2 || o.max_points > 1'000'000) return "max_points must be in [2, 1000000]";
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
    b.strobe = x.strobe;
    b.contacts = x.contacts;
    b.graze_gap = x.graze_gap;
    return b;
  }

  OrbitExtent extent(const Vector5d& z) {
    const auto [p, opt] = point_at_(lambda(z[4]));
    return orbit_extent(Model(p), opt.integrator, state(z), o_.n, counters);
  }

  double length_scale() const { return unit_[0]; }
  double from() const { return from_; }
  double span() const { return span_; }
  // A physical state difference in the scaled units.
  Eigen::Vector4d scaled_difference(const Eigen::Vector4d& d) const { return (d.array() / unit_).matrix(); }

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
// The largest turn of the tangent over one accepted step, rad.
constexpr double kMaxTurn = 0.3;
// A fold, period doubling or Neimark-Sacker point located within this fraction of the interval of
// a grazing located in the same step is the grazing's own jump of the multipliers (the map is not
// smooth there), not a bifurcation of the smooth theory: only the grazing is reported.
constexpr double kAtGrazing = 1e-6;
// The first step onto a doubled branch, scaled. Near the period doubling the residual of P^{2n}
// along v is (mu^2 - 1) h + O(h^3) with mu^2 - 1 -> 0, so any y* + h v with h below about
// (tol / |mu^2 - 1|) passes the residual test without being an orbit; a step of this size is far
// enough out that the cubic term decides, and the landing is a genuine 2n orbit.
constexpr double kSwitchStep = 0.02;
// A doubled branch rejoins its period-n orbit where |P^n(y) - y| (scaled) is below this.
constexpr double kRejoinGap = 1e-4;
// ... and the period doubling where it rejoins is that one of the parent's located within this
// fraction of the interval (its end is located on the doubled branch, to the branch's accuracy).
constexpr double kSameDoubling = 1e-3;
// A branch whose step stays below kStallStep for kStallPoints accepted points in a row stops:
// Newton converges only on tiny steps (a nonsmooth stretch the grazing logic does not cross).
constexpr double kStallStep = 1e-4;
constexpr int kStallPoints = 200;
// Crossings of one grazing point after the first before a branch stops there.
constexpr int kMaxCrossings = 8;
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


// Follows the branch from its last point z (evaluated: e) along t, appending to b.
// half > 0: a doubled branch, which ends where P^half(y) - y changes sign (it rejoined a period-half
// orbit at a period doubling of it, see continuation.hpp).
void trace(Problem& pb, Vector5d z, Eval e, Vector5d t, const ContinuationOptions& o, int half, Branch& b) {
  const double from = pb.from(), to = pb.from() + pb.span();
  const auto half_difference = [&](const BranchPoint& q) {
    return half > 0 && static_cast<int>(q.strobe.size()) > half ? pb.scaled_difference(q.strobe[half] - q.strobe[0])
                                                                : Eigen::Vector4d::Zero().eval();
  };
  double ds = o.ds;
  int stalled = 0;
  int crossings = 0;  // crossings of the last grazing marked
  while (static_cast<int>(b.points.size()) < o.max_points) {
    int iterations = 0;
    auto next = pb.correct(z + ds * t, t, &iterations);
    std::optional<Vector5d> t_next;
    if (next) {
      t_next = Problem::tangent(next->second, t);
      if (t.dot(*t_next) < std::cos(kMaxTurn)) next.reset();  // too sharp a turn: a smaller step
    }
    if (!next) {
      ds /= 2.0;
      if (ds >= o.ds_min) continue;
      // Steps that fail down to ds_min: at a grazing the map stops being smooth (an impact
      // appears), and Newton converges up to it from this side only, so the last point is the
      // grazing point to within ds_min. It is marked, and the branch is continued across with
      // steps from ds_min up, each accepted once Newton converges on the far side.
      const BranchPoint& last = b.points.back();
      const double touching = kGrazingTolerance * pb.length_scale();
      if (!(last.graze_gap <= touching)) {
        b.stop = "the step fell below ds_min (Newton does not converge: a nonsmooth point?)";
        return;
      }
      const bool known = std::any_of(b.bifurcations.begin(), b.bifurcations.end(), [&](const Bifurcation& g) {
        return g.type == BifurcationType::grazing && std::abs(g.at.param - last.param) <= 1e-6 * std::abs(to - from);
      });
      if (!known) {
        b.bifurcations.push_back({BifurcationType::grazing, last});
        crossings = 0;
      } else if (++crossings > kMaxCrossings) {
        b.stop = "grazing: the branch crosses it back and forth (Newton converges only next to it)";
        return;
      }
      std::optional<std::pair<Vector5d, Eval>> across;
      double jump = o.ds_min;
      // Predictors: along the tangent (the branch goes on straight), then the parameter alone
      // stepped on, then back (the far side is another branch through the grazing point, whose
      // tangent has nothing to do with this side's); accepted on the far side only.
      Vector5d along_l = Vector5d::Zero();
      along_l[4] = t[4] >= 0.0 ? 1.0 : -1.0;
      for (; jump <= o.ds_max && !across; jump *= 4.0)
        for (const Vector5d& d : {t, along_l, Vector5d(-along_l)}) {
          const auto far = pb.correct(z + jump * d, d);
          if (far && pb.extent(far->first).contacts != last.contacts) {
            across = far;
            break;
          }
        }
      if (!across) {
        b.stop = "grazing: Newton does not converge beyond it";
        return;
      }
      // The far side's tangent, oriented away from the grazing point.
      const Vector5d away = (across->first - z).normalized();
      z = across->first;
      e = across->second;
      t = Problem::tangent(e, away);
      b.points.push_back(pb.point(z, e));
      ds = std::max(jump, o.ds);
      continue;
    }
    const auto& [z1, e1] = *next;
    const Vector5d t1 = *t_next;
    BranchPoint p1 = pb.point(z1, e1);  // its extent once: the grazing test and the branch use it
    if (half > 0 && half_difference(p1).dot(half_difference(b.points.back())) < 0.0) {
      // Through the period doubling where it rejoins: located by bisection on the sign of
      // P^half(y) - y, the last point is that period doubling.
      const Eigen::Vector4d g0 = half_difference(b.points.back());
      double lo = 0.0, hi = ds;
      std::optional<BranchPoint> tip;
      while (hi - lo > o.locate_tol) {
        const double mid = 0.5 * (lo + hi);
        const auto m = pb.correct(z + mid * t, t);
        if (!m) break;
        BranchPoint q = pb.point(m->first, m->second);
        if (half_difference(q).dot(g0) < 0.0) {
          hi = mid;
          tip = std::move(q);
        } else {
          lo = mid;
        }
      }
      // Through a period doubling, P^half(y) - y goes through zero; a corrector that landed on
      // the orbit's other half (y and P^half(y) swapped) flips it without: a smaller step.
      if (!tip || half_difference(*tip).norm() > kRejoinGap) {
        ds /= 2.0;
        if (ds >= o.ds_min) continue;
        b.stop = "the step fell below ds_min (the doubled branch lands on its own other half)";
        return;
      }
      b.points.push_back(std::move(*tip));
      b.stop = "rejoined the period-" + std::to_string(half) + " orbit at a period doubling of it";
      return;
    }
    // Bifurcations between z and z1: bisection in the arclength s from z along t, on a test
    // `changed(z_m, eval at z_m, tangent at z_m)` that is false at z and true at z1; the point
    // located is the first one found with it true, within locate_tol of the change.
    std::vector<Bifurcation> found;
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
      found.push_back({type, at});
    };
    if ((t[4] > 0.0) != (t1[4] > 0.0))
      locate([&](const Vector5d&, const Eval&, const Vector5d& tm) { return (tm[4] > 0.0) != (t[4] > 0.0); },
             BifurcationType::fold);
    const double pd0 = pd_test(e);
    if ((pd0 > 0.0) != (pd_test(e1) > 0.0))
      locate([&](const Vector5d&, const Eval& em, const Vector5d&) { return (pd_test(em) > 0.0) != (pd0 > 0.0); },
             BifurcationType::period_doubling);
    const int ns0 = ns_count(e);
    if (ns0 != ns_count(e1))
      locate([&](const Vector5d&, const Eval& em, const Vector5d&) { return ns_count(em) != ns0; },
             BifurcationType::neimark_sacker);
    const int contacts0 = b.points.back().contacts;
    if (contacts0 != p1.contacts)
      locate([&](const Vector5d& zm, const Eval&, const Vector5d&) { return pb.extent(zm).contacts != contacts0; },
             BifurcationType::grazing);
    for (const Bifurcation& f : found) {
      const bool at_grazing = f.type != BifurcationType::grazing &&
                              std::any_of(found.begin(), found.end(), [&](const Bifurcation& g) {
                                return g.type == BifurcationType::grazing &&
                                       std::abs(g.at.param - f.at.param) <= kAtGrazing * std::abs(to - from);
                              });
      if (!at_grazing) b.bifurcations.push_back(f);
    }
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
      return;
    }
    z = z1;
    e = e1;
    t = t1;
    b.points.push_back(std::move(p1));
    stalled = ds < kStallStep ? stalled + 1 : 0;
    if (stalled >= kStallPoints) {
      b.stop = "stalled: " + std::to_string(kStallPoints) + " steps in a row below " + std::to_string(kStallStep).substr(0, 7) +
               " (Newton converges only on tiny steps)";
      return;
    }
    if (iterations <= 3) ds = std::min(1.5 * ds, o.ds_max);
  }
  b.stop = "max_points reached";
}

}  // namespace

Branch continue_orbit(const PointAt& point_at, double from, double to, const Eigen::Vector4d& y0,
                      const ContinuationOptions& o) {
  Branch b;
  b.n = o.n;
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
  const Vector5d z = pb.scaled(sh.y, 0.0);
  const std::optional<Eval> e = pb.eval(z);
  if (!e) {
    b.stop = "the integration failed at the start";
    b.counters = pb.counters;
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
  trace(pb, z, *e, t, o, 0, b);
  b.counters = pb.counters;
  return b;
}

Branch switch_period_doubling(const PointAt& point_at, double from, double to, const Bifurcation& pd,
                              const ContinuationOptions& o_n) {
  ContinuationOptions o = o_n;
  o.n = 2 * o_n.n;
  Branch b;
  b.n = o.n;
  if (const std::string err = validate(o); !err.empty()) {
    b.stop = err;
    return b;
  }
  if (pd.type != BifurcationType::period_doubling || !(to != from)) {
    b.stop = "not a period doubling in a non-empty interval";
    return b;
  }
  Problem pb(point_at, from, to, o);
  Problem half(point_at, from, to, o_n);
  const Vector5d z0 = pb.scaled(Model::to_internal(pd.at.y), (pd.at.param - from) / (to - from));
  const std::optional<Eval> e_half = half.eval(z0);
  const std::optional<Eval> e0 = pb.eval(z0);
  if (!e_half || !e0) {
    b.stop = "the integration failed at the period doubling";
    b.counters = pb.counters;
    b.counters += half.counters;
    return b;
  }
  // The eigenvector of the period-n multiplier nearest -1 (real: its eigenvalue is real), scaled.
  const Eigen::EigenSolver<Eigen::Matrix4d> es(e_half->M);
  Eigen::Index k = 0;
  (es.eigenvalues().array() + 1.0).abs().minCoeff(&k);
  Eigen::Vector4cd vc = es.eigenvectors().col(k);
  Eigen::Index big = 0;
  vc.cwiseAbs().maxCoeff(&big);
  vc /= vc[big];
  Vector5d t0 = Vector5d::Zero();
  t0.head<4>() = pb.scaled(vc.real(), 0.0).head<4>();
  t0 /= t0.norm();
  b.points.push_back(pb.point(z0, *e0));
  for (double h = kSwitchStep; h <= 16.0 * kSwitchStep; h *= 2.0) {
    const auto landed = pb.correct(z0 + h * t0, t0);
    if (!landed) continue;
    const std::optional<Eval> eh = half.eval(landed->first);
    if (!eh || eh->F.norm() < 0.1 * h) continue;  // the period-n orbit itself, not the doubled one
    const Vector5d t = Problem::tangent(landed->second, t0);
    b.points.push_back(pb.point(landed->first, landed->second));
    trace(pb, landed->first, landed->second, t, o, o_n.n, b);
    b.counters = pb.counters;
    b.counters += half.counters;
    return b;
  }
  b.stop = "no period-" + std::to_string(o.n) + " orbit found next to the period doubling";
  b.counters = pb.counters;
  b.counters += half.counters;
  return b;
}

std::vector<Branch> continue_branches(const PointAt& point_at, double from, double to, const Eigen::Vector4d& y0,
                                      const ContinuationOptions& o) {
  std::vector<Branch> out{continue_orbit(point_at, from, to, y0, o)};
  std::vector<int> depth{0};
  const double span = std::abs(to - from);
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (depth[i] >= o.pd_depth) continue;
    for (std::size_t j = 0; j < out[i].bifurcations.size(); ++j) {
      if (static_cast<int>(out.size()) >= o.max_branches) return out;
      const Bifurcation pd = out[i].bifurcations[j];
      if (pd.type != BifurcationType::period_doubling) continue;
      // Already found: a doubled branch of the same parent that ends at this period doubling.
      const bool known = std::any_of(out.begin(), out.end(), [&](const Branch& s) {
        return s.parent == static_cast<int>(i) && !s.points.empty() && s.stop.rfind("rejoined", 0) == 0 &&
               std::abs(s.points.back().param - pd.at.param) <= kSameDoubling * span;
      });
      if (known) continue;
      ContinuationOptions on = o;
      on.n = out[i].n;
      Branch s = switch_period_doubling(point_at, from, to, pd, on);
      s.parent = static_cast<int>(i);
      s.born_at = static_cast<int>(j);
      out.push_back(std::move(s));
      depth.push_back(depth[i] + 1);
    }
  }
  return out;
}

}  // namespace vibromap
