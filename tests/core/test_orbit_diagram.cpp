// Tests of the brute-force orbit diagram (core/analysis/continuation/orbit_diagram.hpp): after its transient
// each point keeps the states of the steady motion the point solver finds (a conservation-free,
// independent reference: shooting with Newton), and the state is carried from point to point.

#include <gtest/gtest.h>

#include <cmath>

#include "vibromap/core/analysis/continuation/orbit_diagram.hpp"
#include "vibromap/core/analysis/point/shooting.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap {
namespace {

TEST(OrbitDiagram, KeptStatesAreTheSteadyOrbitOfThePointSolver) {
  const Parameters p;  // Table 1: a stable (1,1) from rest
  const PointOptions o;
  const PointSummary steady = solve_point(p, o);
  ASSERT_EQ(steady.status, SolveStatus::ok);
  ASSERT_EQ(steady.regime.label(), "(1,1)");
  OrbitDiagramOptions d;
  d.transient = 3000;  // xi = 0.01: about 18 periods per e-fold of the transient
  d.keep = 3;
  const std::vector<DiagramStep> steps = orbit_diagram({{p, o}}, p.initial_state(), d);
  ASSERT_EQ(steps.size(), 1u);
  ASSERT_EQ(steps[0].status, SolveStatus::ok);
  ASSERT_EQ(steps[0].strobe.size(), 3u);
  const StateScale scale{Model(p)};
  for (const Eigen::Vector4d& x : steps[0].strobe)
    EXPECT_LT(scale.distance(Model::to_internal(x), Model::to_internal(steady.final_state)), 1e-7);
}

TEST(OrbitDiagram, TheStateIsCarriedFromPointToPoint) {
  // The same point twice: the second step starts where the first ended, so with no transient the
  // two steps together are one run of 2 keep periods (to the integrator's tolerance: the second
  // step starts its step-size control afresh; rtol 1e-10 on states of a few cm).
  const Parameters p;
  const PointOptions o;
  OrbitDiagramOptions d;
  d.transient = 0;
  d.keep = 5;
  const auto two = orbit_diagram({{p, o}, {p, o}}, p.initial_state(), d);
  d.keep = 10;
  const auto one = orbit_diagram({{p, o}}, p.initial_state(), d);
  ASSERT_EQ(two.size(), 2u);
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(two[0].strobe[static_cast<std::size_t>(k)], one[0].strobe[static_cast<std::size_t>(k)]);
    EXPECT_NEAR((two[1].strobe[static_cast<std::size_t>(k)] - one[0].strobe[static_cast<std::size_t>(5 + k)]).norm(),
                0.0, 1e-8);
  }
  EXPECT_FALSE(validate(OrbitDiagramOptions{}).size());
  OrbitDiagramOptions bad;
  bad.keep = 0;
  EXPECT_EQ(validate(bad), "keep must be in [1, 100000] states");
}

}  // namespace
}  // namespace vibromap
