#pragma once
// Internal to vibromap::io: the CF flags of a regime-code dataset (optimise and basins files).

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vibromap/core/quantities.hpp"
#include "vibromap/io/hdf5_file.hpp"

namespace vibromap::detail {

// flag_values / flag_meanings of the map's regime codes (quantities.hpp), 0..8 in RegimeKind order.
inline void set_regime_flags(Dataset& d) {
  std::vector<std::int8_t> values;
  std::string meanings;
  for (int i = 0; i <= static_cast<int>(RegimeKind::failed); ++i) {
    const auto kind = static_cast<RegimeKind>(i);
    values.push_back(regime_code(kind));
    std::string name = to_string(kind);
    std::replace(name.begin(), name.end(), '-', '_');
    meanings.append(meanings.empty() ? "" : " ").append(name);
  }
  d.set_attribute("flag_values", std::span<const std::int8_t>(values));
  d.set_attribute("flag_meanings", meanings);
}

}  // namespace vibromap::detail
