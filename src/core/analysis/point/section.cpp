#include "vibromap/core/analysis/point/section.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace vibromap {

namespace {

// Keep the section at phase 0 while every contact is at least this fraction of a period
// away from it: moving the section costs two part-period integrations and a final Newton
// evaluation on the original section.
constexpr double kQuietFraction = 0.125;

// Contact intervals folded onto [0, T), sorted by start (an interval that wraps around the
// period end is split in two).
std::vector<std::pair<double, double>> folded_contacts(const std::deque<Impact>& impacts,
                                                       const std::optional<Impact>& open, long first, long last,
                                                       double period) {
  std::vector<std::pair<double, double>> out;
  auto add = [&](double start, double length) {
    if (length >= period) {
      out.emplace_back(0.0, period);
      return;
    }
    const double end = start + length;
    if (end <= period) {
      out.emplace_back(start, end);
    } else {
      out.emplace_back(start, period);
      out.emplace_back(0.0, end - period);
    }
  };
  for (const Impact& im : impacts)
    if (im.period_in >= first && im.period_in <= last) add(im.tau_in, im.T_con);
  if (open && open->period_in <= last) {
    // Still in contact at the end of period `last`: from entry to the end of that period.
    add(open->tau_in, static_cast<double>(last + 1 - open->period_in) * period - open->tau_in);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

double section_phase(const std::deque<Impact>& impacts, const std::optional<Impact>& open, long first, long last,
                     double period) {
  const auto contacts = folded_contacts(impacts, open, first, last, period);
  if (contacts.empty()) return 0.0;
  // Distance of phase 0 from the contacts, on the circle.
  const double quiet_before = period - std::max_element(contacts.begin(), contacts.end(), [](auto a, auto b) {
                                         return a.second < b.second;
                                       })->second;
  const double quiet_after = contacts.front().first;
  if (std::min(quiet_before, quiet_after) >= kQuietFraction * period) return 0.0;
  // The longest gap between consecutive contacts, the one across the period end included.
  double best_length = 0.0, best_mid = 0.0, reach = contacts.front().second;
  for (std::size_t i = 1; i < contacts.size(); ++i) {
    if (contacts[i].first > reach && contacts[i].first - reach > best_length) {
      best_length = contacts[i].first - reach;
      best_mid = 0.5 * (reach + contacts[i].first);
    }
    reach = std::max(reach, contacts[i].second);
  }
  const double wrap = period - reach + contacts.front().first;
  if (wrap > best_length) {
    best_length = wrap;
    best_mid = std::fmod(reach + 0.5 * wrap, period);
  }
  return best_length > 0.0 ? best_mid : 0.0;
}

Model shifted_model(const Model& model, double s) {
  Parameters p = model.parameters();
  p.phi0 += p.omega * s;
  return Model(p);
}

namespace {

// Reads the state at one local time from the steps of the first period shown.
class PhaseProbe final : public Observer {
 public:
  explicit PhaseProbe(double tau) : tau_(tau) {}
  void on_step(const StepView& step) override {
    if (!state_ && step.tau0 < tau_ && tau_ <= step.tau1) state_ = step.eval(tau_);
  }
  const std::optional<State>& state() const { return state_; }

 private:
  double tau_;
  std::optional<State> state_;
};

}  // namespace

std::optional<State> state_at_phase(const Model& model, const IntegratorOptions& options, const State& u, double tau,
                                    IntegrationCounters& counters) {
  const auto integ = make_integrator(model, options);
  State v = u;
  integ->reset(v);
  PhaseProbe probe(tau);
  const IntegrationStatus status = integ->advance_period(v, probe);
  counters += integ->counters();
  if (status != IntegrationStatus::ok) return std::nullopt;
  if (tau >= model.period()) return v;
  return probe.state();
}

}  // namespace vibromap
