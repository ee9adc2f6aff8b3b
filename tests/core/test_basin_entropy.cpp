// Basin entropy (Daza et al. 2016) and the uncertainty exponent on constructed label planes whose
// answers are known by hand, and the entropy of a census's basin fractions.

#include "vibromap/core/analysis/census/basin_entropy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "vibromap/core/analysis/census/basins_plane.hpp"
#include "vibromap/core/analysis/census/census.hpp"

namespace vibromap {
namespace {

constexpr double kExact = 1e-14;  // sums of a few dozen logarithms: rounding only

// An n0 x n1 plane, pixel j n0 + i labelled label(i, j).
std::vector<std::int32_t> plane(int n0, int n1, const std::function<int(int, int)>& label) {
  std::vector<std::int32_t> out(static_cast<std::size_t>(n0) * static_cast<std::size_t>(n1));
  for (int j = 0; j < n1; ++j)
    for (int i = 0; i < n0; ++i) out[static_cast<std::size_t>(j * n0 + i)] = label(i, j);
  return out;
}

double entropy2(double p) { return -(p * std::log(p) + (1.0 - p) * std::log(1.0 - p)); }

// A straight boundary: columns 0..21 attractor 0, 22..39 attractor 1, on 40 x 40 pixels in 5 x 5
// boxes (8 x 8 = 64 boxes). Only the box column of pixels 20..24 straddles it: 8 boundary boxes,
// each with 2 of 5 columns on one side, S_i = H(2/5) = 0.6730 < ln 2. S_bb = H(2/5),
// S_b = 8 H(2/5) / 64. f(eps) = 2 eps / 40 exactly (the eps columns on each side), at eps = 1, 2,
// 4, 8 (<= 40 / 4): all below 0.5, so alpha = 1 and d = 1 to rounding.
TEST(BasinEntropy, StraightBoundaryIsSmooth) {
  const auto labels = plane(40, 40, [](int i, int) { return i < 22 ? 0 : 1; });
  const BasinEntropySummary s = basin_entropy(labels, 40, 40, {.box = 5});
  ASSERT_TRUE(s.ok) << s.message;
  EXPECT_EQ(s.boxes, 64);
  EXPECT_EQ(s.boundary_boxes, 8);
  EXPECT_EQ(s.outcomes, 2);
  EXPECT_NEAR(s.S_bb, entropy2(0.4), kExact);
  EXPECT_NEAR(s.S_b, 8.0 * entropy2(0.4) / 64.0, kExact);
  EXPECT_LT(s.S_bb, std::log(2.0));
  EXPECT_EQ(s.verdict, BoundaryVerdict::not_shown);
  ASSERT_EQ(s.eps, (std::vector<int>{1, 2, 4, 8}));
  for (std::size_t k = 0; k < s.eps.size(); ++k) EXPECT_NEAR(s.uncertain[k], 2.0 * s.eps[k] / 40.0, kExact);
  EXPECT_EQ(s.fit_scales, 4);
  EXPECT_EQ(s.eps_lo, 1);
  EXPECT_EQ(s.eps_hi, 8);
  EXPECT_NEAR(s.alpha, 1.0, 1e-12);
  EXPECT_NEAR(s.dimension, 1.0, 1e-12);
  EXPECT_LT(s.fit_rms, 1e-12);
  EXPECT_TRUE(s.alpha_note.empty());
}

// A tilted straight boundary (i > 10 + 0.37 j on 256 x 256) still has dimension 1: alpha within
// 0.05 of 1 (0.98 here, over eps = 1..32: the uncertain band is cut short where the line meets
// the plane's edges, which lowers f a little at large eps).
TEST(BasinEntropy, TiltedStraightBoundaryHasDimensionOne) {
  const auto labels = plane(256, 256, [](int i, int j) { return i > 10 + 0.37 * j ? 1 : 0; });
  const BasinEntropySummary s = basin_entropy(labels, 256, 256, {});
  ASSERT_TRUE(s.ok) << s.message;
  EXPECT_GE(s.fit_scales, 3);
  EXPECT_NEAR(s.alpha, 1.0, 0.05);
  EXPECT_LT(s.S_bb, std::log(2.0));
}

// A disc of radius 12 about (20, 20) on 40 x 40 in 5 x 5 boxes: a smooth boundary, so S_bb stays
// below ln 2 whatever the boxes it cuts, and S_b is S_bb times the share of boundary boxes.
TEST(BasinEntropy, DiscBoundaryIsSmooth) {
  const auto labels = plane(40, 40, [](int i, int j) { return (i - 20) * (i - 20) + (j - 20) * (j - 20) < 144 ? 1 : 0; });
  const BasinEntropySummary s = basin_entropy(labels, 40, 40, {.box = 5});
  ASSERT_TRUE(s.ok) << s.message;
  EXPECT_GT(s.boundary_boxes, 0);
  EXPECT_LT(s.S_bb, std::log(2.0));
  EXPECT_NEAR(s.S_b, s.S_bb * static_cast<double>(s.boundary_boxes) / 64.0, kExact);
  EXPECT_EQ(s.verdict, BoundaryVerdict::not_shown);
}

// A checkerboard at pixel scale: every 4 x 4 box holds 8 and 8, S_i = ln 2 in all 100 boxes.
// Every pixel's neighbour differs: f(eps) = 1 at every scale, saturated, so no exponent.
TEST(BasinEntropy, CheckerboardGivesLogTwo) {
  const auto labels = plane(40, 40, [](int i, int j) { return (i + j) % 2; });
  const BasinEntropySummary s = basin_entropy(labels, 40, 40, {.box = 4});
  ASSERT_TRUE(s.ok) << s.message;
  EXPECT_EQ(s.boxes, 100);
  EXPECT_EQ(s.boundary_boxes, 100);
  EXPECT_NEAR(s.S_b, std::log(2.0), kExact);
  EXPECT_NEAR(s.S_bb, std::log(2.0), kExact);
  for (const double f : s.uncertain) EXPECT_EQ(f, 1.0);
  EXPECT_TRUE(std::isnan(s.alpha));
  EXPECT_NE(s.alpha_note.find("0 of the 4 scales"), std::string::npos) << s.alpha_note;
}

// m = 3 outcomes at pixel scale ((i + j) mod 3) in 6 x 6 boxes: 12 pixels of each in every box,
// S_i = ln 3, the maximum for 3 outcomes; S_bb > ln 2, so the log 2 test says fractal.
TEST(BasinEntropy, ThreeOutcomePatternGivesLogThree) {
  const auto labels = plane(36, 36, [](int i, int j) { return (i + j) % 3; });
  const BasinEntropySummary s = basin_entropy(labels, 36, 36, {.box = 6});
  ASSERT_TRUE(s.ok) << s.message;
  EXPECT_EQ(s.boxes, 36);
  EXPECT_NEAR(s.S_b, std::log(3.0), kExact);
  EXPECT_NEAR(s.S_bb, std::log(3.0), kExact);
  EXPECT_EQ(s.verdict, BoundaryVerdict::fractal);
}

// Unresolved (-1) and unlisted (-2) are outcomes of their own: with attractor 0 they make three
// outcomes in 6 x 6 boxes, ln 3 as above.
TEST(BasinEntropy, UnresolvedAndUnlistedAreOutcomes) {
  const auto labels = plane(36, 36, [](int i, int j) { return (i + j) % 3 - 2; });
  const BasinEntropySummary s = basin_entropy(labels, 36, 36, {.box = 6});
  ASSERT_TRUE(s.ok) << s.message;
  EXPECT_EQ(s.outcomes, 3);
  EXPECT_NEAR(s.S_b, std::log(3.0), kExact);
}

// Overlap (-3) and not-computed (-4) pixels are excluded: a plane of attractor 0 with those
// pixels scattered through it is one outcome, entropy 0, and no pixel is uncertain.
TEST(BasinEntropy, OverlapAndNotComputedAreExcluded) {
  const auto labels = plane(40, 40, [](int i, int j) { return (i * 7 + j * 3) % 5 == 0 ? -3 : (i + j) % 11 == 0 ? -4 : 0; });
  const BasinEntropySummary s = basin_entropy(labels, 40, 40, {.box = 5});
  ASSERT_TRUE(s.ok) << s.message;
  EXPECT_EQ(s.outcomes, 1);
  EXPECT_EQ(s.boxes, 64);
  EXPECT_EQ(s.S_b, 0.0);
  for (const double f : s.uncertain) EXPECT_EQ(f, 0.0);
}

TEST(BasinEntropy, SingleAttractorGivesZero) {
  const auto labels = plane(30, 20, [](int, int) { return 2; });
  const BasinEntropySummary s = basin_entropy(labels, 30, 20, {});
  ASSERT_TRUE(s.ok) << s.message;
  EXPECT_EQ(s.boxes, 24);  // 6 x 4 boxes of 5 x 5
  EXPECT_EQ(s.S_b, 0.0);
  EXPECT_EQ(s.S_bb, 0.0);
  EXPECT_EQ(s.boundary_boxes, 0);
  EXPECT_EQ(s.verdict, BoundaryVerdict::no_boundary);
  EXPECT_TRUE(std::isnan(s.alpha));
  EXPECT_EQ(s.alpha_note, "the plane holds one outcome: no boundary");
}

// The last N mod box columns and rows are in no box: a boundary there changes no box.
TEST(BasinEntropy, PartialBoxesAreLeftOut) {
  const auto labels = plane(23, 22, [](int i, int) { return i < 21 ? 0 : 1; });
  const BasinEntropySummary s = basin_entropy(labels, 23, 22, {.box = 5});
  ASSERT_TRUE(s.ok) << s.message;
  EXPECT_EQ(s.boxes, 16);
  EXPECT_EQ(s.boundary_boxes, 0);
}

TEST(BasinEntropy, RefusesBadInputAsData) {
  const auto labels = plane(4, 4, [](int, int) { return 0; });
  EXPECT_FALSE(basin_entropy(labels, 4, 4, {.box = 0}).ok);
  const BasinEntropySummary big = basin_entropy(labels, 4, 4, {.box = 5});
  EXPECT_FALSE(big.ok);
  EXPECT_EQ(big.message, "the box (5 pixels) exceeds the plane's side (4)");
  EXPECT_FALSE(basin_entropy(labels, 4, 5, {}).ok);
}

TEST(BasinEntropy, FractionEntropyIsMinusSumFLogF) {
  EXPECT_NEAR(fraction_entropy(std::vector<double>{0.5, 0.25, 0.125, 0.125, 0.0}), 1.75 * std::log(2.0), kExact);
  EXPECT_EQ(fraction_entropy(std::vector<double>{1.0, 0.0}), 0.0);
}

// A hand census of K = 8 states: attractors found a (4 states), b (2), c (1), one unresolved;
// with max_attractors = 2, c is unlisted. Shares 1/2, 1/4, 1/8 unresolved, 1/8 unlisted:
// S = -(1/2 ln 1/2 + 1/4 ln 1/4 + 2/8 ln 1/8) = 1.75 ln 2.
TEST(BasinEntropy, CensusCellEntropyOfItsFractions) {
  CensusSummary s;
  s.K = 8;
  std::vector<Attractor> found(3);
  std::vector<int> labels{0, 0, 1, 0, kUnresolvedLabel, 2, 1, 0};
  list_attractors(s, found, labels, 2);
  EXPECT_EQ(s.unlisted, 1);
  EXPECT_EQ(s.unresolved, 1);
  EXPECT_NEAR(s.basin_entropy, 1.75 * std::log(2.0), kExact);
}

}  // namespace
}  // namespace vibromap
