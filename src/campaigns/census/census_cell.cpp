// A census map's cell: see census_cell.hpp.

#include "vibromap/campaigns/census/census_cell.hpp"

namespace vibromap {

CellResult solve_census_cell(const Parameters& p, const PointOptions& options, const CensusOptions& census) {
  return summarize(census_point(p, options, census));
}

}  // namespace vibromap
