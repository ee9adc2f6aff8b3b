// Families of attractors across constructed maps with known families: crossing families, a
// family that changes its label, one born mid-line, one that meets itself in a plane.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "vibromap/core/analysis/census/families.hpp"

namespace vibromap {
namespace {

constexpr double kDistance = 0.15;  // the matching threshold of these maps, motion scales

FamilyNode orbit(Regime r, std::vector<Eigen::Vector4d> points, double fraction = 0.5, bool soft = false) {
  FamilyNode n;
  n.regime = r;
  n.points = std::move(points);
  n.fraction = fraction;
  n.soft = soft;
  return n;
}

FamilyNode p11(double x, double y = 0.0, double fraction = 0.5) {
  return orbit({RegimeKind::periodic, 1, 1}, {Eigen::Vector4d(x, y, 0.0, 0.0)}, fraction);
}

// Labels a map given cell by cell (flat order): each node's family id and flags.
struct Labelled {
  std::vector<std::vector<std::int32_t>> ids;
  std::vector<std::vector<std::int8_t>> flags;
  std::vector<FamilyRecord> families;
};

Labelled label(std::vector<std::size_t> shape, const std::vector<std::vector<FamilyNode>>& cells,
               const std::vector<bool>& done = {}) {
  std::map<std::uint64_t, std::vector<std::int64_t>> labels;
  Labelled out;
  out.flags.resize(cells.size());
  FamilyLabeller labeller(std::move(shape), kDistance,
                          [&](std::uint64_t c, std::span<const std::int64_t> l, std::span<const std::int8_t> f) {
                            labels[c].assign(l.begin(), l.end());
                            out.flags[c].assign(f.begin(), f.end());
                          });
  for (std::size_t c = 0; c < cells.size(); ++c) labeller.add(c, cells[c], done.empty() || done[c]);
  labeller.finish();
  for (std::size_t c = 0; c < cells.size(); ++c) {
    out.ids.emplace_back();
    for (const std::int64_t l : labels.at(c)) out.ids.back().push_back(labeller.id(l));
  }
  out.families = labeller.families();
  return out;
}

TEST(Families, HausdorffDistanceIgnoresTheCyclicShiftAndSeesAPeriodDoubling) {
  const Eigen::Vector4d a(0.0, 0.0, 0.0, 0.0), b(0.3, 0.0, 0.0, 0.0), c(0.0, 0.0, 0.4, 0.0);
  const FamilyNode p3 = orbit({RegimeKind::periodic, 3, 3}, {a, b, c});
  const FamilyNode shifted = orbit({RegimeKind::periodic, 3, 3}, {b, c, a + Eigen::Vector4d(0.01, 0, 0, 0)});
  EXPECT_NEAR(family_distance(p3, shifted), 0.01, 1e-15);
  // A (2,2) born from a (1,1) by period doubling: its two states straddle the (1,1)'s.
  const FamilyNode p1 = p11(0.5);
  const FamilyNode p2 = orbit({RegimeKind::periodic, 2, 2}, {{0.48, 0, 0, 0}, {0.53, 0, 0, 0}});
  EXPECT_NEAR(family_distance(p1, p2), 0.03, 1e-12);
  // Non-periodic sets: by regime kind alone; never with an orbit.
  FamilyNode chaos;
  chaos.periodic = false;
  chaos.regime = {RegimeKind::non_periodic, 0, 0};
  FamilyNode chaos2 = chaos;
  EXPECT_EQ(family_distance(chaos, chaos2), 0.0);
  chaos2.regime.kind = RegimeKind::chatter;
  EXPECT_TRUE(std::isinf(family_distance(chaos, chaos2)));
  EXPECT_TRUE(std::isinf(family_distance(chaos, p1)));
}

TEST(Families, GreedyMatchingIsOneToOneByIncreasingDistance) {
  // b0 is nearest to both a0 (0.05) and a1 (0.02): a1 takes it, a0 falls back on b1 (0.1).
  const std::vector<FamilyNode> a = {p11(0.0), p11(0.07)};
  const std::vector<FamilyNode> b = {p11(0.05), p11(-0.1)};
  const auto m = match_families(a, b, kDistance);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0], (std::pair<int, int>{1, 0}));
  EXPECT_EQ(m[1], (std::pair<int, int>{0, 1}));
  EXPECT_TRUE(match_families(a, b, 0.04).size() == 1u);  // only a1-b0 is below 0.04
}

