#pragma once
// How far a periodic orbit reaches: the largest displacement of each body and the
// closest approach of the bodies, x2 - x1, over one cycle. The closest approach is what grazing
// is about: it crosses zero where an impact appears on the orbit (or vanishes); it is negative
// (a penetration) on an orbit with impacts.
//
// A grazing is where graze_gap reaches zero; with one contact per cycle and none else near,
// that is where clearance_min crosses zero, but a further impact can appear on an orbit that
// already has one (clearance_min stays negative): graze_gap sees both.
//
// The extremes are located, not sampled: each integration step is sampled on its
// dense output (64 points in free flight, more when the step spans more than 4 periods of the
// free system's faster mode, so that at least 16 fall in each; 8 in a contact step), and
// wherever the rate of a quantity (v1 for x1, v2 for x2, w = v1 - v2 for x1 - x2) changes sign
// from + to - between two samples, its maximum is located as a root of that rate on the dense
// output (Illinois, to 1e-13 of the step) and evaluated there; a maximum at a step's end is that
// end's sample. The extremes are thus as exact as the dense output: the closed form in free flight,
// the Dormand-Prince interpolant in contact (a contact-free branch equals the closed-form linear
// response's |Q1|, D + |Q2| and D - |Q2 - Q1| to ~1e-12, tests/core/test_continuation.cpp).
// The closest approaches and peak penetrations behind graze_gap are located the same way.
//
// The approaches: every local minimum of x2 - x1 over the cycle, signed, with its
// phase: a closest approach in free flight (its gap, > 0) and each contact (minus its peak
// penetration, < 0). One approach's signed clearance crosses zero smoothly where its impact
// appears or vanishes (at a grazing the contact is shallow and hardly changes the motion, so its
// peak penetration continues the free flight's closest approach through zero): the grazing
// curves' defining condition (curve_continuation.hpp). A contact cut by the cycle's start is one
// approach (the deeper of its two parts' peaks).

#include <vector>

#include "vibromap/core/integrate/integrator.hpp"

namespace vibromap {

// A local minimum of the clearance x2 - x1 over the cycle.
struct Approach {
  double phase = 0.0;      // its time as a fraction of the n-period cycle, [0, 1]
  double clearance = 0.0;  // m: the gap of a closest approach in free flight (> 0), or minus the
                           // peak penetration of a contact (< 0)
};

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
  std::vector<Approach> approaches;  // in the order of the cycle
};

// The approach whose phase is nearest `phase` (distance on the circle of the cycle's phases);
// none when the orbit has none.
const Approach* nearest_approach(const OrbitExtent& e, double phase);
// The approach whose |clearance| is least (the one touching at a grazing); none without any.
const Approach* touching_approach(const OrbitExtent& e);

// Over the n periods from y (internal coordinates, a period start).
OrbitExtent orbit_extent(const Model& model, const IntegratorOptions& integration, const State& y, int n,
                         IntegrationCounters& counters);

}  // namespace vibromap
