#pragma once
// What one local optimisation from one seed reports (campaigns/multistart/local_search.hpp's
// minimise runs it: NLopt stays out of the core).
//
// Every algorithm works on a TrackedObjective (objective.hpp) in the scaled variables, so
// they share one cache, one budget and one rule for the answer: the best point of a start is
// the best *feasible* evaluation the tracker saw, whatever the algorithm returned. A start
// whose every evaluation is infeasible has no best point (best is empty), which is a result,
// not an error.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vibromap/core/optimise/box.hpp"
#include "vibromap/core/optimise/objective.hpp"
#include "vibromap/core/optimise/optimise_options.hpp"

namespace vibromap {

// Why a local algorithm stopped: NLopt's result name (nlopt_result_to_string: "XTOL_REACHED",
// "FTOL_REACHED", "MAXTIME_REACHED", "ROUNDOFF_LIMITED", "FAILURE", ...) or the same words
// for the budget this layer enforces ("MAXEVAL_REACHED", "MAXTIME_REACHED"; "MAXCALLS_REACHED"
// when an NLopt algorithm asks for more than 50 cached points per allowed solve), and the
// gradient projection's own: "XTOL_REACHED", "FTOL_REACHED", "GRADIENT_ZERO" (the projected
// gradient vanished: a stationary point on the box and the regime boundary),
// "INFEASIBLE_START" (the seed itself is infeasible: nothing to project from).
struct StopReason {
  std::string text;
  int nlopt_code = 0;  // NLopt's nlopt_result; 0 for the gradient projection
};

struct LocalResult {
  std::vector<EvaluationRecord> evaluations;  // distinct evaluations, in order (the first is the seed)
  std::optional<std::size_t> best;            // index of the best feasible evaluation; empty: none feasible
  std::string stop;                           // StopReason::text
  int nlopt_code = 0;                         // StopReason::nlopt_code
  long calls = 0;                             // objective calls by the algorithm, cache hits included
  long cache_hits = 0;                        // calls answered from the cache
  double wall_s = 0.0;                        // time of the start, s
};

}  // namespace vibromap
