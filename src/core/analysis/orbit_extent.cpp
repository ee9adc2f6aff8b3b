#include "vibromap/core/analysis/orbit_extent.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>

namespace vibromap {
namespace {

constexpr int kSamples = 64;        // per free-flight step (the closed form spans up to a period)
constexpr int kContactSamples = 8;  // per contact step (a short part of one impact)
constexpr int kGoldenSteps = 60;   // golden-section iterations: the bracket shrinks by 0.618^60 ~ 3e-13

// The largest of f over [a, b] near the sample at `at` (its neighbours bracket it).
double refine_max(const std::function<double(double)>& f, double a, double b) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  for (int i = 0; i < kGoldenSteps && b - a > 0.0; ++i) {
    if (fc >= fd) {
      b = d, d = c, fd = fc;
      c = b - g * (b - a);
      fc = f(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + g * (b - a);
      fd = f(d);
    }
  }
  return std::max(fc, fd);
}

// Whether the maximum of a smooth f over [t_l, t_r] can exceed `best`, from its samples f_l <= f_m
// >= f_r at t_l < t_m < t_r, equally spaced by h: near a maximum f is a parabola, whose peak lies at
// most (f_m - min(f_l, f_r)) / 4 above f_m (a h^2 / 4 against a h^2 at least); twice that margin
// is kept. A step whose samples cannot beat the best so far is not refined.
bool could_exceed(double f_m, double f_l, double f_r, double best) {
  return f_m + 0.5 * (f_m - std::min(f_l, f_r)) >= best;
}

class ExtentObserver final : public Observer {
 public:
  void on_step(const StepView& step) override {
    if (!(step.tau1 > step.tau0)) return;
    const auto physical = [&](double tau) { return Model::to_physical(step.eval(tau)); };
    // f_k(tau) for x1, x2 and -(x2 - x1): each maximised.
    const std::function<double(const Eigen::Vector4d&)> parts[3] = {
        [](const Eigen::Vector4d& x) { return x[0]; }, [](const Eigen::Vector4d& x) { return x[1]; },
        [](const Eigen::Vector4d& x) { return x[0] - x[1]; }};
    double* best[3] = {&x1_max, &x2_max, &overlap_max};
    const int samples = step.mode == ContactMode::contact ? kContactSamples : kSamples;
    std::array<double, kSamples + 1> taus{};
    std::array<Eigen::Vector4d, kSamples + 1> xs;
    for (int i = 0; i <= samples; ++i) {
      taus[static_cast<std::size_t>(i)] = step.tau0 + (step.tau1 - step.tau0) * i / samples;
      xs[static_cast<std::size_t>(i)] = physical(taus[static_cast<std::size_t>(i)]);
    }
    for (int k = 0; k < 3; ++k) {
      int at = 0;
      for (int i = 1; i <= samples; ++i)
        if (parts[k](xs[static_cast<std::size_t>(i)]) > parts[k](xs[static_cast<std::size_t>(at)])) at = i;
      double value = parts[k](xs[static_cast<std::size_t>(at)]);
      // An interior maximum is refined between its neighbours when it can beat the best so far.
      if (at > 0 && at < samples &&
          could_exceed(value, parts[k](xs[static_cast<std::size_t>(at - 1)]), parts[k](xs[static_cast<std::size_t>(at + 1)]),
                       *best[k]))
        value = std::max(value, refine_max([&](double tau) { return parts[k](physical(tau)); },
                                           taus[static_cast<std::size_t>(at - 1)], taus[static_cast<std::size_t>(at + 1)]));
      *best[k] = std::max(*best[k], value);
    }
    // z = x1 - x2: its interior maxima, the closest approaches in free flight and the deepest
    // penetration in contact.
    const auto z = [&](double tau) { return step.eval(tau)[1]; };
    for (int i = 1; i < samples; ++i) {
      const double zi = xs[static_cast<std::size_t>(i)][0] - xs[static_cast<std::size_t>(i)][1];
      const double zl = xs[static_cast<std::size_t>(i - 1)][0] - xs[static_cast<std::size_t>(i - 1)][1];
      const double zr = xs[static_cast<std::size_t>(i + 1)][0] - xs[static_cast<std::size_t>(i + 1)][1];
      if (!(zi >= zl && zi >= zr)) continue;
      if (step.mode == ContactMode::contact ? !could_exceed(zi, zl, zr, contact_peak) : !could_exceed(zi, zl, zr, -graze_gap))
        continue;
      const double peak = std::max(zi, refine_max(z, taus[static_cast<std::size_t>(i - 1)], taus[static_cast<std::size_t>(i + 1)]));
      if (step.mode == ContactMode::contact)
        contact_peak = std::max(contact_peak, peak);
      else if (peak < 0.0)
        graze_gap = std::min(graze_gap, -peak);
    }
    if (step.mode == ContactMode::contact)
      contact_peak = std::max({contact_peak, z(step.tau0), z(step.tau1)});
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
};

}  // namespace

OrbitExtent orbit_extent(const Model& model, const IntegratorOptions& integration, const State& y, int n,
                         IntegrationCounters& counters) {
  OrbitExtent e;
  const auto integ = make_integrator(model, integration);
  State u = y;
  integ->reset(u);
  ExtentObserver obs;
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
