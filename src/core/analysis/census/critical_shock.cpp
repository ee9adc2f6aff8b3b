// The minimal critical shock: see critical_shock.hpp.

#include "vibromap/core/analysis/census/critical_shock.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "attractor_set.hpp"
#include "vibromap/core/analysis/point/shooting.hpp"

namespace vibromap {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kScanRadii = 12;        // a ray is scanned at R 2^(-j/2), j = kScanRadii - 1 .. 0 (R/45 .. R)
constexpr double kFirstTurn = 0.5;    // the compass search's first angle, rad
constexpr std::uint64_t kDirectionSalt = 0x5eed5c0c;  // the directions' stream apart from the census's draws

// Counts a call of leads.
ShockVerdict call(const ShockLeads& leads, const Eigen::Vector4d& z, ShockSearch& counts) {
  const ShockVerdict v = leads(z);
  ++counts.follows;
  counts.unresolved += v == ShockVerdict::unresolved ? 1 : 0;
  return v;
}

// [r_in, r_out] narrowed to the relative tolerance: r_in never leads elsewhere, r_out does.
RayBoundary bisect(const ShockLeads& leads, const Eigen::Vector4d& u, RayBoundary b, const ShockOptions& o,
                   ShockSearch& counts) {
  while (b.r_out - b.r_in > o.tolerance * b.r_out) {
    const double mid = 0.5 * (b.r_in + b.r_out);
    (call(leads, mid * u, counts) == ShockVerdict::elsewhere ? b.r_out : b.r_in) = mid;
  }
  return b;
}

// The largest radius along u with the bodies not overlapping: r (u1 - u2) <= slack.
double overlap_limit(const Eigen::Vector4d& u, double slack) {
  const double rate = u[0] - u[1];
  return rate > 0.0 ? slack / rate : kInf;
}

// The boundary near `limit` along u (the compass search's evaluation): limit leads elsewhere,
// then radii below it at doubling steps until one does not, then bisection; nullopt when limit
// does not lead elsewhere.
std::optional<RayBoundary> boundary_below(const ShockLeads& leads, const Eigen::Vector4d& u, double limit,
                                          const ShockOptions& o, ShockSearch& counts) {
  if (limit <= 0.0 || call(leads, limit * u, counts) != ShockVerdict::elsewhere) return std::nullopt;
  RayBoundary b{0.0, limit};
  for (double step = 2.0 * o.tolerance * limit; b.r_out - step > 0.0; step *= 2.0) {
    const double r = b.r_out - step;
    if (call(leads, r * u, counts) != ShockVerdict::elsewhere) {
      b.r_in = r;
      break;
    }
    b.r_out = r;
  }
  return bisect(leads, u, b, o, counts);
}

// Uniform random directions on the unit sphere of the coordinates the shock moves (Gaussian
// components, Box-Muller); the two directions of a single coordinate.
std::vector<Eigen::Vector4d> random_directions(const ShockOptions& o) {
  std::vector<int> active;
  for (int i = 0; i < 4; ++i)
    if (o.on[static_cast<std::size_t>(i)]) active.push_back(i);
  std::vector<Eigen::Vector4d> out;
  if (active.size() == 1) {
    out.push_back(Eigen::Vector4d::Unit(active[0]));
    out.push_back(-Eigen::Vector4d::Unit(active[0]));
    return out;
  }
  census_detail::SplitMix64 draws(o.seed ^ kDirectionSalt);
  const auto gaussian = [&draws] {
    const double u1 = 1.0 - draws.uniform(), u2 = draws.uniform();  // u1 in (0, 1]
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  };
  while (static_cast<int>(out.size()) < o.directions) {
    Eigen::Vector4d u = Eigen::Vector4d::Zero();
    for (int i : active) u[i] = gaussian();
    if (u.norm() > 1e-12) out.push_back(u.normalized());
  }
  return out;
}

// An orthonormal basis of the directions tangent to the sphere at u within the moving
// coordinates (u lies among them): Gram-Schmidt on their unit vectors projected off u, the
// longest first; the one that falls to nothing is u's own.
std::vector<Eigen::Vector4d> tangent_basis(const Eigen::Vector4d& u, const std::array<bool, 4>& on) {
  std::vector<Eigen::Vector4d> candidates;
  for (int i = 0; i < 4; ++i)
    if (on[static_cast<std::size_t>(i)]) candidates.push_back(Eigen::Vector4d::Unit(i) - u[i] * u);
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Eigen::Vector4d& a, const Eigen::Vector4d& b) { return a.norm() > b.norm(); });
  std::vector<Eigen::Vector4d> basis;
  for (Eigen::Vector4d v : candidates) {
    for (const Eigen::Vector4d& b : basis) v -= v.dot(b) * b;
    if (v.norm() > 1e-6 && basis.size() + 1 < candidates.size()) basis.push_back(v.normalized());
  }
  return basis;
}

