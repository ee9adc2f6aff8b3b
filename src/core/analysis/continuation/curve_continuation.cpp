// Curves of codimension-one points in two parameters: see curve_continuation.hpp.

#include "vibromap/core/analysis/continuation/curve_continuation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

#include "continuation_problem.hpp"
#include "curve_problem.hpp"
#include "vibromap/core/quantities.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap {

using curve_detail::CurveEval;
using curve_detail::CurveProblem;
using curve_detail::Vector6d;

std::optional<CurveSpec> parse_curve_spec(const std::string& text, std::string& error) {
  CurveSpec s;
  s.label = text;
  if (text == "fold") s.kind = CurveKind::fold;
  else if (text == "period-doubling") s.kind = CurveKind::period_doubling;
  else if (text == "neimark-sacker") s.kind = CurveKind::neimark_sacker;
  else if (text == "grazing") s.kind = CurveKind::grazing;
  else if (text.rfind("level:", 0) == 0) {
    s.kind = CurveKind::level;
    const std::string rest = text.substr(6);
    const auto eq = rest.find('=');
    const std::string name = rest.substr(0, eq);
    if (name == "k_con") s.quantity = LevelQuantity::k_con;
    else if (name == "T_con") s.quantity = LevelQuantity::T_con;
    else if (name == "F_max") s.quantity = LevelQuantity::F_max;
    else if (name == "z_ratio") s.quantity = LevelQuantity::z_ratio;
    else {
      error = text + ": NAME " + name + " is not one of k_con, T_con, F_max, z_ratio";
      return std::nullopt;
    }
    const std::string value = eq == std::string::npos ? std::string() : rest.substr(eq + 1);
    char* end = nullptr;
    s.value = std::strtod(value.c_str(), &end);
    if (value.empty() || end != value.c_str() + value.size() || !std::isfinite(s.value)) {
      error = text + ": VALUE must be a finite number";
      return std::nullopt;
    }
    // A level the quantity never takes (k_con <= 0) would give no curve and no word why.
    const Quantity q = parse_quantity(name);
    if (const Bounds range = quantity_range(q); !range.contains(s.value)) {
      const std::string_view units = quantity_units(q);
      error = cat(text, ": VALUE ", value, " is outside the values ", name, " takes: it must be ", range.to_string(),
                  units == "1" ? std::string() : cat(" (", units, ")"));
      return std::nullopt;
    }
  } else {
    error = text + ": not one of fold, period-doubling, neimark-sacker, grazing, level:NAME=VALUE";
    return std::nullopt;
  }
  return s;
}

double level_value(LevelQuantity q, const PointSummary& s) {
  switch (q) {
    case LevelQuantity::k_con: return s.k_con;
    case LevelQuantity::T_con: return s.T_con;
    case LevelQuantity::F_max: return s.F_max;
    case LevelQuantity::z_ratio: break;
  }
  return s.z_ratio;
}

namespace {

using Corrected = std::pair<Vector6d, CurveEval>;

// "KEY = value" of P (second: Q) for the messages, in the key's own units (CurveBox::log).
std::string key_value(const CurveBox& box, bool second, double x) {
  const bool log = second ? box.log2 : box.log;
  return (second ? box.key2 : box.key) + " = " + number(log ? std::exp(x) : x, 10);
}

// The other kinds a curve watches (curve_continuation.hpp), by their label.
enum class Watch { fold, period_doubling, neimark_sacker, grazing, cusp };
const char* watch_label(Watch w) {
  switch (w) {
    case Watch::fold: return "fold";
    case Watch::period_doubling: return "period-doubling";
    case Watch::neimark_sacker: return "neimark-sacker";
    case Watch::grazing: return "grazing";
    case Watch::cusp: break;
  }
  return "cusp";
}

std::vector<Watch> watches(CurveKind kind) {
  std::vector<Watch> w;
  if (kind != CurveKind::fold) w.push_back(Watch::fold);
  if (kind != CurveKind::period_doubling) w.push_back(Watch::period_doubling);
  if (kind != CurveKind::neimark_sacker) w.push_back(Watch::neimark_sacker);
  if (kind != CurveKind::grazing) w.push_back(Watch::grazing);
  if (kind == CurveKind::fold) w.push_back(Watch::cusp);
  return w;
}

// One end of a step: the point, its evaluation, tangent and what is measured of it.
struct End {
  Vector6d z;
  CurveEval e;
  Vector6d t;
  CurvePoint p;
};

// Whether watch w differs between a and b.
bool changed(Watch w, const End& a, const End& b) {
  switch (w) {
    case Watch::fold: return (curve_detail::fold_test(a.e.M) > 0.0) != (curve_detail::fold_test(b.e.M) > 0.0);
    case Watch::period_doubling: return (curve_detail::pd_test(a.e.M) > 0.0) != (curve_detail::pd_test(b.e.M) > 0.0);
    case Watch::neimark_sacker: return curve_detail::ns_count(a.e.M) != curve_detail::ns_count(b.e.M);
    case Watch::grazing: return a.p.contacts != b.p.contacts;
    case Watch::cusp: break;
  }
  return a.t.segment<2>(4).dot(b.t.segment<2>(4)) < 0.0;
}

// The walk along one direction of a curve from its start.
class CurveTracer {
 public:
  CurveTracer(CurveProblem& pb, const End& start, Curve& curve, std::vector<CurvePoint>& out)
      : pb_(pb), o_(pb.options().base), last_(start), start_(start.z), curve_(curve), out_(out), ds_(o_.ds) {}

