#pragma once
// The solve function of the campaigns that follow initial states on MPI ranks (the point
// census, basins): one initial state followed to its attractor by the rank's CensusFollower, as
// a PixelResult (state_codec.hpp), and the census options those followers use.

#include "vibromap/campaigns/census/state_codec.hpp"
#include "vibromap/core/analysis/census/census.hpp"

namespace vibromap::detail {

// The outcome of following x0 on the rank's follower. An exception is the state's label
// (unresolved), never the run's.
// budget > 0: follow for that many periods (a round of the follow past analysis.max_periods);
// exact: at the scene's tolerance (CensusFollower::follow).
PixelResult follow_state(CensusFollower& follower, const Eigen::Vector4d& x0, long budget = 0, bool exact = false);

// The census options the followers of a campaign use: `census`, never deciding by recurrence.
// A state recurring on a non-periodic set a follower found earlier would be decided
// "non-periodic" at once; on the Table 2 point that set is a chaotic saddle, whose long
// transients mostly end on (3,3), and which states it captures would depend on what the rank
// followed before, so that two runs on the same ranks could disagree. Without it a state is
// non-periodic only when it has not settled after analysis.max_periods, as brute force
// decides, whatever its rank followed before; captures by periodic orbits stay (census.cpp).
CensusOptions follower_census(CensusOptions census);

}  // namespace vibromap::detail
