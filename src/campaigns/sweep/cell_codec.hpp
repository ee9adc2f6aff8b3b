#pragma once
// Internal to the sweep campaign: a cell's CellResult as bytes, field by field; the census, when
// the sweep has one, after the cell's fields: its four fractions, the count of attractors and
// each attractor as the followed states carry theirs (campaigns/census/attractor_codec.hpp).

#include "vibromap/core/quantities.hpp"
#include "vibromap/parallel/campaign.hpp"

namespace vibromap::detail {

// The most attractors a cell's census lists (CensusOptions::max_attractors' upper bound).
constexpr std::uint32_t kMaxCensusAttractors = 64;

class CellCodec : public ResultCodec<CellResult> {
 public:
  // census: the sweep keeps each cell's census.
  explicit CellCodec(bool census = false) : census_(census) {}
  // 6, 7: the soft flag; 8: the census's attractors by AttractorCodec.
  std::uint32_t version() const override { return census_ ? 8 : 6; }
  void encode(const CellResult& c, ByteWriter& out) const override;
  CellResult decode(ByteReader& in) const override;

 private:
  bool census_;
};

}  // namespace vibromap::detail