  // Walks until the curve stops; returns why (one sentence) and whether it closed on its start.
  std::string run(bool& closed);

 private:
  std::optional<End> predict_correct(int& iterations);
  void locate_codim2(const End& next);
  void end_at_box(const End& next);

  CurveProblem& pb_;
  const ContinuationOptions& o_;
  End last_;
  Vector6d start_;
  Curve& curve_;
  std::vector<CurvePoint>& out_;
  double ds_;
  int stalled_ = 0;  // accepted steps in a row below kStallStep
  std::string stop_;
};

std::optional<End> CurveTracer::predict_correct(int& iterations) {
  pb_.track_phase(last_.p.phase);  // grazing: the approach tracked at the last point (the others keep it)
  const std::optional<Corrected> c = pb_.correct(last_.z + ds_ * last_.t, last_.t, &iterations);
  if (!c) return std::nullopt;
  const Vector6d t1 = CurveProblem::tangent(c->second, last_.t);
  if (last_.t.dot(t1) < std::cos(continuation_detail::kMaxTurn)) return std::nullopt;
  return End{c->first, c->second, t1, pb_.point(c->first, c->second)};
}

std::string CurveTracer::run(bool& closed) {
  closed = false;
  while (static_cast<int>(out_.size()) < o_.max_points) {
    if (stop_requested(o_)) return kStoppedOnRequest;
    int iterations = 0;
    const std::optional<End> next = predict_correct(iterations);
    if (!next) {
      ds_ /= 2.0;
      if (ds_ >= o_.ds_min) continue;
      return "cannot be continued beyond " + key_value(pb_.box(), false, last_.p.param) + ", " +
             key_value(pb_.box(), true, last_.p.param2) + " (Newton does not converge on steps down to ds_min)";
    }
    locate_codim2(*next);
    const double u = next->z[4], v = next->z[5];
    if (u < -1e-12 || u > 1.0 + 1e-12 || v < -1e-12 || v > 1.0 + 1e-12) {
      end_at_box(*next);
      return stop_;
    }
    const double step = (next->z - last_.z).norm();
    last_ = *next;
    out_.push_back(next->p);
    stalled_ = ds_ < continuation_detail::kStallStep ? stalled_ + 1 : 0;
    if (stalled_ >= continuation_detail::kStallPoints)
      return "stalled at " + key_value(pb_.box(), false, last_.p.param) + ", " +
             key_value(pb_.box(), true, last_.p.param2) + ": " + std::to_string(continuation_detail::kStallPoints) +
             " steps in a row below 1e-4 (Newton converges only on tiny steps: the map is not smooth here)";
    if (iterations <= 3) ds_ = std::min(1.5 * ds_, o_.ds_max);
    if (out_.size() > 3 && (last_.z - start_).norm() < 0.5 * step) {
      closed = true;
      return "closed: came back to its start";
    }
  }
  return "max_points reached";
}

void CurveTracer::locate_codim2(const End& next) {
  for (const Watch w : watches(pb_.spec().kind)) {
    if (!changed(w, last_, next)) continue;
    double lo = 0.0, hi = (next.z - last_.z).dot(last_.t);
    End best = next;
    while (hi - lo > o_.locate_tol) {
      const double mid = 0.5 * (lo + hi);
      const auto m = pb_.correct(last_.z + mid * last_.t, last_.t);
      if (!m) break;
      const End at{m->first, m->second, CurveProblem::tangent(m->second, last_.t), pb_.point(m->first, m->second)};
      if (changed(w, last_, at)) {
        hi = mid;
        best = at;
      } else {
        lo = mid;
      }
    }
    std::string kind = w == Watch::cusp ? "cusp" : pb_.spec().label + "+" + watch_label(w);
    if (pb_.spec().kind == CurveKind::level) kind = std::string(watch_label(w)) + "+" + pb_.spec().label;
    curve_.codim2.push_back({best.p.param, best.p.param2, kind});
  }
}

void CurveTracer::end_at_box(const End& next) {
  // The bound crossed first along the step, and the point on it (that coordinate fixed).
  int k = -1;
  double s_first = 2.0, bound = 0.0;
  for (int c = 4; c < 6; ++c) {
    const double x0 = last_.z[c], x1 = next.z[c];
    for (const double b : {0.0, 1.0}) {
      if (!(b == 0.0 ? x1 < 0.0 : x1 > 1.0)) continue;
      const double s = (b - x0) / (x1 - x0);
      if (s < s_first) s_first = s, k = c, bound = b;
    }
  }
  Vector6d z_end = last_.z + s_first * (next.z - last_.z);
  z_end[k] = bound;
  Vector6d fixed = Vector6d::Zero();
  fixed[k] = 1.0;
  if (const auto end = pb_.correct(z_end, fixed)) out_.push_back(pb_.point(end->first, end->second));
  const double value = k == 4 ? pb_.P(bound) : pb_.Q(bound);
  stop_ = "left the box at " + key_value(pb_.box(), k == 5, value);
}

Vector6d fixed_q() {
  Vector6d t = Vector6d::Zero();
  t[5] = 1.0;
  return t;
}

std::string contacts_text(int k) { return std::to_string(k) + (k == 1 ? " contact" : " contacts"); }

// Which kind of grazing the start p of a grazing curve is: its other contacts k, and on which
// side in Q the tracked impact exists. With P fixed, the rows of J without P's column give
// (dy, dv) per unit dg; dv > 0: the clearance grows with Q, so the impact is at lower Q.
std::string grazing_kind(const CurveEval& e, const CurvePoint& p, const CurveBox& box) {
  Eigen::Matrix<double, 5, 5> A;
  A.leftCols<4>() = e.J.leftCols<4>();
  A.col(4) = e.J.col(5);
  Eigen::Matrix<double, 5, 1> rhs = Eigen::Matrix<double, 5, 1>::Zero();
  rhs[4] = 1.0;
  const double dv = A.fullPivLu().solve(rhs)[4];
  const int k = p.other_contacts;
  const std::string more = dv > 0.0 ? "lower " : "higher ", fewer = dv > 0.0 ? "higher " : "lower ";
  return (k == 0 ? std::string("a contact-free orbit touches: ")
                 : "an impact appears on an orbit with " + contacts_text(k) + " per cycle: ") +
         std::to_string(k + 1) + " at " + more + box.key2 + ", " + std::to_string(k) + " at " + fewer + box.key2;
}

}  // namespace

