#pragma once
// Internal to the basins campaign: one pixel's result and its bytes (layout 1): the label, the
// periods integrated, whether it was decided early and, for a label >= 0, the attractor's
// record (periodic, regime, T_con, k_con, F_max, z_ratio, z_max, v_in, impulse, hertz_valid,
// max_floquet, stable, soft, the stroboscopic states).

#include <cstdint>

#include "vibromap/core/analysis/census.hpp"
#include "vibromap/parallel/campaign.hpp"

namespace vibromap::detail {

struct PixelResult {
  std::int32_t label = kUnresolvedLabel;  // >= 0: `attractor` holds the record; else a census label or kOverlapLabel
  Attractor attractor;
  std::int64_t periods = 0;               // forcing periods integrated
  bool early = false;                     // decided by capture or recurrence
};

class PixelCodec : public ResultCodec<PixelResult> {
 public:
  std::uint32_t version() const override { return 1; }
  void encode(const PixelResult& r, ByteWriter& out) const override;
  PixelResult decode(ByteReader& in) const override;
};

}  // namespace vibromap::detail
