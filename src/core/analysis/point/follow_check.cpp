#include "follow_check.hpp"

#include <algorithm>
#include <vector>

#include <Eigen/Core>

namespace vibromap::detail {

namespace {

constexpr int kCheckPeriods = 20;  // periods per round of the check that the transient heads for the orbit
constexpr int kCheckRounds = 6;    // rounds before an undecided check refuses the orbit
// Rounds in a row the transient must follow the orbit's linearisation: one round can be a
// transient passing by (on the demo plane, E1 = 2.55e9, E2 = 2.09e10 Pa: a 4x approach to
// (1,1) over 20 periods at 0.12 motion scales, then (3,3), as brute force finds).
constexpr int kFollowingRounds = 2;
// The check compares with the orbit's linearisation, which says nothing about offsets
// beyond the motion's scale: a transient passing the orbit from farther off is not taken as
// following it (with a large basin Newton also finds orbits the transient only passes by).
constexpr double kLinearOffset = 1.0;
// How closely a window of the check must follow the linearisation, as a fraction of its
// starting offset: loosely in kFollowingRounds rounds in a row, or closely in one window
// that also closes in on the orbit. The transients passing by an orbit seen on the demo
// plane and an m2 x E2 plane followed it at 0.05 to 0.14 before they left it; those heading
// for it often follow far closer (Tables 1 and 2 at rtol 1e-4: 0.002 and 0.011 in the windows
// that accept).
constexpr double kLooseFollow = 0.25;
constexpr double kCloseFollow = 0.01;

// The check that the transient closes in on an orbit (transient_approaches) starts from the
// state brute force itself reaches (the transient runs at the scene's tolerance) and compares
// offsets with a 25 % margin: an offset of 1e-3..1 motion scales is integrated at this
// tolerance (or the scene's, when looser), which moves it by far less than the margin.
constexpr double kCheckRtol = 1e-6;
// A smaller offset is integrated at this fraction of it, down to the scene's tolerance: at
// 1e-6 a 20-period round errs by ~1e-5 motion scales, and an offset of 5e-8 to a stable (3,3)
// (demo plane, E1 = 2.55e9, E2 = 2.09e10 Pa) seemed to move away, so brute force took 800 periods.
constexpr double kCheckResolution = 1e-3;
double check_rtol(double scene_rtol, double offset) {
  return std::max(scene_rtol, std::min(kCheckRtol, kCheckResolution * offset));
}
IntegratorOptions check_options(IntegratorOptions budget) {
  budget.rtol = check_rtol(budget.rtol, 1.0);
  return budget;
}

// The n points y, P(y), ..., P^{n-1}(y) of a cycle (fewer when integration fails).
std::vector<State> cycle_points(const Model& model, const State& y, int n, const IntegratorOptions& budget,
                                IntegrationCounters& counters) {
  const auto integ = make_integrator(model, check_options(budget));
  std::vector<State> points{y};
  State u = y;
  integ->reset(u);
  Observer none;
  for (int i = 1; i < n && integ->advance_period(u, none) == IntegrationStatus::ok; ++i) points.push_back(u);
  counters += integ->counters();
  return points;
}

}  // namespace

bool transient_approaches(const Model& model, const State& transient_end, const ShootingResult& sh, int n, double tol,
                          const IntegratorOptions& budget, IntegrationCounters& counters) {
  const StateScale scale(model);
  if (scale.distance(transient_end, sh.y) <= tol) return true;
  const long spent = counters.steps + counters.rejected;
  const std::vector<State> cycle = cycle_points(model, sh.y, n, budget, counters);
  IntegratorOptions rest = budget;  // the step budget less what the cycle took
  rest.max_steps = std::max(0L, budget.max_steps - (counters.steps + counters.rejected - spent));
  if (static_cast<int>(cycle.size()) != n) return false;
  int phase = 0;
  for (int i = 1; i < n; ++i)
    if (scale.distance(transient_end, cycle[static_cast<std::size_t>(i)]) <
        scale.distance(transient_end, cycle[static_cast<std::size_t>(phase)]))
      phase = i;
  const auto integ = make_integrator(model, check_options(rest));
  State u = transient_end;
  integ->reset(u);
  Observer none;
  bool ok = true;
  for (int i = 0; i < (n - phase) % n && ok; ++i) ok = integ->advance_period(u, none) == IntegrationStatus::ok;
  const int cycles = std::max(1, kCheckPeriods / n);
  Eigen::Matrix4d power = Eigen::Matrix4d::Identity();
  for (int i = 0; i < cycles; ++i) power = sh.monodromy * power;
  // The offsets at the last cycles + 1 cycle ends (a ring): the window that ends at each
  // cycle end is compared with the linearisation as it comes, not only at the rounds' ends.
  std::vector<State> offsets(static_cast<std::size_t>(cycles) + 1);
  const auto at = [&](int c) -> State& { return offsets[static_cast<std::size_t>(c % (cycles + 1))]; };
  at(0) = u - sh.y;
  bool accepted = scale.size(at(0)) <= tol, refused = false;  // on the orbit, as at the transient's end
  int following = 0;  // rounds in a row that followed the linearisation
  for (int c = 1; c <= kCheckRounds * cycles && ok && !accepted && !refused; ++c) {
    if ((c - 1) % cycles == 0) integ->set_rtol(check_rtol(budget.rtol, scale.size(at(c - 1))));
    for (int i = 0; i < n && ok; ++i) ok = integ->advance_period(u, none) == IntegrationStatus::ok;
    if (!ok) break;
    at(c) = u - sh.y;
    const double size1 = scale.size(at(c));
    if (size1 <= tol) {  // on the orbit
      accepted = true;
      break;
    }
    if (c < cycles) continue;
    const State& delta0 = at(c - cycles);
    const double size0 = scale.size(delta0);
    const double deviation = scale.size(at(c) - power * delta0);
    // A window the linearisation predicts closely (to Newton's tolerance on the orbit beyond
    // the 1 %), closing in: one is enough.
    accepted = size0 <= kLinearOffset && size1 < size0 && deviation <= kCloseFollow * size0 + tol;
    if (accepted || c % cycles != 0) continue;
    following = size0 <= kLinearOffset && deviation <= kLooseFollow * size0 + kShorterPeriodFactor * tol ? following + 1 : 0;
    accepted = following >= kFollowingRounds;
    refused = size1 > size0;
  }
  counters += integ->counters();
  return ok && accepted;
}

}  // namespace vibromap::detail
