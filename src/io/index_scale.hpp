#pragma once
// Internal to io: an index coordinate 0..n-1 made a dimension scale, so that every dimension of
// every dataset carries a named scale (netCDF-4 readers, xarray with either engine, need one on
// each axis: h5netcdf refuses a dataset with an unlabeled axis).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vibromap/io/hdf5_file.hpp"

namespace vibromap::detail {

// The dataset `name` in `g`: 0..n-1 as int32, a dimension scale named `name`, with `long_name`.
inline Dataset write_index_scale(Group& g, const std::string& name, std::size_t n, const std::string& long_name) {
  std::vector<int> index(n);
  for (std::size_t i = 0; i < n; ++i) index[i] = static_cast<int>(i);
  Dataset d = g.write_dataset(name, std::span<const int>(index));
  d.make_dimension_scale(name);
  d.set_attribute("long_name", long_name);
  return d;
}

// The same for a small categorical dimension: 0..n-1 as int8 with CF flag_values 0..n-1 and
// `flag_meanings` (n space-separated words) naming each index.
inline Dataset write_flag_scale(Group& g, const std::string& name, const std::vector<std::string>& meanings,
                                const std::string& long_name) {
  std::vector<std::int8_t> index(meanings.size());
  std::string words;
  for (std::size_t i = 0; i < meanings.size(); ++i) {
    index[i] = static_cast<std::int8_t>(i);
    words.append(i ? " " : "").append(meanings[i]);
  }
  Dataset d = g.write_dataset(name, std::span<const std::int8_t>(index));
  d.make_dimension_scale(name);
  d.set_attribute("long_name", long_name);
  d.set_attribute("flag_values", std::span<const std::int8_t>(index));
  d.set_attribute("flag_meanings", words);
  return d;
}

}  // namespace vibromap::detail
