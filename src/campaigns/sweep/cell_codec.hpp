#pragma once
// Internal to the sweep campaign: a cell's CellResult as bytes, field by field; the census, when
// the sweep has one, after the cell's fields: its four fractions, the count of attractors and
// each attractor as the followed states carry theirs (campaigns/census/attractor_codec.hpp).
//
// The quantities travel in the order of the quantity table (core/quantities.hpp), so a quantity
// added there is on the wire, and in the layout's version, without a line here.

#include <cstdint>
#include <span>

#include "vibromap/core/quantities.hpp"
#include "vibromap/parallel/campaign.hpp"

namespace vibromap::detail {

// The most attractors a cell's census lists (CensusOptions::max_attractors' upper bound).
constexpr std::uint32_t kMaxCensusAttractors = 64;

// The layout version of a cell carrying `quantities` (in that order): 6, or 8 with a census, for
// the 15 quantities T_con to clipped_impacts these generations were set for (6, 7: the soft
// flag; 8: the census's attractors by AttractorCodec); for another list, a name, a kind or an
// order changed, another number (from a 32-bit fingerprint of the list, cell_codec.cpp).
std::uint32_t cell_layout_version(bool census, std::span<const Quantity> quantities);

class CellCodec : public ResultCodec<CellResult> {
 public:
  // census: the sweep keeps each cell's census.
  explicit CellCodec(bool census = false) : census_(census) {}
  // cell_layout_version over the quantity table: a quantity added there changes it.
  std::uint32_t version() const override;
  void encode(const CellResult& c, ByteWriter& out) const override;
  CellResult decode(ByteReader& in) const override;

 private:
  bool census_;
};

}  // namespace vibromap::detail