Curve continue_curve(const PointAt2& at, const CurveBox& box, const CurveSpec& spec, int n, double start_param,
                     double q0, const Eigen::Vector4d& y0, const CurveOptions& options) {
  Curve c;
  c.spec = spec;
  c.n = n;
  if (const std::string err = validate(options.base); !err.empty()) {
    c.stop = err;
    return c;
  }
  CurveProblem pb(at, box, spec, n, options);
  const Vector6d z0 = pb.scaled(Model::to_internal(y0), start_param, q0);
  if (spec.kind == CurveKind::grazing && !pb.track_touching(z0)) {
    c.stop = "the orbit located at " + key_value(box, false, start_param) + " has no approach of the bodies";
    c.counters = pb.counters;
    return c;
  }
  const std::optional<Corrected> s = pb.correct(z0, fixed_q());
  if (!s) {
    c.stop = "the point located at " + key_value(box, false, start_param) +
             " does not solve the extended system (Newton with " + box.key2 + " fixed fails)";
    c.counters = pb.counters;
    return c;
  }
  Vector6d t0 = CurveProblem::null_vector(s->second);
  if ((std::abs(t0[5]) > 1e-12 ? t0[5] : t0[4]) < 0.0) t0 = -t0;
  const End start{s->first, s->second, t0, pb.point(s->first, s->second)};
  if (spec.kind == CurveKind::grazing) c.grazing = grazing_kind(s->second, start.p, box);
  std::vector<CurvePoint> up, down;
  bool closed = false;
  c.stop = CurveTracer(pb, start, c, up).run(closed);
  if (!closed && !stop_requested(options.base)) {
    End back = start;
    back.t = -t0;
    c.stop += "; " + CurveTracer(pb, back, c, down).run(closed);
  }
  c.points.assign(down.rbegin(), down.rend());
  c.start = static_cast<int>(c.points.size());
  c.points.push_back(start.p);
  c.points.insert(c.points.end(), up.begin(), up.end());
  c.counters = pb.counters;
  return c;
}

std::optional<CurvePoint> locate_level(const PointAt2& at, const CurveBox& box, const CurveSpec& spec, int n, double q0,
                                       const BranchPoint& a, double va, const BranchPoint& b, double vb,
                                       const CurveOptions& options) {
  CurveProblem pb(at, box, spec, n, options);
  const Vector6d za = pb.scaled(Model::to_internal(a.y), a.param, q0);
  const Vector6d zb = pb.scaled(Model::to_internal(b.y), b.param, q0);
  const double w = (spec.value - va) / (vb - va);
  const std::optional<Corrected> s = pb.correct(za + w * (zb - za), fixed_q());
  if (!s) return std::nullopt;
  const double lo = std::min(za[4], zb[4]), hi = std::max(za[4], zb[4]), slack = 1e-6 + 0.5 * (hi - lo);
  if (s->first[4] < lo - slack || s->first[4] > hi + slack) return std::nullopt;
  return pb.point(s->first, s->second);
}

}  // namespace vibromap
