#pragma once
// The Poincare section that shooting works on. The stroboscopic map P samples the motion at
// the start of each forcing period (local time tau = 0). When an impact falls near that
// phase, P is nearly discontinuous: a small change of the state moves the impact across the
// section, into the period before or after, and P jumps by the whole velocity exchange of
// the impact. Newton's basin then shrinks to almost nothing (on the paper's Table 1 the
// impact starts 0.07 % of a period after the section, and Newton fails from 0.06 motion
// scales off the orbit). Sampling at a phase s in the middle of the free flight instead makes
// P smooth over the motion's scale.
//
// The map sampled at phase s is the stroboscopic map of the same system with its forcing
// advanced by s (phi0 + omega s): the motion from y at tau = s is the shifted system's motion
// from y at tau = 0. A state is carried between the two sections by integrating part of a
// period and reading the integrator's dense output.

#include <deque>
#include <optional>

#include "vibromap/core/analysis/point/impact.hpp"
#include "vibromap/core/integrate/integrator.hpp"

namespace vibromap {

// The phase s in [0, T) farthest from every contact of the impacts entered in the periods
// first..last (the open one included): the middle of the longest contact-free stretch, with
// the contacts folded onto one period. 0 when there is no contact, or when 0 is already far
// from every contact, or when contact covers the whole period.
double section_phase(const std::deque<Impact>& impacts, const std::optional<Impact>& open, long first, long last,
                     double period);

// The same system with its forcing advanced by s: its stroboscopic map samples the motion at
// phase s of the forcing period.
Model shifted_model(const Model& model, double s);

// The state at local time tau in (0, T] of the period starting from u. Integrates the whole
// period (the integrators advance whole periods) and reads the dense output at tau; empty
// when the integration fails. counters accumulates the work.
std::optional<State> state_at_phase(const Model& model, const IntegratorOptions& options, const State& u, double tau,
                                    IntegrationCounters& counters);

}  // namespace vibromap
