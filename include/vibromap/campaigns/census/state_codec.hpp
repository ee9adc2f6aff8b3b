#pragma once
// The campaigns that follow initial states on MPI ranks (the point census, basins): one state's
// result (an initial state of a point census, a pixel of a basins plane) and its bytes (layout
// 4): the label, the periods integrated, whether it was decided early or followed to the
// budget's end, whether its integration failed, the state where it was left (the follow past
// the budget goes on from it) and, for a label >= 0, the attractor as the follower holds it
// (attractor_codec.hpp; its count, fraction, from_rest and escape figures are the sink's to
// fill in). Made on the ranks by follow_state (follow_state.hpp).

#include <cstdint>

#include "vibromap/campaigns/census/attractor_codec.hpp"
#include "vibromap/core/analysis/census/census.hpp"
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

class PixelCodec : public ResultCodec<PixelResult> {
 public:
  std::uint32_t version() const override { return 4; }  // 4: the attractor by AttractorCodec
  void encode(const PixelResult& r, ByteWriter& out) const override;
  PixelResult decode(ByteReader& in) const override;
};

}  // namespace vibromap::detail
