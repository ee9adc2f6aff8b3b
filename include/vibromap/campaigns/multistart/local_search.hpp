#pragma once
// One local optimisation from one seed: the entry point that runs any Algorithm on any
// Objective within a Box (the five NLopt algorithms through the NLopt adaptor, the paper's
// gradient projection from the core), and one start of the multistart campaign with the
// physics objective. NLopt is a dependency of this campaign only: the core does not see it.

#include <span>

#include "vibromap/core/optimise/local_optimiser.hpp"
#include "vibromap/core/optimise/multistart.hpp"

namespace vibromap {

// Runs `algorithm` from the physical point `seed` (clamped into the box). Throws
// std::invalid_argument when the options or the seed do not fit the box; never throws for
// what the objective does.
LocalResult minimise(Objective& f, const Box& box, std::span<const double> seed, Algorithm algorithm,
                     const LocalOptions& options);

// Runs one start with the physics objective (point_objective.hpp) on the scene's point and
// options; `census` is the scene's [census], used when o.min_soft_fraction > 0.
LocalResult run_start(const Parameters& base, const PointOptions& options, const OptimiseOptions& o,
                      const Seed& seed, Algorithm algorithm, const CensusOptions& census = {});

}  // namespace vibromap
