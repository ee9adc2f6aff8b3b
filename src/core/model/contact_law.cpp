#include "vibromap/core/model/contact_law.hpp"

#include <stdexcept>

namespace vibromap {

namespace {

class Hertz final : public ContactLaw {
 public:
  ContactLawKind kind() const override { return ContactLawKind::hertz; }
  double chi(double /*e*/) const override { return 0.0; }
};

// Hunt & Crossley (1975): chi = 3 (1 - e) / 2, from a linearised energy balance at small
// damping (e near 1).
class HuntCrossley final : public ContactLaw {
 public:
  ContactLawKind kind() const override { return ContactLawKind::hunt_crossley; }
  double chi(double e) const override { return 1.5 * (1.0 - e); }
};

// Lankarani & Nikravesh (1990): chi = 3 (1 - e^2) / 4, from the energy lost per impact
// (1 - e^2) m v^2 / 2 and the elastic hysteresis loop, again assuming e near 1.
class LankaraniNikravesh final : public ContactLaw {
 public:
  ContactLawKind kind() const override { return ContactLawKind::lankarani_nikravesh; }
  double chi(double e) const override { return 0.75 * (1.0 - e * e); }
};

// Flores, Machado, Silva & Martins (2011): chi = 8 (1 - e) / (5 e), meant for the whole
// range of e.
class Flores final : public ContactLaw {
 public:
  ContactLawKind kind() const override { return ContactLawKind::flores; }
  double chi(double e) const override { return 1.6 * (1.0 - e) / e; }
};

// Gonthier, McPhee, Lange & Piedboeuf (2004): chi = (1 - e^2) / e.
class Gonthier final : public ContactLaw {
 public:
  ContactLawKind kind() const override { return ContactLawKind::gonthier; }
  double chi(double e) const override { return (1.0 - e * e) / e; }
};

struct Entry {
  ContactLawKind kind;
  std::string_view name;
  const ContactLaw* law;
};

const Hertz kHertz;
const HuntCrossley kHuntCrossley;
const LankaraniNikravesh kLankaraniNikravesh;
const Flores kFlores;
const Gonthier kGonthier;
// In enum order.
const Entry kLaws[] = {
    {ContactLawKind::hertz, "hertz", &kHertz},
    {ContactLawKind::hunt_crossley, "hunt-crossley", &kHuntCrossley},
    {ContactLawKind::lankarani_nikravesh, "lankarani-nikravesh", &kLankaraniNikravesh},
    {ContactLawKind::flores, "flores", &kFlores},
    {ContactLawKind::gonthier, "gonthier", &kGonthier},
};

const Entry& entry(ContactLawKind k) {
  const auto i = static_cast<std::size_t>(k);
  if (i >= std::size(kLaws)) throw std::invalid_argument("unknown contact law");
  return kLaws[i];
}

}  // namespace

std::string to_string(ContactLawKind k) { return std::string(entry(k).name); }

ContactLawKind parse_contact_law(std::string_view s) {
  for (const Entry& e : kLaws)
    if (e.name == s) return e.kind;
  std::string names;
  for (const Entry& e : kLaws) names += (names.empty() ? "" : ", ") + std::string(e.name);
  throw std::invalid_argument("unknown contact law '" + std::string(s) + "' (one of " + names + ")");
}

const ContactLaw& contact_law(ContactLawKind k) { return *entry(k).law; }

const std::vector<ContactLawKind>& all_contact_laws() {
  static const std::vector<ContactLawKind> all = [] {
    std::vector<ContactLawKind> v;
    for (const Entry& e : kLaws) v.push_back(e.kind);
    return v;
  }();
  return all;
}

}  // namespace vibromap
