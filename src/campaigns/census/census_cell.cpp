// A census map's cell: see census_cell.hpp.

#include "vibromap/campaigns/census/census_cell.hpp"

#include <chrono>

namespace vibromap {

CellResult solve_census_cell(const Parameters& p, const PointOptions& options, const CensusOptions& census) {
  const auto start = std::chrono::steady_clock::now();
  CellResult c = summarize(census_point(p, options, census));
  c.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();  // the shocks' too
  return c;
}

}  // namespace vibromap
