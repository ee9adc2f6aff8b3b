#pragma once
// Internal: the Dormand-Prince 5(4) stepping engine shared by the dopri5 integrator and the
// contact phase of the hybrid integrator.
//
// Tableau, error coefficients and Shampine's dense output as in Hairer's DOPRI5 (Hairer,
// Norsett, Wanner, "Solving ODEs I", 2nd ed., Table II.5.2 and II.6); PI step-size control
// with beta = 0.04 (ibid., IV.2). The engine integrates Y = [u | Phi] (4 x Cols): column 0 is
// the state, columns 1..4 (Cols = 5) the variational solution Phi' = J(u) Phi, integrated
// with the same stages (internal differentiation: Phi is the exact derivative of the
// numerical flow). Error control and events look at the state only.
//
// The contact mode is frozen within a step; entry/exit are located on the dense output of
// the state and the step is redone to end exactly there, with z set to 0. The Hertz force
// vanishes at z = 0, so the vector field is continuous across the switching surface and the
// saltation matrix at an event is the identity: Phi needs no jump.
//
// A dissipative contact law's force depends on v_in, the approach rate at the contact's
// entry, which the engine remembers from the entry event. v_in is a function of the entry
// state, so in contact Phi' = J Phi + (df/dv_in) g with the row g = d v_in / d u0, set at the
// entry: w_e = w(t_e(u0)) with t_e where z = 0, so g = Phi_w - (w'/w) Phi_z at the event
// (implicit-function theorem; w = z' at the entry). A contact in progress at a restart has
// no entry: its v_in is Model::entry_speed(u) and g that function's gradient.

#include <algorithm>
#include <array>
#include <cmath>

#include "vibromap/core/integrate/cancel.hpp"
#include "vibromap/core/integrate/event_locator.hpp"
#include "vibromap/core/integrate/integrator.hpp"

namespace vibromap::detail {

namespace dp5 {
constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
constexpr double a21 = 1.0 / 5;
constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                 a65 = -5103.0 / 18656;
constexpr double a71 = 35.0 / 384, a73 = 500.0 / 1113, a74 = 125.0 / 192, a75 = -2187.0 / 6784, a76 = 11.0 / 84;
constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                 e6 = 22.0 / 525, e7 = -1.0 / 40;
constexpr double d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799,
                 d4 = -10690763975.0 / 1880347072, d5 = 701980252875.0 / 199316789632,
                 d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;
constexpr double kSafety = 0.9, kBeta = 0.04, kFacMin = 0.2, kFacMax = 10.0;
constexpr double kExpo1 = 0.2 - kBeta * 0.75;
constexpr double kMinStepFraction = 1e-13;  // smallest step, as a fraction of T
constexpr double kPhiMinStepFraction = 1e-9;  // below this step (fraction of T) Phi is not error-controlled
}  // namespace dp5

template <int Cols>
using Augmented = Eigen::Matrix<double, 4, Cols>;

// Shampine's continuous extension of one step, in Hairer's form
// y(theta) = r1 + theta (r2 + (1-theta) (r3 + theta (r4 + (1-theta) r5))); eval gives the state.
template <int Cols>
class Dp5Dense final : public DenseOutput {
 public:
  void prepare(double tau0, double h, const Augmented<Cols>& y0, const Augmented<Cols>& y1,
               const Augmented<Cols>* k) {
    using namespace dp5;
    tau0_ = tau0;
    h_ = h;
    const State dy = y1.col(0) - y0.col(0);
    const State bspl = h * k[0].col(0) - dy;
    r1_ = y0.col(0);
    r2_ = dy;
    r3_ = bspl;
    r4_ = dy - h * k[6].col(0) - bspl;
    r5_ = h * (d1 * k[0].col(0) + d3 * k[2].col(0) + d4 * k[3].col(0) + d5 * k[4].col(0) + d6 * k[5].col(0) +
               d7 * k[6].col(0));
  }
  State eval(double tau) const override {
    const double th = (tau - tau0_) / h_;
    const double th1 = 1.0 - th;
    return r1_ + th * (r2_ + th1 * (r3_ + th * (r4_ + th1 * r5_)));
  }
  // Whether z may reach 0 within the step when it starts on the side of `mode` (z > 0 in
  // contact, z < 0 in free flight). In the form z(theta) = r1 + theta r2 + theta(1-theta) r3
  // + theta^2(1-theta) r4 + theta^2(1-theta)^2 r5 each basis function lies in [0, m] on
  // [0, 1], m = 1, 1/4, 4/27, 1/16, which bounds z over the step; false is certain (no
  // event in the step), true sends the step to the event locator.
  bool z_may_reach_zero(ContactMode mode) const {
    const double s = mode == ContactMode::contact ? 1.0 : -1.0;  // s z > 0 away from the surface
    const double lower = std::min(s * r1_[1], s * (r1_[1] + r2_[1])) + std::min(0.0, s * r3_[1]) / 4.0 +
                         std::min(0.0, s * r4_[1]) * (4.0 / 27.0) + std::min(0.0, s * r5_[1]) / 16.0;
    return !(lower > 0.0);
  }

