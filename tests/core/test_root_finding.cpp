// The Illinois root finder (root_finding.hpp) on functions with known roots. Its promise: given
// g(a) <= 0 < g(b), it returns the right end x of a final bracket no wider than tol, so the root
// r satisfies r <= x <= r + tol and g(x) > 0 (the point just past a crossing an event needs),
// unless g hits exactly 0, which is returned as is.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "vibromap/core/integrate/root_finding.hpp"

using namespace vibromap;

namespace {

// Runs illinois on [a, b] and checks the promise against the exact root r.
RootResult expect_root_within(const std::function<double(double)>& g, double a, double b, double r, double tol) {
  const RootResult res = illinois(g, a, b, g(a), g(b), tol);
  EXPECT_GE(res.x, r) << "tol " << tol;          // the returned end is past the crossing ...
  EXPECT_LE(res.x - r, tol) << "tol " << tol;    // ... by no more than the bracket's width
  EXPECT_GE(g(res.x), 0.0) << "tol " << tol;     // and on the positive side (or exactly on 0)
  return res;
}

}  // namespace

TEST(RootFinding, SquareRootOfTwoToEveryTolerance) {
  auto g = [](double x) { return x * x - 2.0; };
  for (double tol : {1e-3, 1e-8, 1e-12, 4e-16}) expect_root_within(g, 1.0, 2.0, std::numbers::sqrt2, tol);
}

TEST(RootFinding, CosineCrossesAtHalfPi) {
  auto g = [](double x) { return -std::cos(x); };  // -1 at 0, +0.99 at 3
  expect_root_within(g, 0.0, 3.0, std::numbers::pi / 2, 1e-14);
  // A bracket with the root near its left end.
  expect_root_within(g, 1.5, 3.3, std::numbers::pi / 2, 1e-14);
}

TEST(RootFinding, MiddleRootOfACubicWithThreeRoots) {
  // -(x-1)(x-2)(x-3): -0.375 at 1.5, +0.357 at 2.7, root 2 between; the other two roots outside.
  auto g = [](double x) { return -(x - 1.0) * (x - 2.0) * (x - 3.0); };
  expect_root_within(g, 1.5, 2.7, 2.0, 1e-13);
}

TEST(RootFinding, IllinoisIsSuperlinearWhereBisectionIsNot) {
  // To 1e-12 from a bracket of width 1 bisection needs ceil(log2(1e12)) = 40 evaluations.
  // Illinois converges with order 1.442 (Dowell & Jarratt): from ~1e-1 to 1e-12 in some 8
  // evaluations on a smooth simple root; 20 leaves room and still excludes bisection.
  auto g = [](double x) { return x * x - 2.0; };
  const RootResult res = expect_root_within(g, 1.0, 2.0, std::numbers::sqrt2, 1e-12);
  EXPECT_LE(res.iterations, 20);
  EXPECT_GE(res.iterations, 1);
}

TEST(RootFinding, TripleRootIsSlowButStaysBracketed) {
  // (x - 1/3)^3: flat at the root, where regula falsi alone would stall at one end and the
  // Illinois halving only restores linear convergence: more evaluations than bisection's
  // ceil(log2(1e10)) = 34, and more than the default limit of 100 (then the bracket's right end
  // is returned unnarrowed; iterations == the limit tells), but it converges.
  const double r = 1.0 / 3.0;
  auto g = [r](double x) { return (x - r) * (x - r) * (x - r); };
  const RootResult res = illinois(g, 0.0, 1.0, g(0.0), g(1.0), 1e-10, 1000);
  EXPECT_GE(res.x, r);
  EXPECT_LE(res.x - r, 1e-10);
  EXPECT_GT(res.iterations, 34);
  EXPECT_LT(res.iterations, 1000);
}

TEST(RootFinding, ExactZeroIsReturnedAtOnce) {
  // The secant of a line through (0, -0.5) and (1, 0.5) lands on 0.5, where g is exactly 0.
  auto g = [](double x) { return x - 0.5; };
  const RootResult res = illinois(g, 0.0, 1.0, -0.5, 0.5, 1e-15);
  EXPECT_EQ(res.x, 0.5);
  EXPECT_EQ(res.iterations, 1);
}

TEST(RootFinding, RootAtTheLeftEndIsApproachedFromTheRight) {
  // g(a) = 0 is allowed (g(a) <= 0): the root is a itself and the result lies in (a, a + tol].
  auto g = [](double x) { return x; };
  const double tol = 1e-9;
  const RootResult res = illinois(g, 0.0, 1.0, 0.0, 1.0, tol);
  EXPECT_GT(res.x, 0.0);
  EXPECT_LE(res.x, tol);
}

TEST(RootFinding, BracketAlreadyNarrowerThanTolReturnsItsRightEnd) {
  auto g = [](double x) { return x - 1.0; };
  const RootResult res = illinois(g, 0.9999, 1.0001, g(0.9999), g(1.0001), 1e-3);
  EXPECT_EQ(res.x, 1.0001);
  EXPECT_EQ(res.iterations, 0);
}

TEST(RootFinding, IterationLimitStillReturnsAPointPastTheRoot) {
  // tol = 0 can never be met: the limit ends the search with the bracket kept.
  auto g = [](double x) { return x * x - 2.0; };
  const RootResult res = illinois(g, 1.0, 2.0, -1.0, 2.0, 0.0, 5);
  EXPECT_EQ(res.iterations, 5);
  EXPECT_GE(res.x, std::numbers::sqrt2);
  EXPECT_LT(res.x, 2.0);  // five steps narrowed it
  EXPECT_GT(g(res.x), 0.0);
}

TEST(RootFinding, JumpIsLocatedLikeARoot) {
  // A sign change without a zero (a step at 0.3): the bracket closes on the jump.
  auto g = [](double x) { return x < 0.3 ? -1.0 : 1.0; };
  expect_root_within(g, 0.0, 1.0, 0.3, 1e-12);
}
