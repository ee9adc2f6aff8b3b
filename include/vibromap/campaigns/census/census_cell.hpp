#pragma once
// A census map's cell (a sweep whose scene has [census]): every attractor of the cell's point
// with its basin fraction (core/analysis/census/census.hpp), as the map keeps it (CellResult). Serial:
// the sweep shares the cells out over the ranks, not a cell's initial states.

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/core/quantities.hpp"

namespace vibromap {

// The census of the point (p, options) summarized as a map cell; seeds as census_point's. Throws
// what census_point throws (the sweep makes it the cell's status).
CellResult solve_census_cell(const Parameters& p, const PointOptions& options, const CensusOptions& census,
                             const std::vector<Eigen::Vector4d>& seeds = {});

// The seed states a cell gives the next one on its line: the first period-start state of each
// periodic attractor it lists.
std::vector<Eigen::Vector4d> seed_states(const CellResult& cell);

// The cells of a census map with census.seed_from_neighbour, on one rank. Lines are runs of
// `line` consecutive cells (the map's last axis, the fastest); a line's first cell has no seeds
// and every other cell is seeded by the cell before it. The farm hands out whole lines
// (FarmOptions::block), which a rank computes in order, so the cell before is the one it just
// computed; when it is not (a resumed map whose line was cut by the stop), the line's cells
// before are computed again from the line's start, their results dropped. So a cell's seeds,
// and the map, do not depend on the rank count or on a stop and resume. Not thread-safe.
class SeededCells {
 public:
  using Solve = std::function<CellResult(std::uint64_t flat, const std::vector<Eigen::Vector4d>& seeds)>;
  SeededCells(std::uint64_t line, Solve solve);
  CellResult operator()(std::uint64_t flat);
  std::uint64_t recomputed() const { return recomputed_; }  // cells computed again for their seeds

 private:
  CellResult step(std::uint64_t flat);
  std::uint64_t line_;
  Solve solve_;
  std::optional<std::uint64_t> last_;  // the cell computed last
  std::vector<Eigen::Vector4d> seeds_;  // its seed states
  std::uint64_t recomputed_ = 0;
};

}  // namespace vibromap