 private:
  double tau0_ = 0.0, h_ = 1.0;
  State r1_, r2_, r3_, r4_, r5_;
};

template <int Cols>
class Dp5Engine {
 public:
  using Y = Augmented<Cols>;

  Dp5Engine(const Model& model, const IntegratorOptions& options, IntegrationCounters& counters)
      : model_(model), opt_(options), counters_(counters), T_(model.period()),
        dissipative_(model.contact().dissipative()) {
    const double w = model.parameters().omega;
    atol_ << opt_.atol, opt_.atol, opt_.atol * w, opt_.atol * w;
    h_max_ = opt_.max_step * T_;
    h_min_ = dp5::kMinStepFraction * T_;
  }

  void restart() {
    fsal_valid_ = false;
    log_err_old_ = kLogErrFloor;
    after_reject_ = false;
  }
  // Starts from state u (Phi = I) in mode m: a contact in progress gets v_in from the state.
  void begin(const State& u, ContactMode m) {
    set_mode(m);
    restart();
    v_in_ = model_.entry_speed(u);
    entry_gradient_ = dissipative_ && m == ContactMode::contact ? model_.entry_speed_gradient(u)
                                                                : Eigen::RowVector4d::Zero();
    g_ = entry_gradient_;
    fresh_ = true;
  }
  // Phi restarts at I here: v_in's sensitivity is the state's gradient right after begin(),
  // else zero (v_in is then a remembered constant, not a function of the new u0).
  void reset_entry_sensitivity() { g_ = fresh_ ? entry_gradient_ : Eigen::RowVector4d::Zero(); }
  // A contact entry at (tau, y) found elsewhere (the hybrid integrator's free flight).
  void enter_contact(double tau, const Y& y) {
    set_mode(ContactMode::contact);
    remember_entry(tau, y);
    hint_contact_start(y.col(0));
  }
  double entry_speed() const { return v_in_; }
  ContactMode mode() const { return mode_; }
  void set_rtol(double rtol) { opt_.rtol = rtol; }
  void set_max_steps(long max_steps) { opt_.max_steps = max_steps; }
  void set_mode(ContactMode m) {
    if (m != mode_) fsal_valid_ = false;
    mode_ = m;
  }
  // After an entry found elsewhere: start the contact with a step fit for it.
  void hint_contact_start(const State& u) { h_ = h_ > 0.0 ? std::min(h_, contact_step_hint(u)) : contact_step_hint(u); }

  // Integrates y from tau towards tau_end (<= T) in the current mode. Returns at tau_end, or
  // right after the first contact event when stop_at_event (then *event is set), or on
  // failure. tau is updated.
  IntegrationStatus advance(Y& y, double& tau, double tau_end, long period, Observer& obs, bool stop_at_event,
                            bool* event) {
    fresh_ = false;
    if (v_in_ <= 0.0) v_in_ = model_.entry_speed(y.col(0));  // never begin(): no entry known
    return run(y, tau, tau_end, period, obs, true, stop_at_event, event);
  }

 private:
  // The stepping loop; with locate_events false it steps to tau_end in the current mode.
  IntegrationStatus run(Y& y, double& tau, double tau_end, long period, Observer& obs, bool locate_events,
                        bool stop_at_event, bool* event) {
    if (h_ <= 0.0) h_ = std::min(h_max_, T_ / 64.0);
    if (!fsal_valid_) {
      rhs(tau, y, k_[0]);
      fsal_valid_ = true;
    }
    Y y_new;
    while (tau < tau_end) {
      const long taken = counters_.steps + counters_.rejected;
      if (taken >= opt_.max_steps) return IntegrationStatus::step_limit;
      poll_cancel(taken);
      const double remaining = tau_end - tau;
      double h = std::min(h_, h_max_);
      const bool last = h >= remaining * (1.0 - 1e-12);
      if (last) h = remaining;
      const double err = trial(tau, y, h, y_new);
      if (!std::isfinite(err) || err > 1.0) {
        ++counters_.rejected;
        const double fac =
            std::isfinite(err) ? std::min(1.0 / dp5::kFacMin, std::pow(err, dp5::kExpo1) / dp5::kSafety) : 10.0;
        h_ = h / fac;
        after_reject_ = true;
        if (h_ < h_min_) return std::isfinite(err) ? IntegrationStatus::step_underflow : IntegrationStatus::non_finite;
        continue;
      }
      dense_.prepare(tau, h, y, y_new, k_.data());
      const double step_end = last ? tau_end : tau + h;
      const auto found = locate_events && dense_.z_may_reach_zero(mode_)
                             ? locate_contact_event(dense_, tau, step_end, mode_, 4e-16 * T_)
                             : std::nullopt;
      if (found) {
        const IntegrationStatus to_event = finish_at_event(tau, found->tau, y, period, obs);
        if (to_event != IntegrationStatus::ok) return to_event;
        if (stop_at_event) {
          *event = true;
          return IntegrationStatus::ok;
        }
        continue;
      }
      obs.on_step({period, tau, step_end, mode_, &dense_});
      y = y_new;
      tau = step_end;
      k_[0] = k_[6];
      ++counters_.steps;
      control(err, h, last);
    }
    return IntegrationStatus::ok;
  }

