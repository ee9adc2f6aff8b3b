#pragma once
// The restitution a contact law really gives: one impact of two free bodies (no springs,
// dampers or forcing), integrated to a tight tolerance, and its effective restitution
// |v_out / v_in| of the relative velocity.
//
// For the force K z^(3/2) (1 + chi w / v_in) the result depends on chi alone: with
// z = Z s, t = tau_c r, Z = (mu v_in^2 / K)^(2/5), tau_c = Z / v_in, the impact is
// s'' = -s^(3/2) (1 + chi s') with s(0) = 0, s'(0) = 1, free of mu, K and v_in. So a law and a
// target e give one number, the law's effective e (what `vibromap restitution` tabulates).

#include <vector>

#include "vibromap/core/analysis/point/impact.hpp"
#include "vibromap/core/integrate/integrator.hpp"
#include "vibromap/core/model/contact_law.hpp"

namespace vibromap {

// The largest damping factor chi the free impact is integrated for. The impact lasts longer as
// chi grows: its slow separation, at w ~ -v_in / chi, takes about 1.4 chi^0.6 contact time
// scales (tau_c = 0.24 ms for the reference bodies), 22 s at chi = 1e8, and free_impact follows
// it for at most 64 forcing periods (56 s: chi up to about 4e8, found by trying). Up to this chi
// a free impact takes 0.1 s; beyond it the law is refused with the least e it allows
// (min_restitution): flores e >= 1.6e-8, gonthier e >= 1e-8.
inline constexpr double kMaxImpactDamping = 1e8;

// The least restitution e whose law's chi(e) is at most kMaxImpactDamping (0 when every e in
// (0, 1] is: hertz, hunt-crossley, lankarani-nikravesh). Rounded up to 3 significant digits,
// so that e = min_restitution(law) itself is accepted.
double min_restitution(ContactLawKind law);

struct RestitutionOptions {
  double rtol = 1e-12;  // relative tolerance of the impact's integration, -
  double atol = 1e-16;  // absolute tolerance on z (m) for the reference scene (K = 1.54e11, v_in = 0.4 m/s), -
};

struct RestitutionResult {
  ContactLawKind law = ContactLawKind::hertz;
  double e = 1.0;             // target restitution the law is calibrated for, -
  double chi = 0.0;           // the calibrated damping factor, -
  double e_effective = 1.0;   // |v_out / v_in| of the integrated impact, -
  double energy_ratio = 0.0;  // energy dissipated over the entry kinetic energy mu v_in^2 / 2, -
  bool clipped = false;       // the damped force was clipped at 0 before the bodies separated
  IntegrationStatus status = IntegrationStatus::ok;
};

// `base` with no springs, dampers or forcing, and the bodies 1 mm apart closing at v (m/s):
// one impact of two free bodies, the rest of the scene (masses, moduli, law) from `base`.
Parameters free_bodies(Parameters base, double v);

// Integrates the scene `p` (free_bodies()) period by period until its one impact is over (at
// most kMaxImpactPeriods forcing periods) into `impact`; a status other than ok when the
// integration fails, or step_limit when the impact is not over by then.
IntegrationStatus free_impact(const Parameters& p, const RestitutionOptions& options, Impact& impact);

// The free impact of the law calibrated for e (e in [min_restitution(law), 1]; else throws
// std::invalid_argument naming the limit).
RestitutionResult free_impact_restitution(ContactLawKind law, double e, const RestitutionOptions& options = {});

// The same with the damping factor chi given directly (law labels the result only; chi in
// [0, kMaxImpactDamping], else std::invalid_argument).
RestitutionResult free_impact_restitution_chi(ContactLawKind law, double chi, const RestitutionOptions& options = {});

}  // namespace vibromap
