#include "vibromap/core/analysis/continuation/continuation.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "continuation_problem.hpp"
#include "vibromap/core/analysis/continuation/orbit_extent.hpp"
#include "vibromap/core/analysis/point/shooting.hpp"
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

using continuation_detail::Eval;
using continuation_detail::kMaxTurn;
using continuation_detail::kStallPoints;
using continuation_detail::kStallStep;
using continuation_detail::Problem;
using continuation_detail::Vector5d;

// A point whose closest approach is within this many motion scales of zero is at a grazing.
constexpr double kGrazingTolerance = 1e-6;

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


// A corrected point on the branch and its evaluation.
using Corrected = std::pair<Vector5d, Eval>;

// The next point of a branch, corrected: the point, its tangent and Newton's iterations.
struct Next {
  Corrected at;
  Vector5d t;
  int iterations;
};

// The walk along one branch from its last point: the point z (evaluated: e), the tangent t and
// the step ds, and the named steps of one move. trace() below is the walk itself.
class Tracer {
 public:
  // half > 0: a doubled branch, which ends where P^half(y) - y changes sign (it rejoined a
  // period-half orbit at a period doubling of it, see continuation.hpp).
  Tracer(Problem& pb, const Vector5d& z, const Eval& e, const Vector5d& t, const ContinuationOptions& o, int half,
         Branch& b)
      : pb_(pb), o_(o), half_(half), b_(b), z_(z), e_(e), t_(t), ds_(o.ds),
        span_(std::abs((pb.from() + pb.span()) - pb.from())) {}

  // One move along the branch: a point appended, or a smaller step to try; false when the
  // branch stopped (b.stop says why).
  bool step();

 private:
  // Predictor-corrector: Newton from z + ds t; none when it fails or the tangent turns too sharply.
  std::optional<Next> predict_correct();

  // Halves the step; false once it is below ds_min.
  bool smaller_step();

  Eigen::Vector4d half_difference(const BranchPoint& q) const;

  // Grazing crossing. Steps that fail down to ds_min: at a grazing the map stops being smooth
  // (an impact appears), and Newton converges up to it from this side only, so the last point
  // is the grazing point to within ds_min. It is marked, and the branch is continued across
  // with steps from ds_min up, each accepted once Newton converges on the far side.
  bool cross_grazing();

  // The grazing at `last` among the branch's bifurcations (once); false when the branch has
  // crossed it back and forth too often.
  bool mark_grazing(const BranchPoint& last);

  // A point beyond the grazing, from steps `jump` growing from ds_min. Predictors: along the
  // tangent (the branch goes on straight), then the parameter alone stepped on, then back (the
  // far side is another branch through the grazing point, whose tangent has nothing to do with
  // this side's); accepted on the far side only.
  std::optional<Corrected> far_side(const BranchPoint& last, double& jump);

  // Branch switching's end: through the period doubling where a doubled branch rejoins its
  // period-half orbit, located by bisection on the sign of P^half(y) - y; the last point is
  // that period doubling.
  bool rejoin();

  // Event location: the bifurcations between z and the next point, each by a test function
  // whose sign (or count) changes there, appended to the branch unless at a grazing.
  void locate_bifurcations(const Next& next, const BranchPoint& p1);

  // Bisection in the arclength s from z along t, on a test `changed(z_m, eval at z_m, tangent
  // at z_m)` that is false at z and true at `end`; the point located is the first one found
  // with it true, within locate_tol of the change.
  template <class Changed>
  void locate(Changed changed, BifurcationType type, const Corrected& end, std::vector<Bifurcation>& found);

  // The branch leaves the interval: its last point is at the end it crosses, corrected with the
  // parameter fixed there.
  void end_at_interval(const Vector5d& z1);

  // The next point becomes the branch's last; the step grows after an easy correction. False
  // when the branch has stalled.
  bool accept(const Next& next, BranchPoint p1);

  Problem& pb_;
  const ContinuationOptions& o_;
  int half_;
  Branch& b_;
  Vector5d z_;
  Eval e_;
  Vector5d t_;
  double ds_;
  double span_;        // |to - from|, as the interval's ends give it
  int stalled_ = 0;    // accepted steps in a row below kStallStep
  int crossings_ = 0;  // crossings of the last grazing marked
};

