#pragma once
// Internal to the sweep campaign: a cell's CellResult as bytes, field by field (layout 1).

#include "vibromap/core/quantities.hpp"
#include "vibromap/parallel/campaign.hpp"

namespace vibromap::detail {

class CellCodec : public ResultCodec<CellResult> {
 public:
  std::uint32_t version() const override { return 1; }
  void encode(const CellResult& c, ByteWriter& out) const override;
  CellResult decode(ByteReader& in) const override;
};

}  // namespace vibromap::detail
