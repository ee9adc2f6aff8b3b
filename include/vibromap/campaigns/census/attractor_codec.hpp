#pragma once
// One attractor of a census (core/analysis/census/census.hpp's Attractor) as bytes, every field (layout
// 1): periodic, the regime (kind, n, k), T_con, k_con, F_max, z_ratio, z_max, v_in, impulse,
// max_floquet, fraction, fraction_stderr, escape_rate, hertz_valid, stable, count, from_rest,
// soft, transient, escape_exposure, escapes, the stroboscopic states and (layout 2) the minimal
// critical shock. The one attractor
// layout of the campaigns' messages: a followed state's (state_codec.hpp, the point census and
// basins) and a census map cell's (the sweep's cell codec) both carry their attractors so.

#include <cstdint>

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/parallel/campaign.hpp"

namespace vibromap::detail {

class AttractorCodec : public ResultCodec<Attractor> {
 public:
  std::uint32_t version() const override { return 2; }
  void encode(const Attractor& a, ByteWriter& out) const override;
  // Throws WireError on truncated input, an unknown regime kind or too many stroboscopic states.
  Attractor decode(ByteReader& in) const override;
};

}  // namespace vibromap::detail
