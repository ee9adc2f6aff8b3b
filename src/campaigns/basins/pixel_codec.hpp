#pragma once
// Internal to the campaigns that follow initial states on MPI ranks (basins, the point census):
// one state's result and its bytes (layout 3): the label, the periods integrated, whether it
// was decided early or followed to the budget's end, whether its integration failed, the state
// where it was left (the follow past the budget goes on from it) and, for a label >= 0, the attractor's
// record (periodic, regime, T_con, k_con, F_max, z_ratio, z_max, v_in, impulse, hertz_valid,
// max_floquet, stable, soft, transient, the stroboscopic states).

#include <cstdint>

#include "vibromap/core/analysis/census.hpp"
#include "vibromap/parallel/campaign.hpp"

namespace vibromap::detail {

struct PixelResult {
  std::int32_t label = kUnresolvedLabel;  // >= 0: `attractor` holds the record; else a census label or kOverlapLabel
  Attractor attractor;
  std::int64_t periods = 0;               // forcing periods integrated
  bool early = false;                     // decided by capture or recurrence
  bool budget = false;                    // followed to the end of analysis.max_periods undecided
  bool failed = false;                    // the integration failed
  Eigen::Vector4d end_state = Eigen::Vector4d::Zero();  // physical state where it was left
};

// The outcome of following x0 on the rank's follower. An exception is the state's label
// (unresolved), never the run's.
// budget > 0: follow for that many periods (a round of the follow past analysis.max_periods);
// exact: at the scene's tolerance (CensusFollower::follow).
PixelResult follow_state(CensusFollower& follower, const Eigen::Vector4d& x0, long budget = 0, bool exact = false);

// The census options the followers of a campaign use: `census`, never deciding by recurrence.
// A state recurring on a non-periodic set a follower found earlier would be decided
// "non-periodic" at once; on the Table 2 point that set is a chaotic saddle, whose long
// transients mostly end on (3,3), and which states it captures would depend on what the rank
// followed before (measured on a 48x48 basins plane: 112 pixels non-periodic with capture, 9
// without; two 2-rank runs of 200x200 differed by 920 pixels). Without it a state is
// non-periodic only when it has not settled after analysis.max_periods, as brute force
// decides, whatever its rank followed before; captures by periodic orbits stay (census.cpp).
CensusOptions follower_census(CensusOptions census);

class PixelCodec : public ResultCodec<PixelResult> {
 public:
  std::uint32_t version() const override { return 3; }
  void encode(const PixelResult& r, ByteWriter& out) const override;
  PixelResult decode(ByteReader& in) const override;
};

}  // namespace vibromap::detail
