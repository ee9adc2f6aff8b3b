// A census map's cell: see census_cell.hpp.

#include "vibromap/campaigns/census/census_cell.hpp"

#include <chrono>
#include <stdexcept>
#include <utility>

namespace vibromap {

CellResult solve_census_cell(const Parameters& p, const PointOptions& options, const CensusOptions& census,
                             const std::vector<Eigen::Vector4d>& seeds) {
  const auto start = std::chrono::steady_clock::now();
  CellResult c = summarize(census_point(p, options, census, seeds));
  c.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();  // the shocks' too
  return c;
}

std::vector<Eigen::Vector4d> seed_states(const CellResult& cell) {
  std::vector<Eigen::Vector4d> seeds;
  for (const Attractor& a : cell.census)
    if (a.periodic && !a.strobe.empty() && a.strobe.front().allFinite()) seeds.push_back(a.strobe.front());
  return seeds;
}

SeededCells::SeededCells(std::uint64_t line, Solve solve) : line_(line), solve_(std::move(solve)) {
  if (line_ == 0) throw std::invalid_argument("SeededCells: a line has at least one cell");
}

CellResult SeededCells::step(std::uint64_t flat) {
  static const std::vector<Eigen::Vector4d> none;
  CellResult c = solve_(flat, flat % line_ == 0 ? none : seeds_);
  seeds_ = seed_states(c);
  last_ = flat;
  return c;
}

CellResult SeededCells::operator()(std::uint64_t flat) {
  const std::uint64_t start = flat - flat % line_;
  std::uint64_t j = last_ && *last_ >= start && *last_ < flat ? *last_ + 1 : start;
  for (; j < flat; ++j, ++recomputed_) step(j);
  return step(flat);
}

}  // namespace vibromap
