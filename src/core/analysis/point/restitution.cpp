#include "vibromap/core/analysis/point/restitution.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace vibromap {

Parameters free_bodies(Parameters base, double v) {
  base.spring1 = {Spring::Form::stiffness, 0.0};
  base.spring2 = {Spring::Form::stiffness, 0.0};
  base.damper1 = {Damper::Form::coefficient, 0.0};
  base.damper2 = {Damper::Form::coefficient, 0.0};
  base.F0 = 0.0;
  base.D = 1e-3;
  base.initial = Eigen::Vector4d(0.0, base.D, v, 0.0);
  return base;
}

namespace {
// Forcing periods (0.87 s each at the default omega) an impact may take: the approach of 1 mm
// takes 2.5 ms; at kMaxImpactDamping the separation takes some 25 periods.
constexpr long kMaxImpactPeriods = 64;
}  // namespace

IntegrationStatus free_impact(const Parameters& p, const RestitutionOptions& options, Impact& impact) {
  const Model model(p);
  IntegratorOptions o;
  o.rtol = options.rtol;
  o.atol = options.atol;
  auto integ = make_integrator(model, o);
  State u = Model::to_internal(p.initial_state());
  integ->reset(u);
  ImpactRecorder rec(model, kMaxImpactPeriods + 1);
  for (long k = 0; k < kMaxImpactPeriods; ++k) {
    const IntegrationStatus status = integ->advance_period(u, rec);
    if (status != IntegrationStatus::ok) return status;
    rec.on_period_end(k, u);
    if (!rec.impacts().empty() && !rec.open_impact()) break;
  }
  if (rec.impacts().size() != 1 || rec.open_impact()) return IntegrationStatus::step_limit;
  impact = rec.impacts().front();
  return IntegrationStatus::ok;
}

double min_restitution(ContactLawKind law) {
  const ContactLaw& l = contact_law(law);
  if (!(l.chi(1e-300) > kMaxImpactDamping)) return 0.0;
  // chi(e) falls as e grows for every law: bisect on log e for chi(e) = kMaxImpactDamping.
  double lo = 1e-300, hi = 1.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(lo * hi);
    (l.chi(mid) > kMaxImpactDamping ? lo : hi) = mid;
  }
  const double scale = std::pow(10.0, std::floor(std::log10(hi)) - 2.0);  // 3 significant digits, up
  return std::ceil(hi / scale) * scale;
}

RestitutionResult free_impact_restitution_chi(ContactLawKind law, double chi, const RestitutionOptions& options) {
  if (!(chi >= 0.0 && chi <= kMaxImpactDamping))
    throw std::invalid_argument("the damping factor chi = " + std::to_string(chi) + " must be in [0, " +
                                std::to_string(kMaxImpactDamping) + "]");
  RestitutionResult r;
  r.law = law;
  r.chi = chi;
  r.e = std::nan("");  // not calibrated: chi was given
  // The reference scene: Table 1's contact (K = 1.54e11 N/m^1.5) between free bodies of 1000 kg
  // and 100 kg meeting at 0.4 m/s. Any other gives the same e_effective (the impact is
  // scale-free); this one keeps the step sizes ordinary.
  constexpr double kApproachSpeed = 0.4;  // m/s
  Parameters base;
  base.law = law == ContactLawKind::hertz && chi != 0.0 ? ContactLawKind::hunt_crossley : law;
  if (chi != 0.0) base.damping = chi;
  const Parameters p = free_bodies(base, kApproachSpeed);
  Impact im;
  r.status = free_impact(p, options, im);
  if (r.status != IntegrationStatus::ok) return r;
  r.e_effective = im.e_effective;
  r.energy_ratio = im.energy_dissipated / (0.5 * Model(p).reduced_mass() * im.v_in * im.v_in);
  r.clipped = im.clipped;
  return r;
}

RestitutionResult free_impact_restitution(ContactLawKind law, double e, const RestitutionOptions& options) {
  if (!(e > 0.0 && e <= 1.0)) throw std::invalid_argument("restitution e must be in (0, 1]");
  if (const double least = min_restitution(law); e < least) {
    std::ostringstream os;
    os << "restitution e = " << e << " is below " << to_string(law) << "'s lower limit " << least
       << ": its damping chi(e) = " << contact_law(law).chi(e) << " would pass " << kMaxImpactDamping
       << ", the most a free impact is integrated for";
    throw std::invalid_argument(os.str());
  }
  RestitutionResult r = free_impact_restitution_chi(law, contact_law(law).chi(e), options);
  r.e = e;
  return r;
}

}  // namespace vibromap
