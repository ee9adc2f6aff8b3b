#include "vibromap/core/optimise/gradient_projection.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace vibromap {
namespace {

using Vec = std::vector<double>;

double dot(const Vec& a, const Vec& b) { return std::inner_product(a.begin(), a.end(), b.begin(), 0.0); }

double max_abs(const Vec& a) {
  double m = 0.0;
  for (const double v : a) m = std::max(m, std::abs(v));
  return m;
}

// A point of the run and its evaluation.
struct Point {
  Vec u;
  Evaluation e;
};

// Outcome of one line search.
enum class Search { accepted, too_short, budget };

class GradientProjection {
 public:
  GradientProjection(TrackedObjective& f, const GradientProjectionOptions& o)
      : f_(f), o_(o), lo_(f.options()), step_(lo_.initial_step) {}

  StopReason run(std::span<const double> u0) {
    const std::optional<Evaluation> e0 = f_.evaluate(u0);
    if (!e0) return {f_.budget_reason()};
    if (!e0->feasible) return {"INFEASIBLE_START"};
    x_.u.assign(u0.begin(), u0.end());
    for (double& v : x_.u) v = std::clamp(v, 0.0, 1.0);
    x_.e = *e0;
    for (;;) {
      const std::optional<FdGradient> g = fd_gradient(f_, x_.u, x_.e, lo_.fd_step);
      if (!g) return {f_.budget_reason()};
      const Vec d = direction(*g);
      if (max_abs(d) == 0.0) return {"GRADIENT_ZERO"};
      Point next;
      const Search s = line_search(*g, d, next);
      if (s == Search::budget) return {f_.budget_reason()};
      if (s == Search::too_short) return {"XTOL_REACHED"};
      Vec moved(next.u.size());
      for (std::size_t i = 0; i < moved.size(); ++i) moved[i] = next.u[i] - x_.u[i];
      const double decrease = x_.e.value - next.e.value;
      x_ = std::move(next);
      step_ = std::min(o_.max_step, 2.0 * max_abs(moved));
      if (max_abs(moved) <= lo_.xtol_rel) return {"XTOL_REACHED"};
      if (decrease <= lo_.ftol_rel * std::abs(x_.e.value)) return {"FTOL_REACHED"};
    }
  }

 private:
  // -grad f projected on the tangent space of the active constraints together: the active
  // bounds (the variables held) and, when the step is predicted to cross it, the regime
  // boundary, whose normal is restricted to the free variables so that the projection keeps
  // the held ones held (a projection on one after the other would not be a descent direction).
  Vec direction(const FdGradient& g) const {
    Vec d(g.value.size());
    std::vector<bool> held(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      d[i] = -g.value[i];
      held[i] = (x_.u[i] <= 0.0 && d[i] < 0.0) || (x_.u[i] >= 1.0 && d[i] > 0.0);
      if (held[i]) d[i] = 0.0;
    }
    Vec n = g.violation;
    for (std::size_t i = 0; i < n.size(); ++i)
      if (held[i]) n[i] = 0.0;
    const double n2 = dot(n, n);
    if (n2 == 0.0 || max_abs(d) == 0.0 || dot(n, d) <= 0.0) return d;
    if (x_.e.violation + step_ * dot(n, d) / max_abs(d) <= 0.0) return d;  // the step stays inside
    Vec tangent = d;
    const double along = dot(d, n) / n2;
    for (std::size_t i = 0; i < d.size(); ++i) tangent[i] -= along * n[i];
    return dot(g.value, tangent) < 0.0 ? tangent : d;  // descent, else the corrections take over
  }

  // Backtracking along d from x_: halves the step until a feasible trial decreases f enough.
  Search line_search(const FdGradient& g, const Vec& d, Point& out) {
    const double scale = max_abs(d);
    for (;;) {
      if (step_ < lo_.xtol_rel) return Search::too_short;
      Vec s(d.size());
      for (std::size_t i = 0; i < s.size(); ++i) s[i] = std::clamp(x_.u[i] + step_ * d[i] / scale, 0.0, 1.0) - x_.u[i];
      const Search found = corrected_trial(g, s, out);
      if (found == Search::budget) return found;
      if (found == Search::accepted) {
        Vec moved(s.size());
        for (std::size_t i = 0; i < moved.size(); ++i) moved[i] = out.u[i] - x_.u[i];
        if (out.e.value <= x_.e.value + o_.armijo * dot(g.value, moved)) return Search::accepted;
      }
      step_ *= 0.5;
    }
  }

  // The trial x_ + s, corrected toward feasibility while it is infeasible (see the header):
  // Rosen's restoration step along -grad c while the violation is continuous (the kept
  // regime, c < 1), else to 90 % of the linearised crossing, else halving toward x_.
  Search corrected_trial(const FdGradient& g, Vec s, Point& out) {
    const double gc2 = dot(g.violation, g.violation);
    int restorations = 0;
    for (int k = 0; k <= o_.max_corrections; ++k) {
      out.u.resize(s.size());
      for (std::size_t i = 0; i < s.size(); ++i) out.u[i] = x_.u[i] + s[i];
      const std::optional<Evaluation> e = f_.evaluate(out.u);
      if (!e) return Search::budget;
      out.e = *e;
      if (out.e.feasible) return Search::accepted;
      if (out.e.violation < 1.0 && gc2 > 0.0 && restorations++ < o_.max_restorations) {
        const double shift = (out.e.violation + o_.restore_margin) / gc2;
        for (std::size_t i = 0; i < s.size(); ++i)
          s[i] = std::clamp(x_.u[i] + s[i] - shift * g.violation[i], 0.0, 1.0) - x_.u[i];
      } else {
        const double slope = dot(g.violation, s);
        double t = 0.5;
        if (slope > 0.0 && x_.e.violation < 0.0 && -x_.e.violation / slope < 1.0) t = 0.9 * (-x_.e.violation / slope);
        for (double& v : s) v *= t;
      }
      if (max_abs(s) < lo_.xtol_rel) return Search::too_short;
    }
    return Search::too_short;
  }

  TrackedObjective& f_;
  GradientProjectionOptions o_;
  LocalOptions lo_;
  double step_;
  Point x_;
};

}  // namespace

StopReason run_gradient_projection(TrackedObjective& f, std::span<const double> u0,
                                   const GradientProjectionOptions& options) {
  return GradientProjection(f, options).run(u0);
}

}  // namespace vibromap
