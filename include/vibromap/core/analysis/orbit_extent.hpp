#pragma once
// How far a periodic orbit reaches (issue #12): the largest displacement of each body and the
// closest approach of the bodies, x2 - x1, over one cycle. The closest approach is what grazing
// is about: it crosses zero where an impact appears on the orbit (or vanishes); it is negative
// (a penetration) on an orbit with impacts.
//
// Each integration step is sampled on its dense output (64 points) and the extreme sample is
// refined by golden-section search on the step's interpolant, so a smooth extremum inside a step
// is found to the interpolant's accuracy (the closed form in free flight, the Dormand-Prince
// interpolant in contact).

#include "vibromap/core/integrate/integrator.hpp"

namespace vibromap {

struct OrbitExtent {
  bool ok = false;            // false: the integration failed
  double x1_max = 0.0;        // m
  double x2_max = 0.0;        // m
  double clearance_min = 0.0; // least x2 - x1, m (negative: the bodies overlap, a contact)
};

// Over the n periods from y (internal coordinates, a period start).
OrbitExtent orbit_extent(const Model& model, const IntegratorOptions& integration, const State& y, int n,
                         IntegrationCounters& counters);

}  // namespace vibromap