bool Tracer::step() {
  const std::optional<Next> next = predict_correct();
  if (!next) return smaller_step() || cross_grazing();
  BranchPoint p1 = pb_.point(next->at.first, next->at.second);  // its extent once: the tests and the branch use it
  if (half_ > 0 && half_difference(p1).dot(half_difference(b_.points.back())) < 0.0) return rejoin();
  locate_bifurcations(*next, p1);
  if (next->at.first[4] < -1e-12 || next->at.first[4] > 1.0 + 1e-12) {
    end_at_interval(next->at.first);
    return false;
  }
  return accept(*next, std::move(p1));
}

std::optional<Next> Tracer::predict_correct() {
  int iterations = 0;
  const std::optional<Corrected> corrected = pb_.correct(z_ + ds_ * t_, t_, &iterations);
  if (!corrected) return std::nullopt;
  const Vector5d t1 = Problem::tangent(corrected->second, t_);
  if (t_.dot(t1) < std::cos(kMaxTurn)) return std::nullopt;  // too sharp a turn: a smaller step
  return Next{*corrected, t1, iterations};
}

bool Tracer::smaller_step() {
  ds_ /= 2.0;
  return ds_ >= o_.ds_min;
}

Eigen::Vector4d Tracer::half_difference(const BranchPoint& q) const {
  return half_ > 0 && static_cast<int>(q.strobe.size()) > half_ ? pb_.scaled_difference(q.strobe[half_] - q.strobe[0])
                                                                : Eigen::Vector4d::Zero().eval();
}

bool Tracer::cross_grazing() {
  const BranchPoint& last = b_.points.back();
  const double touching = kGrazingTolerance * pb_.length_scale();
  if (!(last.graze_gap <= touching)) {
    b_.stop = "the step fell below ds_min (Newton does not converge: a nonsmooth point?)";
    return false;
  }
  if (!mark_grazing(last)) return false;
  double jump = o_.ds_min;
  const std::optional<Corrected> across = far_side(last, jump);
  if (!across) {
    b_.stop = "grazing: Newton does not converge beyond it";
    return false;
  }
  // The far side's tangent, oriented away from the grazing point.
  const Vector5d away = (across->first - z_).normalized();
  z_ = across->first;
  e_ = across->second;
  t_ = Problem::tangent(e_, away);
  b_.points.push_back(pb_.point(z_, e_));
  ds_ = std::max(jump, o_.ds);
  return true;
}

bool Tracer::mark_grazing(const BranchPoint& last) {
  const bool known = std::any_of(b_.bifurcations.begin(), b_.bifurcations.end(), [&](const Bifurcation& g) {
    return g.type == BifurcationType::grazing && std::abs(g.at.param - last.param) <= 1e-6 * span_;
  });
  if (!known) {
    b_.bifurcations.push_back({BifurcationType::grazing, last});
    crossings_ = 0;
  } else if (++crossings_ > kMaxCrossings) {
    b_.stop = "grazing: the branch crosses it back and forth (Newton converges only next to it)";
    return false;
  }
  return true;
}

std::optional<Corrected> Tracer::far_side(const BranchPoint& last, double& jump) {
  std::optional<Corrected> across;
  Vector5d along_l = Vector5d::Zero();
  along_l[4] = t_[4] >= 0.0 ? 1.0 : -1.0;
  for (; jump <= o_.ds_max && !across; jump *= 4.0)
    for (const Vector5d& d : {t_, along_l, Vector5d(-along_l)}) {
      const auto far = pb_.correct(z_ + jump * d, d);
      if (far && pb_.extent(far->first).contacts != last.contacts) {
        across = far;
        break;
      }
    }
  return across;
}

bool Tracer::rejoin() {
  const Eigen::Vector4d g0 = half_difference(b_.points.back());
  double lo = 0.0, hi = ds_;
  std::optional<BranchPoint> tip;
  while (hi - lo > o_.locate_tol) {
    const double mid = 0.5 * (lo + hi);
    const auto m = pb_.correct(z_ + mid * t_, t_);
    if (!m) break;
    BranchPoint q = pb_.point(m->first, m->second);
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
    if (smaller_step()) return true;
    b_.stop = "the step fell below ds_min (the doubled branch lands on its own other half)";
    return false;
  }
  b_.points.push_back(std::move(*tip));
  b_.stop = "rejoined the period-" + std::to_string(half_) + " orbit at a period doubling of it";
  return false;
}