// Step 2: the compass search on the sphere from (u, r) (critical_shock.hpp).
void compass_search(const ShockLeads& leads, double slack, const ShockOptions& o, Eigen::Vector4d u, ShockSearch& s) {
  double r = s.size;
  for (double theta = kFirstTurn; theta >= o.tolerance && s.follows < o.max_follows;) {
    bool moved = false;
    for (const Eigen::Vector4d& b : tangent_basis(u, o.on)) {
      for (const double sign : {1.0, -1.0}) {
        const Eigen::Vector4d v = (std::cos(theta) * u + sign * std::sin(theta) * b).normalized();
        const double limit = std::min({r * (1.0 - o.tolerance), o.max_radius, overlap_limit(v, slack)});
        const std::optional<RayBoundary> found = boundary_below(leads, v, limit, o, s);
        if (found && found->r_out < r) {
          u = v;
          r = found->r_out;
          moved = true;
          break;
        }
      }
      if (moved) break;
    }
    if (!moved) theta *= 0.5;
  }
  s.size = r;
  s.z = r * u;
}

}  // namespace

ShockOptions shock_options(const CensusOptions& c) {
  ShockOptions o;
  o.on = c.shock_on;
  o.directions = c.shock_directions;
  o.tolerance = c.shock_tolerance;
  o.max_radius = c.shock_max_radius;
  o.optimise = c.shock_optimise;
  o.seed = c.seed;
  return o;
}

std::optional<RayBoundary> ray_boundary(const ShockLeads& leads, const Eigen::Vector4d& u, double limit,
                                        const ShockOptions& o, ShockSearch& counts) {
  std::vector<double> radii;  // the scan's radii below the limit, then the limit
  for (int j = kScanRadii - 1; j >= 0; --j)
    if (const double r = o.max_radius * std::exp2(-0.5 * j); r < limit) radii.push_back(r);
  radii.push_back(limit);
  double r_in = 0.0;
  for (const double r : radii) {
    if (call(leads, r * u, counts) == ShockVerdict::elsewhere) return bisect(leads, u, {r_in, r}, o, counts);
    r_in = r;
  }
  return std::nullopt;
}

ShockSearch search_shock(const ShockLeads& leads, double overlap_slack, const ShockOptions& o, double below) {
  ShockSearch s;
  double best = std::min(below, kInf);
  Eigen::Vector4d best_u = Eigen::Vector4d::Zero();
  for (const Eigen::Vector4d& u : random_directions(o)) {
    const double limit = std::min({best * (1.0 - o.tolerance), o.max_radius, overlap_limit(u, overlap_slack)});
    if (limit <= 0.0) continue;
    if (const std::optional<RayBoundary> b = ray_boundary(leads, u, limit, o, s); b && b->r_out < best) {
      best = b->r_out;
      best_u = u;
      s.found = true;
    }
  }
  if (!s.found) return s;
  s.random_size = s.size = best;
  s.z = best * best_u;
  if (o.optimise) compass_search(leads, overlap_slack, o, best_u, s);
  return s;
}