TEST(Families, CrossingFamiliesKeepTheirIdsWhileTheirIndicesSwap) {
  // Two (1,1) orbits whose x1 cross between cells 4 and 5 (0.3 apart in x2 there), their basin
  // fractions crossing too, so that the census lists them in the other order after the crossing.
  std::vector<std::vector<FamilyNode>> cells;
  for (int i = 0; i < 10; ++i) {
    FamilyNode a = p11(0.1 * i, 0.0, 0.9 - 0.08 * i), b = p11(0.9 - 0.1 * i, 0.3, 0.18 + 0.08 * i);
    if (a.fraction >= b.fraction) cells.push_back({a, b});
    else cells.push_back({b, a});
  }
  const Labelled l = label({10}, cells);
  ASSERT_EQ(l.families.size(), 2u);
  for (int i = 0; i < 10; ++i) {
    const bool swapped = i >= 5;
    EXPECT_EQ(l.ids[i][swapped ? 1 : 0], 0) << "cell " << i;  // family 0: x1 = 0.1 i
    EXPECT_EQ(l.ids[i][swapped ? 0 : 1], 1) << "cell " << i;
  }
  EXPECT_EQ(l.families[0].cells, 10);
  EXPECT_EQ(l.families[0].edge_cells, 0);
  EXPECT_EQ(l.families[1].label_changes, 0);
  EXPECT_NEAR(l.families[0].fraction_min, 0.18, 1e-12);
  EXPECT_NEAR(l.families[0].fraction_max, 0.9, 1e-12);
}

TEST(Families, AFamilyChangesItsLabelAtAGrazing) {
  // One orbit moving steadily; from cell 4 on it no longer touches: (1,1) becomes no-contact.
  std::vector<std::vector<FamilyNode>> cells;
  for (int i = 0; i < 8; ++i) {
    const Regime r = i < 4 ? Regime{RegimeKind::periodic, 1, 1} : Regime{RegimeKind::no_contact, 1, 0};
    cells.push_back({orbit(r, {Eigen::Vector4d(0.05 * i, 0, 0, 0)}, 1.0, i < 4)});
  }
  const Labelled l = label({8}, cells);
  ASSERT_EQ(l.families.size(), 1u);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(l.ids[i][0], 0);
  EXPECT_EQ(l.families[0].label_changes, 1);
  EXPECT_EQ(l.families[0].soft_cells, 4);
  ASSERT_EQ(l.families[0].regimes.size(), 2u);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(l.flags[i][0], (i == 3 || i == 4) ? kFamilyLabelChange : 0) << "cell " << i;
}

TEST(Families, AFamilyBornMidLineHasItsEdgeWhereItIsBorn) {
  // Cells 0..9: one orbit throughout; a second from cell 5 on (far from the first); cell 7 not
  // computed (it matches nothing and is nobody's edge).
  std::vector<std::vector<FamilyNode>> cells;
  std::vector<bool> done;
  for (int i = 0; i < 10; ++i) {
    cells.push_back({p11(0.01 * i, 0.0, 0.7)});
    if (i >= 5) cells.back().push_back(p11(1.0 + 0.01 * i, 0.0, 0.3));
    done.push_back(i != 7);
  }
  const Labelled l = label({10}, cells, done);
  // Cell 7 cuts the line: 0..6 and 8..9 are apart, for each orbit.
  ASSERT_EQ(l.families.size(), 4u);
  EXPECT_EQ(l.ids[0][0], 0);
  EXPECT_EQ(l.ids[6][0], 0);
  EXPECT_EQ(l.ids[5][1], 1);
  EXPECT_EQ(l.ids[6][1], 1);
  EXPECT_TRUE(l.ids[7].empty());
  EXPECT_EQ(l.ids[8][0], 2);
  EXPECT_EQ(l.ids[8][1], 3);
  EXPECT_EQ(l.families[1].first_cell, 5u);
  EXPECT_EQ(l.families[1].first_attractor, 1);
  EXPECT_EQ(l.families[1].edge_cells, 1);  // cell 5, whose neighbour 4 lacks it
  EXPECT_EQ(l.flags[5][1], kFamilyEdge);
  EXPECT_EQ(l.flags[4][0], 0);
  EXPECT_EQ(l.families[0].edge_cells, 0);
}

TEST(Families, AFamilyThatMeetsItselfInAPlaneHasOneIdFixedByItsFirstCell) {
  // A 3 x 4 plane (rows slowest): a U of one orbit whose arms start apart in raster order
  // (columns 0 and 3 of row 0) and join along row 2; the cells between hold a far orbit.
  //   U . . U
  //   U . . U
  //   U U U U
  std::vector<std::vector<FamilyNode>> cells;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c)
      cells.push_back({(r == 2 || c == 0 || c == 3) ? p11(0.02 * (r + c)) : p11(5.0 + 0.01 * c)});
  const Labelled l = label({3, 4}, cells);
  ASSERT_EQ(l.families.size(), 2u);
  for (int i = 0; i < 12; ++i) {
    const int r = i / 4, c = i % 4;
    EXPECT_EQ(l.ids[i][0], (r == 2 || c == 0 || c == 3) ? 0 : 1) << "cell " << i;
  }
  EXPECT_EQ(l.families[0].cells, 8);
  EXPECT_EQ(l.families[1].first_cell, 1u);
  // Every node of the U beside the far orbit's cells is at its edge: (0,0) (0,3) (1,0) (1,3) (2,1) (2,2).
  EXPECT_EQ(l.families[0].edge_cells, 6);
}

}  // namespace
}  // namespace vibromap
