#pragma once
// The minimal critical shock of an attractor of a census (docs/model.md): the smallest
// perturbation dx of one of its period-start states x* (forcing phase 0) such that the motion
// from x* + dx ends on another attractor. Klinshov et al. 2015 call it the stability threshold,
// Halekotte and Feudel 2020 the minimal fatal shock; Attractors.jl's minimal_critical_shock finds
// it by random sampling and a black-box optimiser on a penalised norm. Here the search works on
// rays, because the census's follower decides a state cheaply when it stays (it is captured by
// its own orbit) and a ray's boundary is a one-dimensional bisection:
//  1. random directions u (seeded, deterministic; only the coordinates of census.shock_on move),
//     each scanned outwards at radii R 2^(-j/2), j = 11 .. 0 (R: census.shock_max_radius), up
//     to the least radius found so far, and the first radius that leads elsewhere bisected
//     down to the one before it, to the relative tolerance;
//  2. a compass search on the sphere of directions from the best one (Kolda, Lewis, Torczon
//     2003, "Optimization by direct search"): turns of angle theta towards +-each tangent axis,
//     taken when the boundary along the turned ray is nearer by more than the tolerance, theta
//     halved when none is, until theta < tolerance (rad): the radius then changes by about the
//     tolerance at most, even where the nearest point is a kink (a corner with the contact
//     limit below), where it changes linearly with the angle.
// The norm is Euclidean in motion scales: |(dx1/L, dx2/L, dv1/(omega L), dv2/(omega L))|, L
// the census box's (census.hpp). A perturbation may not press the bodies deeper into each other
// than x* itself: x1 - x2 <= max(0, x1* - x2*), so from a state with the bodies apart no overlap
// at all (touching is allowed), and from a state in contact (an impact that spans forcing phase
// 0, as Table 2's soft (1,1) does: x1* - x2* = +0.016 m there) none deeper than its own, which
// the motion itself passes through. A ray stops where it reaches that limit. "Leads elsewhere": the
// follower decides another periodic attractor (listed by the census or not), or a non-periodic
// one the census lists; a state still undecided at the budget's end, or on a non-periodic set the
// census does not list (at Table 2 a chaotic saddle whose transients outlast the budget), counts
// as not elsewhere and is counted apart (unresolved).

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "vibromap/core/analysis/census/census.hpp"

namespace vibromap {

// The search's options (CensusOptions' shock_* fields).
struct ShockOptions {
  std::array<bool, 4> on = {true, true, true, true};  // coordinates the shock moves: x1, x2, v1, v2
  int directions = 32;       // random directions of step 1, -
  double tolerance = 1e-3;   // relative tolerance on the shock's size (bisection, compass stop), -
  double max_radius = 2.0;   // largest shock looked for, in motion scales, -
  bool optimise = true;      // false: step 1 alone (the random directions; for checks)
  std::uint64_t seed = 1;    // seed of the directions, -
  long max_follows = 20000;  // follows at most per attractor (the compass search stops there), -
};
ShockOptions shock_options(const CensusOptions& c);

// Where a scaled perturbation z of x* leads.
enum class ShockVerdict { stays, elsewhere, unresolved };

// The search in scaled coordinates, apart from the dynamics (a test gives it a known basin).
// leads(z): where x* + D z leads (D = diag(L, L, omega L, omega L)). overlap_slack: the largest
// z1 - z2 allowed (the contact limit above; +inf: no limit). below: only shocks smaller than this
// are looked for (the best of another strobe state).
struct ShockSearch {
  bool found = false;
  double size = 0.0;                        // |z| of the best perturbation found, motion scales
  Eigen::Vector4d z = Eigen::Vector4d::Zero();  // that perturbation, scaled
  double random_size = 0.0;                 // the best of step 1 (before the compass search); found only
  long follows = 0;                         // calls of leads
  int unresolved = 0;                       // of which undecided
};
using ShockLeads = std::function<ShockVerdict(const Eigen::Vector4d& z)>;
ShockSearch search_shock(const ShockLeads& leads, double overlap_slack, const ShockOptions& o, double below);

// The boundary along one ray (unit u, scaled): the first of the scan's radii up to `limit` that
// leads elsewhere, bisected down to the one before it to the relative tolerance; nullopt when
// none does. [r_in, r_out]: r_in does not lead elsewhere, r_out does.
struct RayBoundary {
  double r_in = 0.0, r_out = 0.0;
};
std::optional<RayBoundary> ray_boundary(const ShockLeads& leads, const Eigen::Vector4d& u, double limit,
                                        const ShockOptions& o, ShockSearch& counts);

// The shock of attractor `index` of census s (its attractors list, s from census_point with the
// same p, options, census); follower: one for the point and census options, shared by the
// attractors of one census (it keeps the attractors it finds). Non-periodic attractors have no
// period-start states: status not_periodic.
CriticalShock critical_shock(const Parameters& p, const PointOptions& options, const CensusOptions& census,
                             const CensusSummary& s, std::size_t index, CensusFollower& follower);
// Every listed attractor's shock (Attractor::shock), when census.shock.
void add_critical_shocks(const Parameters& p, const PointOptions& options, const CensusOptions& census,
                         CensusSummary& s);

}  // namespace vibromap
