#pragma once
// The seam between the optimisers and what they optimise (in the spirit of Ceres'
// CostFunction: one pure virtual call), and the bookkeeping every local algorithm shares.
//
// An Objective maps physical parameters x to an Evaluation: the value to minimise and a
// constraint residual `violation` (<= 0 feasible, > 0 how far from feasible). The physics
// objective (point_objective.hpp) solves the point and keeps a regime; tests use analytic ones.
//
// TrackedObjective wraps an Objective for one local optimisation: it works in the Box's
// scaled variables u, caches every evaluation (the same u is never solved twice: NLopt asks
// for the objective and then the constraint at one point, and a finite-difference stencil
// often revisits points), records each distinct evaluation in order, enforces the start's
// budget (max_evaluations solves, max_time), and keeps the best *feasible* evaluation itself.
// The best point of a start is always taken from here, never from what an algorithm returns.

#include <chrono>
#include <cstddef>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vibromap/core/analysis/point/regime.hpp"
#include "vibromap/core/optimise/box.hpp"
#include "vibromap/core/optimise/optimise_options.hpp"

namespace vibromap {

// The violation of an evaluation that failed (an exception, a non-finite value, a solver
// failure): the largest an objective reports. The scale of the physics objective is
// documented in point_objective.hpp.
inline constexpr double kFailedViolation = 3.0;

struct Evaluation {
  double value = std::numeric_limits<double>::quiet_NaN();  // the objective as minimised (sense * quantity)
  double violation = kFailedViolation;  // constraint residual: <= 0 feasible, > 0 infeasible (finite, O(1))
  bool feasible = false;                // violation <= 0 and value finite
  Regime regime{RegimeKind::failed, 0, 0};  // physics objectives: the point's regime
  int stable = -1;                      // 1 stable, 0 unstable, -1 unknown (physics objectives)
  std::vector<double> measures;         // extra numbers, named by Objective::measure_names()
  std::string message;                  // why the point is infeasible or failed, when it is
};

class Objective {
 public:
  virtual ~Objective() = default;
  // The evaluation at physical parameters x (the Box's variables, in order). May throw:
  // TrackedObjective turns an exception into a failed, infeasible evaluation.
  virtual Evaluation evaluate(std::span<const double> x) = 0;
  // Names of Evaluation::measures, in order (written to the output file).
  virtual std::vector<std::string> measure_names() const { return {}; }
};

// One distinct evaluation of a start, in the order it was made.
struct EvaluationRecord {
  std::vector<double> x;   // physical parameters
  Evaluation result;
  double wall_s = 0.0;     // time of this evaluation, s
};

class TrackedObjective {
 public:
  TrackedObjective(Objective& f, Box box, const LocalOptions& options);

  // The evaluation at scaled u (clamped into the unit cube): from the cache when u was seen
  // before, else evaluated and recorded. nullopt when a new evaluation is needed but the
  // budget is spent.
  std::optional<Evaluation> evaluate(std::span<const double> u);

  bool exhausted() const;            // no new evaluation is allowed any more
  std::string budget_reason() const; // "MAXEVAL_REACHED" or "MAXTIME_REACHED" (exhausted only)

  const std::vector<EvaluationRecord>& history() const { return history_; }
  std::optional<std::size_t> best() const { return best_; }  // best feasible record (lowest value; first on ties)
  long calls() const { return calls_; }            // evaluate() calls that returned an evaluation
  long cache_hits() const { return cache_hits_; }
  double elapsed() const;                          // s since construction
  const Box& box() const { return box_; }
  const LocalOptions& options() const { return options_; }

 private:
  Evaluation checked_evaluation(std::span<const double> x);

  Objective& f_;
  Box box_;
  LocalOptions options_;
  std::vector<EvaluationRecord> history_;
  std::map<std::vector<double>, std::size_t> cache_;  // clamped u -> index into history_
  std::optional<std::size_t> best_;
  long calls_ = 0, cache_hits_ = 0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// Finite-difference gradients in the scaled variables at u (whose evaluation is `centre`).
// Forward differences with step h; backward where u_i + h > 1 or where the forward point is
// not usable. A stencil point is usable when its value is finite and it has the centre's
// feasibility and regime (across a regime boundary the value and the violation jump, and a
// difference quotient would be meaningless); a component with neither neighbour usable is 0
// and marks the gradient incomplete.
struct FdGradient {
  std::vector<double> value;      // d value / d u_i
  std::vector<double> violation;  // d violation / d u_i
  bool complete = true;           // every component from a usable neighbour
};

// nullopt when the budget ran out during the stencil.
std::optional<FdGradient> fd_gradient(TrackedObjective& f, std::span<const double> u, const Evaluation& centre,
                                      double h);

}  // namespace vibromap
