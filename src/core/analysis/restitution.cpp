#include "vibromap/core/analysis/restitution.hpp"

#include <cmath>
#include <stdexcept>

#include "vibromap/core/analysis/impact.hpp"

namespace vibromap {

namespace {

// The reference scene: Table 1's contact (K = 1.54e11 N/m^1.5) between free bodies of
// 1000 kg and 100 kg meeting at 0.4 m/s after 1 mm of free approach. Any other scene gives
// the same e_effective (the impact is scale-free); this one keeps the step sizes ordinary.
Parameters free_bodies(ContactLawKind law, double chi) {
  Parameters p;
  p.spring1 = {Spring::Form::stiffness, 0.0};
  p.spring2 = {Spring::Form::stiffness, 0.0};
  p.damper1 = {Damper::Form::coefficient, 0.0};
  p.damper2 = {Damper::Form::coefficient, 0.0};
  p.F0 = 0.0;
  p.D = 1e-3;
  p.law = law;
  p.damping = chi;
  constexpr double kApproachSpeed = 0.4;  // m/s
  p.initial = Eigen::Vector4d(0.0, p.D, kApproachSpeed, 0.0);
  return p;
}

}  // namespace

RestitutionResult free_impact_restitution_chi(ContactLawKind law, double chi, const RestitutionOptions& options) {
  RestitutionResult r;
  r.law = law;
  r.chi = chi;
  r.e = std::nan("");  // not calibrated: chi was given
  Parameters p = free_bodies(law == ContactLawKind::hertz && chi != 0.0 ? ContactLawKind::hunt_crossley : law, chi);
  if (chi == 0.0) p.damping.reset();
  const Model model(p);
  IntegratorOptions o;
  o.rtol = options.rtol;
  o.atol = options.atol;
  auto integ = make_integrator(model, o);
  State u = Model::to_internal(p.initial_state());
  integ->reset(u);
  ImpactRecorder rec(model, 2);
  // One forcing period (0.87 s) is far longer than the approach (2.5 ms) and the contact.
  r.status = integ->advance_period(u, rec);
  if (r.status != IntegrationStatus::ok) return r;
  if (rec.impacts().size() != 1) {
    r.status = IntegrationStatus::non_finite;  // no completed impact: cannot happen for chi >= 0
    return r;
  }
  const Impact& im = rec.impacts().front();
  r.e_effective = im.e_effective;
  r.energy_ratio = im.energy_dissipated / (0.5 * model.reduced_mass() * im.v_in * im.v_in);
  r.clipped = im.clipped;
  return r;
}

RestitutionResult free_impact_restitution(ContactLawKind law, double e, const RestitutionOptions& options) {
  if (!(e > 0.0 && e <= 1.0)) throw std::invalid_argument("restitution e must be in (0, 1]");
  RestitutionResult r = free_impact_restitution_chi(law, contact_law(law).chi(e), options);
  r.e = e;
  return r;
}

}  // namespace vibromap
