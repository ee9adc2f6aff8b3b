#pragma once
// A census map's cell (a sweep whose scene has [census]): every attractor of the cell's point
// with its basin fraction (core/analysis/census/census.hpp), as the map keeps it (CellResult). Serial:
// the sweep shares the cells out over the ranks, not a cell's initial states.

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/core/quantities.hpp"

namespace vibromap {

// The census of the point (p, options) summarized as a map cell. Throws what census_point
// throws (the sweep makes it the cell's status).
CellResult solve_census_cell(const Parameters& p, const PointOptions& options, const CensusOptions& census);

}  // namespace vibromap
