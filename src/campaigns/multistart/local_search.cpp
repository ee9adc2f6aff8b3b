#include "vibromap/campaigns/multistart/local_search.hpp"

#include <chrono>
#include <stdexcept>

#include "vibromap/core/optimise/gradient_projection.hpp"
#include "nlopt_adaptor.hpp"
#include "vibromap/core/optimise/point_objective.hpp"

namespace vibromap {

LocalResult minimise(Objective& f, const Box& box, std::span<const double> seed, Algorithm algorithm,
                     const LocalOptions& options) {
  if (const std::string e = validate(options); !e.empty()) throw std::invalid_argument("minimise: " + e);
  if (seed.size() != box.size()) throw std::invalid_argument("minimise: the seed does not have the box's dimension");
  const auto t0 = std::chrono::steady_clock::now();
  TrackedObjective tracked(f, box, options);
  const std::vector<double> u0 = box.to_scaled(seed);
  tracked.evaluate(u0);  // the seed is the first evaluation whatever the algorithm does first
  const StopReason stop = algorithm == Algorithm::gradient_projection ? run_gradient_projection(tracked, u0)
                                                                      : run_nlopt(tracked, u0, algorithm);
  LocalResult r;
  r.evaluations = tracked.history();
  r.best = tracked.best();
  r.stop = stop.text;
  r.nlopt_code = stop.nlopt_code;
  r.calls = tracked.calls();
  r.cache_hits = tracked.cache_hits();
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

LocalResult run_start(const Parameters& base, const PointOptions& options, const OptimiseOptions& o,
                      const Seed& seed, Algorithm algorithm, const CensusOptions& census) {
  PointObjective f(base, options, o, census);
  return minimise(f, Box(o.variables), seed.x, algorithm, o.local);
}

}  // namespace vibromap