void Tracer::locate_bifurcations(const Next& next, const BranchPoint& p1) {
  const Eval& e1 = next.at.second;
  std::vector<Bifurcation> found;
  if ((t_[4] > 0.0) != (next.t[4] > 0.0))
    locate([&](const Vector5d&, const Eval&, const Vector5d& tm) { return (tm[4] > 0.0) != (t_[4] > 0.0); },
           BifurcationType::fold, next.at, found);
  const double pd0 = pd_test(e_);
  if ((pd0 > 0.0) != (pd_test(e1) > 0.0))
    locate([&](const Vector5d&, const Eval& em, const Vector5d&) { return (pd_test(em) > 0.0) != (pd0 > 0.0); },
           BifurcationType::period_doubling, next.at, found);
  const int ns0 = ns_count(e_);
  if (ns0 != ns_count(e1))
    locate([&](const Vector5d&, const Eval& em, const Vector5d&) { return ns_count(em) != ns0; },
           BifurcationType::neimark_sacker, next.at, found);
  const int contacts0 = b_.points.back().contacts;
  if (contacts0 != p1.contacts)
    locate([&](const Vector5d& zm, const Eval&, const Vector5d&) { return pb_.extent(zm).contacts != contacts0; },
           BifurcationType::grazing, next.at, found);
  for (const Bifurcation& f : found) {
    const bool at_grazing = f.type != BifurcationType::grazing &&
                            std::any_of(found.begin(), found.end(), [&](const Bifurcation& g) {
                              return g.type == BifurcationType::grazing &&
                                     std::abs(g.at.param - f.at.param) <= kAtGrazing * span_;
                            });
    if (!at_grazing) b_.bifurcations.push_back(f);
  }
}

template <class Changed>
void Tracer::locate(Changed changed, BifurcationType type, const Corrected& end, std::vector<Bifurcation>& found) {
  double lo = 0.0, hi = ds_;
  std::optional<Corrected> best = end;
  while ((hi - lo) > o_.locate_tol) {
    const double mid = 0.5 * (lo + hi);
    const auto m = pb_.correct(z_ + mid * t_, t_);
    if (!m) break;
    if (changed(m->first, m->second, Problem::tangent(m->second, t_))) {
      hi = mid;
      best = m;
    } else {
      lo = mid;
    }
  }
  BranchPoint at = pb_.point(best->first, best->second);
  if (type != BifurcationType::grazing && !has_critical_multiplier(type, at.multipliers)) return;
  found.push_back({type, at});
}

void Tracer::end_at_interval(const Vector5d& z1) {
  const double end = z1[4] > 1.0 ? 1.0 : 0.0;
  Vector5d fixed = Vector5d::Zero();
  fixed[4] = 1.0;
  const double s = (end - z_[4]) / (z1[4] - z_[4]);
  Vector5d z_end = z_ + s * (z1 - z_);
  z_end[4] = end;
  if (const auto last = pb_.correct(z_end, fixed)) b_.points.push_back(pb_.point(last->first, last->second));
  b_.stop = end == 1.0 ? "reached the end of the interval" : "came back to the start of the interval";
}

bool Tracer::accept(const Next& next, BranchPoint p1) {
  z_ = next.at.first;
  e_ = next.at.second;
  t_ = next.t;
  b_.points.push_back(std::move(p1));
  stalled_ = ds_ < kStallStep ? stalled_ + 1 : 0;
  if (stalled_ >= kStallPoints) {
    b_.stop = "stalled: " + std::to_string(kStallPoints) + " steps in a row below " +
              std::to_string(kStallStep).substr(0, 7) + " (Newton converges only on tiny steps)";
    return false;
  }
  if (next.iterations <= 3) ds_ = std::min(1.5 * ds_, o_.ds_max);
  return true;
}

// Follows the branch from its last point z (evaluated: e) along t, appending to b, until it
// stops or has max_points points. half > 0: a doubled branch (Tracer).
void trace(Problem& pb, const Vector5d& z, const Eval& e, const Vector5d& t, const ContinuationOptions& o, int half,
           Branch& b) {
  Tracer tracer(pb, z, e, t, o, half, b);
  while (static_cast<int>(b.points.size()) < o.max_points) {
    if (stop_requested(o)) {
      b.stop = kStoppedOnRequest;
      return;
    }
    if (!tracer.step()) return;
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
      if (static_cast<int>(out.size()) >= o.max_branches || stop_requested(o)) return out;
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
