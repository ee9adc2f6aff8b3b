#pragma once
// Contact laws: elastic Hertz and Hertz with nonlinear (Hunt-Crossley form) damping,
//   Fc = max(0, K z^(3/2) (1 + chi w / v_in))  for approach z > 0, else 0,
// w = z' the approach rate, v_in > 0 the approach rate at the contact's entry (docs/model.md,
// "Dissipative contact laws"). The laws share this force; they differ in how the damping
// factor chi (dimensionless) is calibrated from a coefficient of restitution e in (0, 1]:
//   hertz                chi = 0                         (elastic, e = 1 whatever is asked)
//   hunt-crossley        chi = 3 (1 - e) / 2             (Hunt & Crossley 1975)
//   lankarani-nikravesh  chi = 3 (1 - e^2) / 4           (Lankarani & Nikravesh 1990)
//   flores               chi = 8 (1 - e) / (5 e)         (Flores et al. 2011)
//   gonthier             chi = (1 - e^2) / e             (Gonthier et al. 2004)
// Each calibration assumes a different model of the impact, so the restitution a law really
// gives (its effective e, `vibromap restitution`) differs from the e it was calibrated for.
//
// The seam: a ContactLaw is a name and a calibration chi(e); everything downstream (the
// force, its Jacobian, events, shooting) sees only chi, so a new law is one small type.

#include <string>
#include <string_view>
#include <vector>

namespace vibromap {

enum class ContactLawKind { hertz, hunt_crossley, lankarani_nikravesh, flores, gonthier };
std::string to_string(ContactLawKind k);             // "hertz", "hunt-crossley", ...
ContactLawKind parse_contact_law(std::string_view s);  // throws std::invalid_argument

class ContactLaw {
 public:
  virtual ~ContactLaw() = default;
  virtual ContactLawKind kind() const = 0;
  // The damping factor chi (-) calibrated for restitution e in (0, 1]; chi(1) = 0.
  virtual double chi(double e) const = 0;
};

// The law of each kind (static objects, never null).
const ContactLaw& contact_law(ContactLawKind k);
// Every law, in enum order (the index of a law in a map's categorical axis).
const std::vector<ContactLawKind>& all_contact_laws();

}  // namespace vibromap