  void rhs(double tau, const Y& y, Y& dy) { rhs_forced(model_.forcing(tau), y, dy); }
  void rhs_forced(double F, const Y& y, Y& dy) {
    State f;
    model_.rhs_forced(F, y.col(0), mode_, v_in_, f);
    dy.col(0) = f;
    if constexpr (Cols > 1) {
      dy.template rightCols<Cols - 1>() = model_.jacobian(y.col(0), mode_, v_in_) * y.template rightCols<Cols - 1>();
      if (dissipative_ && mode_ == ContactMode::contact)
        dy.template rightCols<Cols - 1>() += model_.entry_speed_column(y.col(0), mode_, v_in_) * g_;
    }
    ++counters_.rhs_evals;
  }

  // v_in and its sensitivity g = Phi_w - (w'/w) Phi_z at an entry (see the file comment);
  // w' is the free vector field's (the contact force is 0 at z = 0).
  void remember_entry(double tau, const Y& y) {
    const State u = y.col(0);
    v_in_ = model_.entry_speed(u);
    if constexpr (Cols > 1) {
      g_.setZero();
      if (!dissipative_ || !(u[3] > model_.min_entry_speed())) return;
      State f;
      model_.rhs_forced(model_.forcing(tau), u, ContactMode::free, v_in_, f);
      const auto phi = y.template rightCols<4>();
      g_ = phi.row(3) - (f[3] / u[3]) * phi.row(1);
    }
  }

  // One trial step of size h from (tau, y): fills k_[1..6] and y_new, returns the scaled
  // RMS error of the state.
  double trial(double tau, const Y& y, double h, Y& y_new) {
    using namespace dp5;
    Y* k = k_.data();
    std::array<double, 5> F;  // the forcing at the stages (6 and 7 are both at tau + h)
    model_.forcing_at(tau, h, std::array<double, 5>{c2, c3, c4, c5, 1.0}, F);
    Y s;
    s = y + h * (a21 * k[0]);
    rhs_forced(F[0], s, k[1]);
    s = y + h * (a31 * k[0] + a32 * k[1]);
    rhs_forced(F[1], s, k[2]);
    s = y + h * (a41 * k[0] + a42 * k[1] + a43 * k[2]);
    rhs_forced(F[2], s, k[3]);
    s = y + h * (a51 * k[0] + a52 * k[1] + a53 * k[2] + a54 * k[3]);
    rhs_forced(F[3], s, k[4]);
    s = y + h * (a61 * k[0] + a62 * k[1] + a63 * k[2] + a64 * k[3] + a65 * k[4]);
    const double F_end = F[4];
    rhs_forced(F_end, s, k[5]);
    y_new = y + h * (a71 * k[0] + a73 * k[2] + a74 * k[3] + a75 * k[4] + a76 * k[5]);
    rhs_forced(F_end, y_new, k[6]);
    const Y err = h * (e1 * k[0] + e3 * k[2] + e4 * k[3] + e5 * k[4] + e6 * k[5] + e7 * k[6]);
    const Eigen::Array4d scale = atol_ + opt_.rtol * y.col(0).array().abs().max(y_new.col(0).array().abs());
    const double state_err = std::sqrt((err.col(0).array() / scale).square().mean());
    if constexpr (Cols > 1) {
      // The variational solution is error-controlled too: its coefficient dFc/dz ~ sqrt(z) is
      // rougher in time at contact entry and exit than the state, and a step sized for the
      // state alone leaves Phi wrong there. Phi_ij has the units of u_i / u0_j; relative
      // accuracy: rtol times (|Phi_ij| + the natural size atol_i / atol_j). Below
      // kPhiMinStep (a grazing contact makes sqrt(z) steep over a vanishing interval) only
      // the state is controlled, so Phi can never drive the step size to underflow.
      if (h < dp5::kPhiMinStepFraction * T_) return state_err;
      double sum = 0.0;
      for (int j = 1; j < Cols; ++j) {
        const Eigen::Array4d phi_scale =
            opt_.rtol * (atol_ / atol_[j - 1] + y.col(j).array().abs().max(y_new.col(j).array().abs()));
        sum += (err.col(j).array() / phi_scale).square().sum();
      }
      return std::max(state_err, std::sqrt(sum / (4.0 * (Cols - 1))));
    }
    return state_err;
  }

