#pragma once
// How far a periodic orbit reaches (issue #12): the largest displacement of each body and the
// closest approach of the bodies, x2 - x1, over one cycle. The closest approach is what grazing
// is about: it crosses zero where an impact appears on the orbit (or vanishes); it is negative
// (a penetration) on an orbit with impacts.
//
// A grazing is where graze_gap reaches zero; with one contact per cycle and none else near,
// that is where clearance_min crosses zero, but a further impact can appear on an orbit that
// already has one (clearance_min stays negative): graze_gap sees both.
//
// Each integration step is sampled on its dense output (64 points in free flight, 8 in a short
// contact step) and an interior extreme sample that can beat the best so far is refined by
// golden-section search on the step's interpolant, so a smooth extremum inside a step is found
// to the interpolant's accuracy (the closed form in free flight, the Dormand-Prince
// interpolant in contact).

#include <vector>

#include "vibromap/core/integrate/integrator.hpp"

namespace vibromap {

struct OrbitExtent {
  bool ok = false;            // false: the integration failed
  double x1_max = 0.0;        // m
  double x2_max = 0.0;        // m
  double clearance_min = 0.0; // least x2 - x1, m (negative: the bodies overlap, a contact)
  std::vector<Eigen::Vector4d> strobe;  // the n states at the period starts, y first, physical
  int contacts = 0;           // contact entries over the n periods
  // How near the orbit is to a change of its number of contacts, m: the least of the gaps
  // x2 - x1 at the closest approaches in free flight (an impact appears when one reaches 0)
  // and the peak penetrations of its contacts (an impact vanishes when one reaches 0).
  // Infinite for an orbit without either.
  double graze_gap = 0.0;
};

// Over the n periods from y (internal coordinates, a period start).
OrbitExtent orbit_extent(const Model& model, const IntegratorOptions& integration, const State& y, int n,
                         IntegrationCounters& counters);

}  // namespace vibromap
