#include "vibromap/core/analysis/continuation/orbit_extent.hpp"

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
    take(t, part.value(Model::to_physical(step.eval(t))));
  }
}

// The largest of a part over the step: at its samples (the step's ends among them) and at its
// located interior maxima. A maximum at a step's end (the rate keeps its sign over the step) is
// that end's sample; one inside is a root of the rate: the largest is found whichever it is.
double step_max(const StepView& step, const Samples& s, const Part& part) {
  double best = -std::numeric_limits<double>::infinity();
  for (const Physical& x : s.x) best = std::max(best, part.value(x));
  interior_maxima(step, s, part, [&](double, double v) { best = std::max(best, v); });
  return best;
}

// The largest value of a quantity seen so far and where (phase) it was.
struct Peak {
  double value = -std::numeric_limits<double>::infinity();
  double phase = 0.0;
  bool seen() const { return value > -std::numeric_limits<double>::infinity(); }
  void take(double v, double at) {
    if (v > value) value = v, phase = at;
  }
};

class ExtentObserver final : public Observer {
 public:
  ExtentObserver(const Model& model, int n) : fast_(fast_frequency(model)), period_(model.period()), n_(n) {}

  void begin_period(int i) { index_ = i; }

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
      entered_ = true;
    } else {
      close_contact();
    }
  }
  // The contact in progress ends: its peak penetration is an approach (and a graze_gap candidate).
  void close_contact() {
    if (!contact_peak.seen()) return;
    graze_gap = std::min(graze_gap, contact_peak.value);
    if (!entered_) first_open_ = static_cast<int>(approaches.size());  // it began before the cycle did
    approaches.push_back({contact_peak.phase, -contact_peak.value});
    contact_peak = Peak{};
  }
  // The cycle's end: a contact still in progress is closed; when it continues the one the cycle
  // began in (the same contact, cut by the cycle's start), the two parts are one approach.
  void finish() {
    const bool open_at_end = contact_peak.seen();
    close_contact();
    if (!open_at_end || first_open_ < 0 || first_open_ + 1 >= static_cast<int>(approaches.size())) return;
    const Approach last = approaches.back();
    approaches.pop_back();
    Approach& first = approaches[static_cast<std::size_t>(first_open_)];
    if (last.clearance < first.clearance) first = last;
  }
  int contacts = 0;
  double graze_gap = std::numeric_limits<double>::infinity();
  Peak contact_peak;  // of x1 - x2 in the contact in progress
  std::vector<Approach> approaches;
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

  // z = x1 - x2: its interior maxima are the closest approaches in free flight (graze_gap and
  // approaches) and the deepest penetration in contact (with the step's ends: contact_peak).
  void track_gaps(const StepView& step, const Samples& s) {
    const bool in_contact = step.mode == ContactMode::contact;
    interior_maxima(step, s, kOverlap, [&](double tau, double peak) {
      if (in_contact) {
        contact_peak.take(peak, phase(tau));
      } else if (peak < 0.0) {
        graze_gap = std::min(graze_gap, -peak);
        approaches.push_back({phase(tau), -peak});
      }
    });
    if (in_contact) {
      contact_peak.take(kOverlap.value(s.x.front()), phase(s.tau.front()));
      contact_peak.take(kOverlap.value(s.x.back()), phase(s.tau.back()));
    }
  }
  // Local time tau of the current period as a fraction of the n-period cycle.
  double phase(double tau) const { return (index_ + tau / period_) / n_; }

  double fast_;     // rad/s
  double period_;   // T, in the integrator's time
  int n_;           // periods in the cycle
  int index_ = 0;   // the current period's index in the cycle
  bool entered_ = false;  // a contact entry seen since the cycle began
  int first_open_ = -1;   // the approach of a contact in progress at the cycle's start
};

}  // namespace

OrbitExtent orbit_extent(const Model& model, const IntegratorOptions& integration, const State& y, int n,
                         IntegrationCounters& counters) {
  OrbitExtent e;
  const auto integ = make_integrator(model, integration);
  State u = y;
  integ->reset(u);
  ExtentObserver obs(model, n);
  for (int i = 0; i < n; ++i) {
    e.strobe.push_back(Model::to_physical(u));
    obs.begin_period(i);
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
  obs.finish();
  e.contacts = obs.contacts;
  e.graze_gap = obs.graze_gap;
  e.approaches = std::move(obs.approaches);
  return e;
}

const Approach* nearest_approach(const OrbitExtent& e, double phase) {
  const Approach* best = nullptr;
  double best_d = 2.0;
  for (const Approach& a : e.approaches) {
    const double d = std::abs(a.phase - phase), circular = std::min(d, 1.0 - d);
    if (circular < best_d) best_d = circular, best = &a;
  }
  return best;
}

const Approach* touching_approach(const OrbitExtent& e) {
  const Approach* best = nullptr;
  for (const Approach& a : e.approaches)
    if (!best || std::abs(a.clearance) < std::abs(best->clearance)) best = &a;
  return best;
}

}  // namespace vibromap
