#include "vibromap/core/analysis/orbit_extent.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "vibromap/core/integrate/root_finding.hpp"

namespace vibromap {
namespace {

constexpr int kSamples = 64;           // per free-flight step at least (the closed form spans up to a period)
constexpr int kSamplesPerFastPeriod = 16;  // per period of the free system's faster mode, at least
constexpr int kMaxSamples = 4096;      // per step, at most
constexpr int kContactSamples = 8;     // per contact step (a short part of one impact)
constexpr double kRootTolerance = 1e-13;  // a maximum's time, relative to the step: its value to ~1e-25

using Physical = Eigen::Vector4d;  // (x1, x2, v1, v2)

// A quantity whose maxima are sought and its rate of change: x1, x2 and x1 - x2 (the overlap,
// minus the clearance x2 - x1).
struct Part {
  double (*value)(const Physical&);
  double (*rate)(const Physical&);
};
constexpr Part kX1{[](const Physical& x) { return x[0]; }, [](const Physical& x) { return x[2]; }};
constexpr Part kX2{[](const Physical& x) { return x[1]; }, [](const Physical& x) { return x[3]; }};
constexpr Part kOverlap{[](const Physical& x) { return x[0] - x[1]; }, [](const Physical& x) { return x[2] - x[3]; }};

// The angular frequency of the faster undamped mode of the free system (no contact), rad/s:
// the larger root of det(K - w^2 M) = 0.
double fast_frequency(const Model& model) {
  const Parameters& p = model.parameters();
  const double a = (model.k1() + model.k2()) / p.m1, d = model.k2() / p.m2, bc = model.k2() * model.k2() / (p.m1 * p.m2);
  return std::sqrt(0.5 * (a + d) + std::sqrt(0.25 * (a - d) * (a - d) + bc));
}

// One step sampled on its dense output at equally spaced times, its ends included.
struct Samples {
  std::vector<double> tau;
  std::vector<Physical> x;
};

// The local maxima of a part within one step: where its rate changes sign from + to - between two
// samples, located as a root of the rate on the dense output (the velocity is part of the state,
// so no difference quotient is needed). Each maximum's time and value are passed to `take`.
template <class Take>
void interior_maxima(const StepView& step, const Samples& s, const Part& part, Take take) {
  const double tol = kRootTolerance * (step.tau1 - step.tau0);
  for (std::size_t i = 0; i + 1 < s.tau.size(); ++i) {
    const double ga = -part.rate(s.x[i]), gb = -part.rate(s.x[i + 1]);
    if (!(ga < 0.0 && gb > 0.0)) continue;  // a rate exactly 0 at a sample: that sample is the maximum
    const auto g = [&](double tau) { return -part.rate(Model::to_physical(step.eval(tau))); };
    const double t = illinois(g, s.tau[i], s.tau[i + 1], ga, gb, tol).x;
    take(part.value(Model::to_physical(step.eval(t))));
  }
}

// The largest of a part over the step: at its samples (the step's ends among them) and at its
// located interior maxima. A maximum at a step's end (the rate keeps its sign over the step) is
// that end's sample; one inside is a root of the rate: the largest is found whichever it is.
double step_max(const StepView& step, const Samples& s, const Part& part) {
  double best = -std::numeric_limits<double>::infinity();
  for (const Physical& x : s.x) best = std::max(best, part.value(x));
  interior_maxima(step, s, part, [&](double v) { best = std::max(best, v); });
  return best;
}

class ExtentObserver final : public Observer {
 public:
  explicit ExtentObserver(const Model& model) : fast_(fast_frequency(model)) {}

  void on_step(const StepView& step) override {
    if (!(step.tau1 > step.tau0)) return;
    const Samples s = sample(step);
    x1_max = std::max(x1_max, step_max(step, s, kX1));
    x2_max = std::max(x2_max, step_max(step, s, kX2));
    overlap_max = std::max(overlap_max, step_max(step, s, kOverlap));
    track_gaps(step, s);
  }
  void on_event(const ContactEvent& event) override {
    if (event.kind == ContactEvent::Kind::entry) {
      ++contacts;
    } else {
      close_contact();
    }
  }
  void close_contact() {
    if (contact_peak > -std::numeric_limits<double>::infinity()) graze_gap = std::min(graze_gap, contact_peak);
    contact_peak = -std::numeric_limits<double>::infinity();
  }
  int contacts = 0;
  double graze_gap = std::numeric_limits<double>::infinity();
  double contact_peak = -std::numeric_limits<double>::infinity();
  double x1_max = -std::numeric_limits<double>::infinity();
  double x2_max = -std::numeric_limits<double>::infinity();
  double overlap_max = -std::numeric_limits<double>::infinity();  // max of x1 - x2

 private:
  // A free-flight step gets kSamples samples, more when it spans several periods of the faster
  // mode (so that no sub-interval holds two extremes of a part); a contact step kContactSamples.
  Samples sample(const StepView& step) const {
    int n = kContactSamples;
    if (step.mode != ContactMode::contact) {
      const double periods = (step.tau1 - step.tau0) * fast_ / (2.0 * std::numbers::pi);
      n = std::clamp(static_cast<int>(std::ceil(kSamplesPerFastPeriod * periods)), kSamples, kMaxSamples);
    }
    Samples s;
    s.tau.resize(static_cast<std::size_t>(n) + 1);
    s.x.resize(s.tau.size());
    for (int i = 0; i <= n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      s.tau[k] = i == n ? step.tau1 : step.tau0 + (step.tau1 - step.tau0) * i / n;
      s.x[k] = Model::to_physical(step.eval(s.tau[k]));
    }
    return s;
  }

  // z = x1 - x2: its interior maxima are the closest approaches in free flight (graze_gap) and
  // the deepest penetration in contact (with the step's ends: contact_peak).
  void track_gaps(const StepView& step, const Samples& s) {
    const bool in_contact = step.mode == ContactMode::contact;
    interior_maxima(step, s, kOverlap, [&](double peak) {
      if (in_contact)
        contact_peak = std::max(contact_peak, peak);
      else if (peak < 0.0)
        graze_gap = std::min(graze_gap, -peak);
    });
    if (in_contact) contact_peak = std::max({contact_peak, kOverlap.value(s.x.front()), kOverlap.value(s.x.back())});
  }

  double fast_;  // rad/s
};

}  // namespace

OrbitExtent orbit_extent(const Model& model, const IntegratorOptions& integration, const State& y, int n,
                         IntegrationCounters& counters) {
  OrbitExtent e;
  const auto integ = make_integrator(model, integration);
  State u = y;
  integ->reset(u);
  ExtentObserver obs(model);
  for (int i = 0; i < n; ++i) {
    e.strobe.push_back(Model::to_physical(u));
    if (integ->advance_period(u, obs) != IntegrationStatus::ok) {
      counters += integ->counters();
      e.strobe.clear();
      return e;
    }
  }
  counters += integ->counters();
  e.ok = true;
  e.x1_max = obs.x1_max;
  e.x2_max = obs.x2_max;
  e.clearance_min = -obs.overlap_max;
  obs.close_contact();
  e.contacts = obs.contacts;
  e.graze_gap = obs.graze_gap;
  return e;
}

}  // namespace vibromap
