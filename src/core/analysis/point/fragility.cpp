#include "vibromap/core/analysis/point/fragility.hpp"

#include <algorithm>

#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/analysis/point/shooting.hpp"

namespace vibromap {
namespace {

// Two orbits are one attractor when their cycles agree to this scaled distance (or 1000 Newton
// tolerances, when larger): Newton solutions from different starts differ by about
// tol / (1 - |mu|), distinct orbits by far more (two (1,1) orbits 3 % apart in T_con at one point of the paper's box).
constexpr double kSameOrbit = 1e-6;

// The rows of the 4 x 4 Hadamard matrix over 2: orthogonal unit vectors each moving every
// coordinate by half the perturbation's size.
constexpr double kHadamard[4][4] = {
    {0.5, 0.5, 0.5, 0.5}, {0.5, -0.5, 0.5, -0.5}, {0.5, 0.5, -0.5, -0.5}, {0.5, -0.5, -0.5, 0.5}};

// The cycle of a settled answer: Newton for its period at the scene's tolerance from the state
// its motion ended in (a period start), then the cycle's other n - 1 period starts. The ended
// state itself starts the cycle when Newton fails or finds no stable orbit (a brute-force
// answer is then within steady_tol / (1 - |mu|) of its orbit).
std::vector<Eigen::Vector4d> settled_cycle(const Model& model, const PointOptions& o, const PointSummary& s,
                                           Fragility& f) {
  const int n = s.regime.n;
  State y = Model::to_internal(s.final_state);
  if (o.integrator.method != Method::rk4) {
    ShootingOptions so;
    so.n = n;
    so.tol = newton_tolerance(o);
    so.max_iterations = o.analysis.newton_max_iterations;
    const ShootingResult sh = shoot(model, o.integrator, y, so, f.counters);
    if (sh.converged && sh.stable()) y = sh.y;
  }
  const auto integ = make_integrator(model, o.integrator);
  State u = y;
  integ->reset(u);
  Observer none;
  std::vector<Eigen::Vector4d> cycle{Model::to_physical(u)};
  for (int i = 1; i < n && integ->advance_period(u, none) == IntegrationStatus::ok; ++i)
    cycle.push_back(Model::to_physical(u));
  f.counters += integ->counters();
  f.periods += integ->period();
  return cycle;
}

SteadyEnd end_of(const Model& model, const PointOptions& o, const Eigen::Vector4d& x0, const PointSummary& s,
                 Fragility& f) {
  SteadyEnd e;
  e.x0 = x0;
  e.regime = s.regime;
  e.settled = s.status == SolveStatus::ok && s.regime.n > 0;
  if (e.settled) e.strobe = settled_cycle(model, o, s, f);
  return e;
}

}  // namespace

Eigen::Vector4d fragility_direction(int i) {
  const double sign = i % 2 == 0 ? 1.0 : -1.0;
  const double* h = kHadamard[(i / 2) % 4];
  return sign * Eigen::Vector4d(h[0], h[1], h[2], h[3]);
}

double same_orbit_tolerance(const PointOptions& options) {
  return std::max(kSameOrbit, 1000.0 * newton_tolerance(options));
}

bool same_cycle(const Model& model, const std::vector<State>& a, const std::vector<State>& b, double tol) {
  const std::size_t n = a.size();
  if (n == 0 || b.size() != n) return false;
  const StateScale scale(model);
  for (std::size_t shift = 0; shift < n; ++shift) {
    bool all = true;
    for (std::size_t k = 0; k < n && all; ++k) all = scale.distance(a[(k + shift) % n], b[k]) <= tol;
    if (all) return true;
  }
  return false;
}

bool same_steady_state(const Parameters& p, const PointOptions& options, const SteadyEnd& a, const SteadyEnd& b) {
  if (a.settled != b.settled) return false;
  if (!a.settled) return a.regime.kind == b.regime.kind;
  if (a.regime.n != b.regime.n) return false;
  std::vector<State> x, y;
  for (const Eigen::Vector4d& s : a.strobe) x.push_back(Model::to_internal(s));
  for (const Eigen::Vector4d& s : b.strobe) y.push_back(Model::to_internal(s));
  return same_cycle(Model(p), x, y, same_orbit_tolerance(options));
}

Fragility assess_fragility(const Parameters& p, const PointOptions& options, const PointSummary& own) {
  Fragility f;
  f.size = options.analysis.fragility;
  if (f.size <= 0.0 || own.status == SolveStatus::invalid_input) return f;
  const Model model(p);
  const StateScale scale(model);
  const Eigen::Array4d unit = scale.unit();
  // Each perturbed state is followed as the point's own is, and only that: no trajectory, no
  // fragility of its own.
  PointOptions follow = options;
  follow.analysis.fragility = 0.0;
  follow.analysis.trajectory_periods = 0;
  const Eigen::Vector4d x0 = p.initial_state();
  f.own = end_of(model, options, x0, own, f);
  for (int i = 0; i < options.analysis.fragility_states; ++i) {
    Parameters q = p;
    q.initial = x0 + (f.size * fragility_direction(i).array() * unit).matrix();
    const PointSummary s = solve_point(q, follow);
    f.periods += s.periods;
    f.counters += s.counters;
    SteadyEnd e = end_of(model, options, *q.initial, s, f);
    e.same = same_steady_state(p, options, f.own, e);
    f.fragile = f.fragile || !e.same;
    f.perturbed.push_back(std::move(e));
  }
  return f;
}

}  // namespace vibromap
