#pragma once
// Locates a contact entry or exit inside one step, on the step's dense output.
//
// In free mode the event is the first time z rises above 0 (entry); in contact mode the
// first time z falls below 0 (exit). With g = +z (free) or -z (contact), the event is the
// first tau where g > 0, given g(tau0) <= 0.
//
// Guard against stepping over a short excursion: looking only at the step's end points
// would miss a grazing contact that enters and leaves within one step (z < 0 at both ends).
// So g is sampled at kSamples + 1 points of the dense output and, in each sub-interval where
// g' = +-w changes sign from + to -, the interior maximum of g is located as a root of w and
// tested too. A quartic dense output has at most three extrema; the step-size limit
// (IntegratorOptions::max_step) and the error control keep steps short against the motion,
// so two extrema inside one sub-interval (1/8 of a step) would need an excursion shorter
// than the error control resolves.

#include <optional>

#include "vibromap/core/integrate/observer.hpp"

namespace vibromap {

struct LocatedEvent {
  double tau;  // event time (the state there is just past the boundary or on it)
};

// tau_tol: time tolerance of the located root, s.
std::optional<LocatedEvent> locate_contact_event(const DenseOutput& dense, double tau0, double tau1,
                                                 ContactMode mode, double tau_tol);

}  // namespace vibromap
