// SeededCells (campaigns/census/census_cell.hpp): a line's first cell gets no seeds, every other
// cell the seed states of the cell before it, whatever order and gaps the cells are asked in (a
// rank given whole lines, or a resumed map's cut line): the results equal those of computing every
// line in order from its start.

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <vector>

#include "vibromap/campaigns/census/census_cell.hpp"

namespace vibromap {
namespace {

// A cell whose one periodic attractor's first period-start state is (flat, sum of the seeds' first
// coordinates + 1, 0, 0): its seeds show in its result, and its result in the next cell's seeds.
CellResult fake_cell(std::uint64_t flat, const std::vector<Eigen::Vector4d>& seeds) {
  double sum = 0.0;
  for (const Eigen::Vector4d& s : seeds) sum += s[1];
  Attractor a;
  a.periodic = true;
  a.strobe = {Eigen::Vector4d(static_cast<double>(flat), sum + 1.0, 0.0, 0.0)};
  Attractor chaotic;  // gives no seed
  chaotic.periodic = false;
  CellResult c;
  c.census = {a, chaotic};
  return c;
}

double chain(const CellResult& c) { return c.census.front().strobe.front()[1]; }

TEST(SeededCells, EachCellIsSeededByTheCellBeforeItOnItsLineWhateverTheOrder) {
  constexpr std::uint64_t line = 4;
  SeededCells in_order(line, fake_cell);
  std::map<std::uint64_t, double> reference;
  for (std::uint64_t flat = 0; flat < 12; ++flat) reference[flat] = chain(in_order(flat));
  EXPECT_EQ(in_order.recomputed(), 0u);
  // Along a line the chain counts the cells from the line's start: 1, 2, 3, 4.
  for (std::uint64_t flat = 0; flat < 12; ++flat) EXPECT_EQ(reference[flat], static_cast<double>(flat % line + 1));

  SeededCells jumping(line, fake_cell);
  for (const std::uint64_t flat : {6u, 7u, 0u, 11u, 9u, 1u, 4u, 5u})
    EXPECT_EQ(chain(jumping(flat)), reference[flat]) << "cell " << flat;
  // 6 computes 4, 5 again; 7 none; 0 none; 11: 8, 9, 10; 9: 8; 1: 0; 4 and 5 none.
  EXPECT_EQ(jumping.recomputed(), 7u);
}

TEST(SeededCells, SeedStatesAreTheFirstPeriodStateOfEachPeriodicAttractor) {
  CellResult c = fake_cell(3, {});
  Attractor empty;  // periodic without states (failed): no seed
  c.census.push_back(empty);
  const std::vector<Eigen::Vector4d> seeds = seed_states(c);
  ASSERT_EQ(seeds.size(), 1u);
  EXPECT_EQ(seeds[0], Eigen::Vector4d(3.0, 1.0, 0.0, 0.0));
}

}  // namespace
}  // namespace vibromap
