#include <algorithm>
#include <cmath>
#include <exception>

#include "vibromap/core/optimise/objective.hpp"

namespace vibromap {

TrackedObjective::TrackedObjective(Objective& f, Box box, const LocalOptions& options)
    : f_(f), box_(std::move(box)), options_(options) {}

double TrackedObjective::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

bool TrackedObjective::exhausted() const {
  if (static_cast<long>(history_.size()) >= options_.max_evaluations) return true;
  return options_.max_time > 0.0 && elapsed() >= options_.max_time;
}

std::string TrackedObjective::budget_reason() const {
  return static_cast<long>(history_.size()) >= options_.max_evaluations ? "MAXEVAL_REACHED" : "MAXTIME_REACHED";
}

// The objective's answer, made safe: an exception or a non-finite number is a failed point,
// never a crash and never a feasible one.
Evaluation TrackedObjective::checked_evaluation(std::span<const double> x) {
  Evaluation e;
  try {
    e = f_.evaluate(x);
  } catch (const std::exception& ex) {
    e = Evaluation{};
    e.message = std::string("evaluation failed: ") + ex.what();
    return e;
  }
  if (!std::isfinite(e.violation)) {
    e.violation = kFailedViolation;
    e.feasible = false;
  }
  if (!std::isfinite(e.value) || e.violation > 0.0) e.feasible = false;
  return e;
}

std::optional<Evaluation> TrackedObjective::evaluate(std::span<const double> u_in) {
  std::vector<double> u(u_in.begin(), u_in.end());
  for (double& v : u) v = std::isnan(v) ? 0.0 : std::clamp(v, 0.0, 1.0);
  if (const auto it = cache_.find(u); it != cache_.end()) {
    ++calls_;
    ++cache_hits_;
    return history_[it->second].result;
  }
  if (exhausted()) return std::nullopt;
  ++calls_;
  const auto t0 = std::chrono::steady_clock::now();
  EvaluationRecord rec{box_.to_physical(u), {}, 0.0};
  rec.result = checked_evaluation(rec.x);
  rec.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::size_t index = history_.size();
  if (rec.result.feasible && (!best_ || rec.result.value < history_[*best_].result.value)) best_ = index;
  history_.push_back(std::move(rec));
  cache_.emplace(std::move(u), index);
  return history_[index].result;
}

namespace {

bool usable(const Evaluation& e, const Evaluation& centre) {
  return std::isfinite(e.value) && std::isfinite(centre.value) && e.feasible == centre.feasible &&
         e.regime == centre.regime;
}

}  // namespace

std::optional<FdGradient> fd_gradient(TrackedObjective& f, std::span<const double> u, const Evaluation& centre,
                                      double h) {
  const std::size_t n = u.size();
  FdGradient g{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0), true};
  const Evaluation& c = centre;
  std::vector<double> p(u.begin(), u.end());
  for (std::size_t i = 0; i < n; ++i) {
    const double forward = u[i] + h <= 1.0 ? h : -h;
    bool done = false;
    for (const double step : {forward, -forward}) {
      if (u[i] + step < 0.0 || u[i] + step > 1.0) continue;
      p[i] = u[i] + step;
      const std::optional<Evaluation> e = f.evaluate(p);
      p[i] = u[i];
      if (!e) return std::nullopt;
      if (!usable(*e, c)) continue;
      g.value[i] = (e->value - c.value) / step;
      g.violation[i] = (e->violation - c.violation) / step;
      done = true;
      break;
    }
    if (!done) g.complete = false;
  }
  return g;
}

}  // namespace vibromap
