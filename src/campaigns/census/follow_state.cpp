// One initial state followed on a rank: see follow_state.hpp.

#include "vibromap/campaigns/census/follow_state.hpp"

namespace vibromap::detail {

PixelResult follow_state(CensusFollower& follower, const Eigen::Vector4d& x0, long budget, bool exact) {
  PixelResult r;
  try {
    const CensusFollower::Outcome out = budget > 0 ? follower.follow(x0, budget, exact) : follower.follow(x0);
    r.label = out.label;
    r.periods = out.periods;
    r.early = out.early;
    r.budget = out.budget;
    r.failed = out.failed;
    r.end_state = out.end_state;
    if (out.label >= 0) r.attractor = follower.attractor(static_cast<std::size_t>(out.label));
  } catch (const std::exception&) {
    r.label = kUnresolvedLabel;
    r.failed = true;
  }
  return r;
}

CensusOptions follower_census(CensusOptions census) {
  census.decide_by_recurrence = false;
  return census;
}

}  // namespace vibromap::detail