namespace {

// Where x* + D z leads for the search: the follower's label against the attractor's own. A
// state that ends on a non-periodic set the census does not list (often a chaotic saddle's long
// transient, as at Table 2) is undecided, not elsewhere.
ShockLeads leads_from(CensusFollower& follower, const Eigen::Vector4d& x_star, const Eigen::Vector4d& unit, int self,
                      const std::function<bool(const Attractor&)>& listed) {
  return [&follower, x_star, unit, self, listed](const Eigen::Vector4d& z) {
    const CensusFollower::Outcome f = follower.follow(x_star + (z.array() * unit.array()).matrix());
    if (f.label == kUnresolvedLabel) return ShockVerdict::unresolved;
    if (f.label == self) return ShockVerdict::stays;
    if (f.label >= 0) {
      const Attractor& a = follower.attractor(static_cast<std::size_t>(f.label));
      if (!a.periodic && !listed(a)) return ShockVerdict::unresolved;
    }
    return ShockVerdict::elsewhere;
  };
}

// The verification: x_star + dx followed by a fresh follower (no attractor known before), where it
// ends set in `shock` (to, to_regime, verified).
void verify(const Parameters& p, const PointOptions& options, const CensusOptions& census, const CensusSummary& s,
            std::size_t index, CriticalShock& shock) {
  CensusFollower fresh(p, options, census);
  const CensusFollower::Outcome f = fresh.follow(shock.x_star + shock.dx);
  ++shock.follows;
  if (f.label < 0) {
    shock.to = -1;
    shock.to_regime = Regime{};
    shock.unresolved += f.label == kUnresolvedLabel ? 1 : 0;
    return;
  }
  const Attractor& reached = fresh.attractor(static_cast<std::size_t>(f.label));
  shock.to_regime = reached.regime;
  shock.to = kShockToUnlisted;
  for (std::size_t i = 0; i < s.attractors.size(); ++i)
    if (same_attractor(p, options, s.attractors[i], reached)) shock.to = static_cast<int>(i);
  shock.verified = shock.to != static_cast<int>(index) && (reached.periodic || shock.to >= 0);
}

}  // namespace

CriticalShock critical_shock(const Parameters& p, const PointOptions& options, const CensusOptions& census,
                             const CensusSummary& s, std::size_t index, CensusFollower& follower) {
  const auto start = std::chrono::steady_clock::now();
  const Attractor& a = s.attractors.at(index);
  CriticalShock out;
  out.status = ShockStatus::not_periodic;
  if (!a.periodic || a.strobe.empty()) return out;
  const StateScale scale{Model(p)};
  const Eigen::Vector4d unit(scale.length(), scale.length(), scale.speed(), scale.speed());
  const ShockOptions o = shock_options(census);
  // The follower's own index of the attractor: where its first strobe state stays.
  const CensusFollower::Outcome own = follower.follow(a.strobe.front());
  out.follows = 1;
  out.status = ShockStatus::failed;
  if (own.label < 0 || !same_attractor(p, options, a, follower.attractor(static_cast<std::size_t>(own.label)))) return out;
  const auto listed = [&](const Attractor& b) {
    return std::any_of(s.attractors.begin(), s.attractors.end(),
                       [&](const Attractor& c) { return same_attractor(p, options, c, b); });
  };
  double best = kInf, random_best = kInf;
  for (std::size_t k = 0; k < a.strobe.size(); ++k) {
    const Eigen::Vector4d& x = a.strobe[k];
    // No deeper into contact than x itself (x1 - x2 <= max(0, x1* - x2*)): critical_shock.hpp.
    const double slack = std::max(0.0, x[1] - x[0]) / scale.length();
    out.status = out.status == ShockStatus::found ? out.status : ShockStatus::none;
    const ShockSearch r = search_shock(leads_from(follower, x, unit, own.label, listed), slack, o, best);
    out.follows += r.follows;
    out.unresolved += r.unresolved;
    if (!r.found) continue;
    random_best = std::min(random_best, r.random_size);
    if (r.size < best) {
      best = r.size;
      out.size = r.size;
      out.x_star = x;
      out.strobe_index = static_cast<int>(k);
      out.dx = (r.z.array() * unit.array()).matrix();
    }
    out.status = ShockStatus::found;
  }
  if (out.status == ShockStatus::found) {
    out.random_size = random_best;
    verify(p, options, census, s, index, out);
  }
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

void add_critical_shocks(const Parameters& p, const PointOptions& options, const CensusOptions& census,
                         CensusSummary& s) {
  if (!census.shock || s.status == SolveStatus::invalid_input) return;
  CensusFollower follower(p, options, census);
  for (std::size_t i = 0; i < s.attractors.size(); ++i)
    if (!census.shock_soft_only || s.attractors[i].soft)
      s.attractors[i].shock = critical_shock(p, options, census, s, i, follower);
}

std::string to_string(ShockStatus s) {
  switch (s) {
    case ShockStatus::not_computed: return "not_computed";
    case ShockStatus::found: return "found";
    case ShockStatus::none: return "none";
    case ShockStatus::not_periodic: return "not_periodic";
    case ShockStatus::failed: return "failed";
  }
  return "failed";
}

}  // namespace vibromap
