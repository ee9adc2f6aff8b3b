#pragma once
// Internal to the sweep campaign: a cell's CellResult as bytes, field by field (layout 2: the
// census, when the sweep has one, after the fields of layout 1).

#include "vibromap/core/quantities.hpp"
#include "vibromap/parallel/campaign.hpp"

namespace vibromap::detail {

// The most attractors a cell's census lists (CensusOptions::max_attractors' upper bound).
constexpr std::uint32_t kMaxCensusAttractors = 64;

class CellCodec : public ResultCodec<CellResult> {
 public:
  // census: the sweep keeps each cell's census.
  explicit CellCodec(bool census = false) : census_(census) {}
  std::uint32_t version() const override { return census_ ? 7 : 6; }  // 6, 7: the soft flag
  void encode(const CellResult& c, ByteWriter& out) const override;
  CellResult decode(ByteReader& in) const override;

 private:
  bool census_;
};

}  // namespace vibromap::detail
