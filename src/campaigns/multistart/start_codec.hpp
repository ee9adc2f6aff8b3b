#pragma once
// Internal to the multistart campaign: one start's StartRecord as bytes (layout 1): the start's
// index and rank, every evaluation (parameters, value, feasibility, regime, stability, measures,
// message, time), the best evaluation, the stop reason and the counters.

#include <vector>

#include "vibromap/core/optimise/multistart.hpp"
#include "vibromap/parallel/campaign.hpp"

namespace vibromap::detail {

class StartCodec : public ResultCodec<StartRecord> {
 public:
  explicit StartCodec(const std::vector<StartSpec>& plan) : plan_(plan) {}
  std::uint32_t version() const override { return 1; }
  void encode(const StartRecord& s, ByteWriter& out) const override;
  StartRecord decode(ByteReader& in) const override;  // the spec comes from the plan

 private:
  const std::vector<StartSpec>& plan_;
};

}  // namespace vibromap::detail
