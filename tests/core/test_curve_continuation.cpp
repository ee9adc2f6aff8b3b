// Tests of curves in two parameters (core/analysis/continuation/curve_continuation.hpp) against closed forms
// and the one-parameter continuation: the grazing curve of a contact-free orbit against the
// linear response, the fold curve against the fold the branch locates at another force, and a
// level curve of k_con against plain solves.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "support/linear_response.hpp"
#include "vibromap/core/model/keys.hpp"
#include "vibromap/core/analysis/continuation/continuation.hpp"
#include "vibromap/core/analysis/continuation/curve_continuation.hpp"
#include "vibromap/core/analysis/continuation/orbit_extent.hpp"
#include "vibromap/core/analysis/point/shooting.hpp"
#include "support/paper_points.hpp"

namespace vibromap {
namespace {

using test::Linear;

using test::table2;  // tests/support/paper_points.hpp

// The points of base with one parameter (a key's name, Key::at) stepped; and with two.
PointAt path(const Parameters& base, const PointOptions& o, const char* name) {
  return [=](double x) {
    Parameters p = base;
    Key::at(name).set(p, x);
    return std::make_pair(p, o);
  };
}
PointAt2 plane(const Parameters& base, const PointOptions& o, const char* name, const char* name2) {
  return [=](double x, double y) {
    Parameters p = base;
    Key::at(name2).set(p, y);
    Key::at(name).set(p, x);
    return std::make_pair(p, o);
  };
}

const Bifurcation* first_of(const Branch& b, BifurcationType type) {
  for (const Bifurcation& x : b.bifurcations)
    if (x.type == type) return &x;
  return nullptr;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double worst_residual(const Curve& c) {
  double w = 0.0;
  for (const CurvePoint& q : c.points) w = std::max(w, q.residual);
  return w;
}

// a. The contact-free (1,1) orbit of Table 2 followed down in omega from 11 rad/s reaches
// contact at a grazing; its curve in (omega, F0) over F0 in [300, 700] N is the closed form's
// F0 |U1 - U2| = D (U the linear response per unit force) at every point to 1e-7.
TEST(CurveContinuation, TheGrazingCurveOfAContactFreeOrbitIsTheLinearClosedForm) {
  const auto t0 = std::chrono::steady_clock::now();
  const Parameters base = table2();
  const PointOptions options;
  Parameters start = base;
  start.omega = 11.0;
  ContinuationOptions co;
  co.tol = 1e-11;
  const Branch b = continue_orbit(path(base, options, "omega"), 11.0, 7.3, Linear(start).orbit(start), co);
  const Bifurcation* g = first_of(b, BifurcationType::grazing);
  ASSERT_NE(g, nullptr) << b.stop;
  CurveOptions o;
  o.base = co;
  const CurveBox box{11.0, 7.3, 300.0, 700.0, "forcing.omega", "forcing.F0"};
  const CurveSpec spec{CurveKind::grazing, LevelQuantity::k_con, 0.0, "grazing"};
  const Curve c = continue_curve(plane(base, options, "omega", "F0"), box, spec, 1, g->at.param, base.F0, g->at.y, o);
  ASSERT_GT(c.points.size(), 10u) << c.stop;
  double worst = 0.0, hi = -1e300;
  for (const CurvePoint& q : c.points) {
    Parameters p = base;
    p.omega = q.param;
    p.F0 = q.param2;
    const Eigen::Vector2cd Q = Linear(p).amplitudes(p);
    worst = std::max(worst, std::abs(std::abs(Q[1] - Q[0]) / p.D - 1.0));
    hi = std::max(hi, q.param2);
  }
  EXPECT_LT(worst, 1e-7);
  EXPECT_LE(worst_residual(c), o.condition_tol);
  // It crosses the box, ending exactly on its sides: F0 = 700 N one way, omega = 7.3 rad/s the other.
  EXPECT_EQ(hi, 700.0);
  EXPECT_EQ(c.points.front().param, 7.3);
  EXPECT_EQ(c.stop, "left the box at forcing.F0 = 700; left the box at forcing.omega = 7.3");
  std::printf("grazing curve: %zu points, omega %.6f .. %.6f, worst |F0 |U1 - U2| / D - 1| %.1e, worst residual "
              "%.1e, stop: %s; %.1f s\n",
              c.points.size(), c.points.front().param, c.points.back().param, worst, worst_residual(c), c.stop.c_str(),
              seconds_since(t0));
}

// a2. The grazings of Table 2's period-2 orbit (the branch doubled from the (1,1) one over omega
// in [7.23, 12] rad/s at F0 = 500 N, near 7.4636 and 7.5831 rad/s) are a further impact appearing
// on an orbit with one (clearance_min < 0 there: the old condition could not follow them). Each
// as a curve in (omega, F0) over [300, 700] N, checked at its ends and middle against orbits
// solved anew by shooting (Newton on P^2, independent of the curve's extended system): at the
// point the tracked approach touches to within the condition tolerance, and 0.5 N either side in
// F0 the orbit has 1 impact per cycle below and 2 above (measure_orbit, as `run` counts them),
// as the curve's summary says.
TEST(CurveContinuation, TheGrazingCurvesOfAFurtherImpactSeparateOneImpactFromTwo) {
  const auto t0 = std::chrono::steady_clock::now();
  const Parameters base = table2();
  const PointOptions options;
  const PointSummary s = solve_point(base, options);
  ContinuationOptions co;
  co.pd_depth = 1;
  co.tol = 1e-11;
  const std::vector<Branch> branches = continue_branches(path(base, options, "omega"), 7.23, 12.0, s.final_state, co);
  std::vector<const Bifurcation*> grazings;
  for (const Branch& b : branches)
    for (const Bifurcation& x : b.bifurcations)
      if (b.n == 2 && x.type == BifurcationType::grazing) grazings.push_back(&x);
  ASSERT_EQ(grazings.size(), 2u);
  CurveOptions o;
  o.base = co;
  const CurveBox box{7.23, 12.0, 300.0, 700.0, "forcing.omega", "forcing.F0"};
  const CurveSpec spec{CurveKind::grazing, LevelQuantity::k_con, 0.0, "grazing"};
  Parameters corner = base;  // the condition's length scale is the box corner's (curve_problem.cpp)
  corner.omega = 7.23;
  corner.F0 = 300.0;
  const double L = StateScale(Model(corner)).length();
  ShootingOptions so;
  so.n = 2;
  so.tol = 1e-12;
  IntegrationCounters counters;
  for (const Bifurcation* g : grazings) {
    EXPECT_LT(g->at.clearance_min, -1e-4) << g->at.param;  // the orbit has a contact already
    const Curve c = continue_curve(plane(base, options, "omega", "F0"), box, spec, 2, g->at.param, base.F0, g->at.y, o);
    ASSERT_GT(c.points.size(), 10u) << c.stop;
    EXPECT_EQ(c.stop, "left the box at forcing.F0 = 700; left the box at forcing.F0 = 300");
    EXPECT_EQ(c.grazing, "an impact appears on an orbit with 1 contact per cycle: 2 at higher forcing.F0, 1 at lower "
                         "forcing.F0");
    EXPECT_LE(worst_residual(c), o.condition_tol);
    for (const std::size_t i : {std::size_t{0}, c.points.size() / 2, c.points.size() - 1}) {
      const CurvePoint& q = c.points[i];
      Parameters p = base;
      p.omega = q.param;
      p.F0 = q.param2;
      const ShootingResult r = shoot(Model(p), options.integrator, Model::to_internal(q.y), so, counters);
      ASSERT_TRUE(r.converged) << r.message;
      const OrbitExtent x = orbit_extent(Model(p), options.integrator, r.y, 2, counters);
      const Approach* a = nearest_approach(x, q.phase);
      ASSERT_NE(a, nullptr);
      EXPECT_LE(std::abs(a->clearance) / L, o.condition_tol) << q.param << " " << q.param2;
      std::size_t impacts[2] = {0, 0};
      double side_clearance[2] = {0.0, 0.0};
      for (const int side : {0, 1}) {
        p.F0 = q.param2 + (side == 0 ? -0.5 : 0.5);
        const ShootingResult rs = shoot(Model(p), options.integrator, r.y, so, counters);
        ASSERT_TRUE(rs.converged) << rs.message;
        impacts[side] = measure_orbit(p, options, Model::to_physical(rs.y), 2).impacts.size();
        const OrbitExtent xs = orbit_extent(Model(p), options.integrator, rs.y, 2, counters);
        side_clearance[side] = nearest_approach(xs, q.phase)->clearance;
      }
      EXPECT_EQ(impacts[0], 1u) << q.param << " " << q.param2;
      EXPECT_EQ(impacts[1], 2u) << q.param << " " << q.param2;
      std::printf("period-2 grazing curve from omega %.4f, point %zu (omega %.8f, F0 %.4f): tracked clearance %.1e "
                  "of L; F0 -/+ 0.5 N: %zu / %zu impacts, clearance %+.2e / %+.2e m\n",
                  g->at.param, i, q.param, q.param2, a->clearance / L, impacts[0], impacts[1], side_clearance[0],
                  side_clearance[1]);
    }
    std::printf("period-2 grazing curve from omega %.4f: %zu points, worst residual %.1e\n", g->at.param,
                c.points.size(), worst_residual(c));
  }
  std::printf("period-2 grazing curves: %.1f s\n", seconds_since(t0));
}

// b. The fold of Table 2's (1,1) branch (omega 7.23 -> 8.3 at F0 = 500 N) followed in
// (omega, F0) over [400, 600] N ends on the box's sides exactly; there it agrees with the fold
// the one-parameter continuation locates on the branch at that force.
TEST(CurveContinuation, TheFoldCurveEndsOnTheFoldsOfTheBranchesAtItsEnds) {
  const auto t0 = std::chrono::steady_clock::now();
  const Parameters base = table2();
  const PointOptions options;
  const auto fold_at = [&](double F0) {
    Parameters p = base;
    p.F0 = F0;
    const PointSummary s = solve_point(p, options);
    ContinuationOptions co;
    co.max_points = 3000;
    return continue_orbit(path(p, options, "omega"), 7.23, 8.3, s.final_state, co);
  };
  const Branch b = fold_at(base.F0);
  const Bifurcation* f = first_of(b, BifurcationType::fold);
  ASSERT_NE(f, nullptr) << b.stop;
  CurveOptions o;
  const CurveBox box{7.23, 8.3, 400.0, 600.0, "forcing.omega", "forcing.F0"};
  const CurveSpec spec{CurveKind::fold, LevelQuantity::k_con, 0.0, "fold"};
  const Curve c = continue_curve(plane(base, options, "omega", "F0"), box, spec, 1, f->at.param, base.F0, f->at.y, o);
  ASSERT_GT(c.points.size(), 3u) << c.stop;
  EXPECT_LE(worst_residual(c), o.condition_tol);
  for (const CurvePoint* end : {&c.points.front(), &c.points.back()}) {
    if (end->param2 != 400.0 && end->param2 != 600.0) continue;
    const Branch e = fold_at(end->param2);
    const Bifurcation* fe = first_of(e, BifurcationType::fold);
    ASSERT_NE(fe, nullptr) << e.stop;
    EXPECT_NEAR(end->param, fe->at.param, 1e-9 * (8.3 - 7.23)) << "F0 = " << end->param2;  // locate_tol
    std::printf("fold curve at F0 = %.0f N: omega %.10f, the branch's fold %.10f (difference %.1e)\n", end->param2,
                end->param, fe->at.param, end->param - fe->at.param);
  }
  std::printf("fold curve: %zu points, F0 %.3f .. %.3f, worst residual %.1e, stop: %s; %.1f s\n", c.points.size(),
              c.points.front().param2, c.points.back().param2, worst_residual(c), c.stop.c_str(), seconds_since(t0));
}

// The period doubling of Table 1's (1,1) branch (omega 7.23 -> 6.3 at F0 = 500 N) followed in
// (omega, F0) over [450, 550] N: a multiplier at -1 at every point, and the curve's ends on the
// box's sides agree with the period doubling the branch locates at that force.
TEST(CurveContinuation, ThePeriodDoublingCurveEndsOnTheDoublingsOfTheBranches) {
  const auto t0 = std::chrono::steady_clock::now();
  const Parameters base;  // Table 1
  const PointOptions options;
  const auto pd_at = [&](double F0) {
    Parameters p = base;
    p.F0 = F0;
    const PointSummary s = solve_point(p, options);
    return continue_orbit(path(p, options, "omega"), 7.23, 6.3, s.final_state, ContinuationOptions{});
  };
  const Branch b = pd_at(base.F0);
  const Bifurcation* pd = first_of(b, BifurcationType::period_doubling);
  ASSERT_NE(pd, nullptr) << b.stop;
  CurveOptions o;
  const CurveBox box{7.23, 6.3, 450.0, 550.0, "forcing.omega", "forcing.F0"};
  const CurveSpec spec{CurveKind::period_doubling, LevelQuantity::k_con, 0.0, "period-doubling"};
  const Curve c = continue_curve(plane(base, options, "omega", "F0"), box, spec, 1, pd->at.param, base.F0, pd->at.y, o);
  ASSERT_GT(c.points.size(), 3u) << c.stop;
  EXPECT_LE(worst_residual(c), o.condition_tol);
  double nearest = 0.0;  // the worst over the points of the multiplier nearest -1
  for (const CurvePoint& q : c.points) {
    double d = 1e300;
    for (const auto& mu : q.multipliers) d = std::min(d, std::abs(mu + 1.0));
    nearest = std::max(nearest, d);
  }
  EXPECT_LT(nearest, 1e-9 * (12.0 - 3.0));  // locate_tol
  int ends = 0;
  for (const CurvePoint* end : {&c.points.front(), &c.points.back()}) {
    if (end->param2 != 450.0 && end->param2 != 550.0) continue;
    ++ends;
    const Branch e = pd_at(end->param2);
    const Bifurcation* pe = first_of(e, BifurcationType::period_doubling);
    ASSERT_NE(pe, nullptr) << e.stop;
    EXPECT_NEAR(end->param, pe->at.param, 1e-9 * (7.23 - 6.3)) << "F0 = " << end->param2;  // locate_tol
    std::printf("period-doubling curve at F0 = %.0f N: omega %.10f, the branch's %.10f (difference %.1e)\n",
                end->param2, end->param, pe->at.param, end->param - pe->at.param);
  }
  EXPECT_GE(ends, 1) << c.stop;
  std::printf("period-doubling curve: %zu points, worst residual %.1e, multipliers within %.1e of -1, stop: %s; "
              "%.1f s\n",
              c.points.size(), worst_residual(c), nearest, c.stop.c_str(), seconds_since(t0));
}

// The last Neimark-Sacker point of Table 2's branch over omega in [3, 12] rad/s (near 6.4015)
// followed in (omega, F0) over [450, 550] N: a complex pair on the unit circle at every point,
// and the curve's end at 450 N is a Neimark-Sacker point the branch locates at that force.
TEST(CurveContinuation, TheNeimarkSackerCurveKeepsAComplexPairOnTheUnitCircle) {
  const auto t0 = std::chrono::steady_clock::now();
  const Parameters base = table2();
  const PointOptions options;
  const auto branch_at = [&](double F0) {
    Parameters p = base;
    p.F0 = F0;
    p.omega = 3.0;
    const PointSummary s = solve_point(p, options);
    return continue_orbit(path(p, options, "omega"), 3.0, 12.0, s.final_state, ContinuationOptions{});
  };
  const Branch b = branch_at(base.F0);
  const Bifurcation* ns = nullptr;
  for (const Bifurcation& x : b.bifurcations)
    if (x.type == BifurcationType::neimark_sacker) ns = &x;
  ASSERT_NE(ns, nullptr) << b.stop;
  ASSERT_NEAR(ns->at.param, 6.4015, 1e-3);
  CurveOptions o;
  const CurveBox box{3.0, 12.0, 450.0, 550.0, "forcing.omega", "forcing.F0"};
  const CurveSpec spec{CurveKind::neimark_sacker, LevelQuantity::k_con, 0.0, "neimark-sacker"};
  const Curve c = continue_curve(plane(base, options, "omega", "F0"), box, spec, 1, ns->at.param, base.F0, ns->at.y, o);
  ASSERT_GT(c.points.size(), 3u) << c.stop;
  EXPECT_EQ(c.stop, "left the box at forcing.F0 = 550; left the box at forcing.F0 = 450");
  double worst = 0.0;  // over the points: the complex pair's distance from the unit circle
  for (const CurvePoint& q : c.points) {
    double d = 1e300;
    for (const auto& mu : q.multipliers)
      if (std::abs(mu.imag()) > 1e-6) d = std::min(d, std::abs(std::abs(mu) - 1.0));
    worst = std::max(worst, d);
  }
  EXPECT_LT(worst, 1e-9);
  const CurvePoint& end = c.points.front();
  ASSERT_EQ(end.param2, 450.0);
  const Branch e = branch_at(450.0);
  double nearest = 1e300;
  for (const Bifurcation& x : e.bifurcations)
    if (x.type == BifurcationType::neimark_sacker) nearest = std::min(nearest, std::abs(x.at.param - end.param));
  EXPECT_LT(nearest, 1e-9 * (12.0 - 3.0));  // locate_tol
  std::printf("neimark-sacker curve: %zu points, abs(mu) - 1 within %.1e, its end at 450 N %.1e rad/s from the "
              "branch's; %.1f s\n",
              c.points.size(), worst, nearest, seconds_since(t0));
}

// c. The level k_con = 10 of the (1,1) family at omega = 7.23 found along E2 in [1e6, 2e6] Pa
// and continued in E1 over [1e9, 1e11] Pa: at three of its points a plain solve from rest
// gives k_con = 10.
TEST(CurveContinuation, TheLevelCurveOfKconHasKconTenInPlainSolves) {
  const auto t0 = std::chrono::steady_clock::now();
  const Parameters base = table2();
  const PointOptions options;
  const PointSummary s = solve_point(base, options);
  ASSERT_EQ(s.regime.label(), "(1,1)");
  const Branch b = continue_orbit(path(base, options, "E2"), 1e6, 2e6, s.final_state, ContinuationOptions{});
  std::string error;
  const CurveSpec spec = *parse_curve_spec("level:k_con=10", error);
  const CurveBox box{1e6, 2e6, 1e9, 1e11, "contact.E2", "contact.E1"};
  const PointAt2 at = plane(base, options, "E2", "E1");
  std::optional<CurvePoint> start;
  double va = 0.0;
  for (std::size_t i = 0; i < b.points.size() && !start; ++i) {
    const auto [p, o] = at(b.points[i].param, base.E1);
    const double v = measure_orbit(p, o, b.points[i].y, 1).k_con;
    if (i > 0 && (va - 10.0) * (v - 10.0) < 0.0)
      start = locate_level(at, box, spec, 1, base.E1, b.points[i - 1], va, b.points[i], v, CurveOptions{});
    va = v;
  }
  ASSERT_TRUE(start.has_value()) << b.stop;
  const Curve c = continue_curve(at, box, spec, 1, start->param, base.E1, start->y, CurveOptions{});
  ASSERT_GT(c.points.size(), 5u) << c.stop;
  EXPECT_LE(worst_residual(c), 1e-9);
  double worst = 0.0;
  for (const std::size_t i : {std::size_t{0}, c.points.size() / 2, c.points.size() - 1}) {
    const auto [p, o] = at(c.points[i].param, c.points[i].param2);
    const PointSummary r = solve_point(p, o);
    EXPECT_EQ(r.regime.label(), "(1,1)") << "E2 " << p.E2 << " E1 " << p.E1;
    worst = std::max(worst, std::abs(r.k_con - 10.0));
    EXPECT_NEAR(r.k_con, 10.0, 1e-6) << "E2 " << p.E2 << " E1 " << p.E1;
  }
  std::printf("level curve: %zu points, E2 %.6g .. %.6g, E1 %.6g .. %.6g, worst residual %.1e, plain solves |k_con - "
              "10| <= %.1e; stop: %s; %.1f s\n",
              c.points.size(), c.points.front().param, c.points.back().param, c.points.front().param2,
              c.points.back().param2, worst_residual(c), worst, c.stop.c_str(), seconds_since(t0));
}

TEST(CurveContinuation, KindsAreParsedAndBadOnesSaid) {
  std::string error;
  EXPECT_EQ(parse_curve_spec("period-doubling", error)->kind, CurveKind::period_doubling);
  const auto level = parse_curve_spec("level:z_ratio=0.01", error);
  ASSERT_TRUE(level.has_value());
  EXPECT_EQ(level->quantity, LevelQuantity::z_ratio);
  EXPECT_EQ(level->value, 0.01);
  EXPECT_FALSE(parse_curve_spec("cusp", error).has_value());
  EXPECT_EQ(error, "cusp: not one of fold, period-doubling, neimark-sacker, grazing, level:NAME=VALUE");
  EXPECT_FALSE(parse_curve_spec("level:x1=3", error).has_value());
  EXPECT_EQ(error, "level:x1=3: NAME x1 is not one of k_con, T_con, F_max, z_ratio");
  EXPECT_FALSE(parse_curve_spec("level:k_con=ten", error).has_value());
  EXPECT_EQ(error, "level:k_con=ten: VALUE must be a finite number");
}

}  // namespace
}  // namespace vibromap