  void control(double err, double h, bool last) {
    using namespace dp5;
    // err^kExpo1 / err_old^kBeta as one exponential of logarithms (the step's cost is small
    // enough that two pow() calls were a tenth of a period's time).
    const double log_err = std::log(err);
    double fac = std::clamp(std::exp(kExpo1 * log_err - kBeta * log_err_old_) / kSafety, 1.0 / kFacMax, 1.0 / kFacMin);
    if (after_reject_) fac = std::max(fac, 1.0);  // no growth right after a rejection (Hairer's DOPRI5)
    after_reject_ = false;
    log_err_old_ = std::max(log_err, kLogErrFloor);
    // Keep the controller's proposal when the step was cut to land on the interval's end.
    h_ = last ? std::max(h_, h / fac) : h / fac;
  }

  // Integrates from tau to the located event with error-controlled steps that end exactly
  // there (the step that found it is discarded), sets z = 0 (the event's residual is within
  // the root tolerance), switches the mode and reports the event; tau becomes the event time.
  // Controlled steps, not one redone step: at the exit the variational coefficient dFc/dz ~
  // sqrt(z) has an infinite slope, and only the error control shrinks the steps into it.
  IntegrationStatus finish_at_event(double& tau, double tau_event, Y& y, long period, Observer& obs) {
    if (tau_event > tau) {
      const IntegrationStatus status = run(y, tau, tau_event, period, obs, false, false, nullptr);
      if (status != IntegrationStatus::ok) return status;
    }
    tau = tau_event;
    y(1, 0) = 0.0;
    const bool entering = mode_ == ContactMode::free;
    mode_ = entering ? ContactMode::contact : ContactMode::free;
    if (entering) remember_entry(tau_event, y);
    ++counters_.events;
    obs.on_event({entering ? ContactEvent::Kind::entry : ContactEvent::Kind::exit, period, tau_event, y.col(0)});
    rhs(tau_event, y, k_[0]);
    if (entering) h_ = std::min(h_, contact_step_hint(y.col(0)));
    return IntegrationStatus::ok;
  }

  // After an entry the contact lasts about 3.2 (m*^2 / (K^2 v))^(1/5) (Hertz impact of two
  // free bodies); starting the contact with a step well below that saves a cascade of
  // rejected steps sized for the free flight.
  double contact_step_hint(const State& u) const {
    const double v = std::abs(u[3]);
    const double K = model_.contact().stiffness();
    if (v <= 0.0 || K <= 0.0) return h_max_;
    const double m = model_.reduced_mass();
    return 3.2 * std::pow(m * m / (K * K * v), 0.2) / 16.0;
  }

  const Model& model_;
  IntegratorOptions opt_;
  IntegrationCounters& counters_;
  double T_;
  bool dissipative_;         // the contact law reads v_in
  double v_in_ = 0.0;        // approach rate at the current contact's entry, m/s
  Eigen::RowVector4d g_ = Eigen::RowVector4d::Zero();               // d v_in / d u0
  Eigen::RowVector4d entry_gradient_ = Eigen::RowVector4d::Zero();  // d entry_speed / du at begin()
  bool fresh_ = false;       // begin() and no step since
  Eigen::Array4d atol_;
  double h_max_, h_min_;
  ContactMode mode_ = ContactMode::free;
  double h_ = 0.0;           // proposed next step, s
  static constexpr double kLogErrFloor = -9.210340371976184;  // log(1e-4): the error's floor in the PI control
  double log_err_old_ = kLogErrFloor;  // log of the previous accepted error (PI control)
  bool after_reject_ = false;  // the last trial was rejected
  bool fsal_valid_ = false;  // k_[0] holds f(tau, y) for the current point and mode
  std::array<Y, 7> k_;
  Dp5Dense<Cols> dense_;
};

}  // namespace vibromap::detail
