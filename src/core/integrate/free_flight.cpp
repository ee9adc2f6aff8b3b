#include "vibromap/core/integrate/free_flight.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace vibromap {

namespace {
constexpr double kMaxCondition = 1e8;  // of the eigenvector matrix V
constexpr int kNewtonIterations = 4;   // refinement of a bracketed entry
using cd = std::complex<double>;

// e^z for the exponents met here (finite, real part <= 0 or small): std::exp(complex) without
// the special-case handling of infinities and overflow, which cost as much as the sine and
// cosine themselves in find_entry (perf: __cexp 4 % of a census beside sincos 15 %).
inline cd exp_of(cd z) {
  const double r = std::exp(z.real());
  if (z.imag() == 0.0) return {r, 0.0};
  return {r * std::cos(z.imag()), r * std::sin(z.imag())};
}
// e^{i theta}.
inline cd cis(double theta) { return {std::cos(theta), std::sin(theta)}; }
}  // namespace

FreeFlight::System::System(const Model& m) : omega(m.parameters().omega), phi0(m.parameters().phi0) {
  const Parameters& p = m.parameters();
  const double m1 = p.m1, m2 = p.m2;
  // The rows of system.hpp's rhs without the contact force.
  A << 0, 0, 1, 0,                                                         //
      0, 0, 0, 1,                                                          //
      -m.k1() / m1, -m.k2() / m1, -m.c1() / m1, -m.c2() / m1,              //
      -m.k1() / m1, -m.k2() / m1 - m.k2() / m2, -m.c1() / m1, -m.c2() / m1 - m.c2() / m2;
  b = State(0, 0, force_amplitude(p) / m1, force_amplitude(p) / m1);
  c = State(0, 0, -m.k2() * p.D / m1, -m.k2() * p.D / m1 - m.k2() * p.D / m2);
  // Entry tolerance on z: a few ulps of the motion's length scale.
  z_tol = 1e-13 * motion_length(p);
}

bool FreeFlight::describes(const Model& model) const { return System(model) == sys_; }

FreeFlight::FreeFlight(const Model& m) : sys_(m) {
  const State& b = sys_.b;
  const State& c = sys_.c;
  const Eigen::EigenSolver<Eigen::Matrix4d> es(sys_.A);
  if (es.info() != Eigen::Success) return;
  V_ = es.eigenvectors();
  lambda_ = es.eigenvalues();
  // Eigen gives a complex pair of a real matrix as adjacent, exactly conjugate eigenvalues
  // and eigenvectors: the second exponential of a pair is the conjugate of the first.
  for (int j = 1; j < 4; ++j)
    if (lambda_[j].imag() != 0.0 && lambda_[j] == std::conj(lambda_[j - 1]) && conjugate_of_[j - 1] < 0 &&
        V_.col(j) == V_.col(j - 1).conjugate())
      conjugate_of_[j] = j - 1;
  const Eigen::PartialPivLU<Eigen::Matrix4cd> lu(V_);
  V_inv_ = lu.inverse();
  const double cond = V_.cwiseAbs().rowwise().sum().maxCoeff() * V_inv_.cwiseAbs().rowwise().sum().maxCoeff();
  if (!(cond < kMaxCondition)) return;
  for (int j = 0; j < 4; ++j)
    if (lambda_[j].real() > 1e-12 * std::abs(lambda_[j])) return;  // a growing mode: no bound on z''
  const Eigen::Matrix4cd M = cd(0, sys_.omega) * Eigen::Matrix4cd::Identity() - sys_.A.cast<cd>();
  const Eigen::FullPivLU<Eigen::Matrix4cd> lu_m(M);
  if (!lu_m.isInvertible() || lu_m.rcond() < 1e-12) return;  // resonant forcing of an undamped mode
  amp_ = lu_m.solve(b.cast<cd>());
  if (c.isZero()) {
    constant_.setZero();
  } else {
    const Eigen::FullPivLU<Eigen::Matrix4d> lu_a(sys_.A);
    if (!lu_a.isInvertible()) return;
    constant_ = -lu_a.solve(c);
  }
  forcing_z2_ = sys_.omega * sys_.omega * std::abs(amp_[1]);
  const Vec4c mu = modal_exp(2.0 * std::numbers::pi / sys_.omega);  // Parameters::period()
  multipliers_.assign(mu.data(), mu.data() + 4);
  std::sort(multipliers_.begin(), multipliers_.end(), [](cd x, cd y) {
    return std::abs(x) != std::abs(y) ? std::abs(x) > std::abs(y) : x.imag() > y.imag();
  });
  valid_ = amp_.allFinite() && constant_.allFinite() && V_inv_.allFinite();
}

State FreeFlight::particular(double tau) const { return particular_at(cis(sys_.omega * tau + sys_.phi0)); }

State FreeFlight::particular_at(std::complex<double> forcing) const { return (amp_ * forcing).real() + constant_; }

FreeFlight::Vec4c FreeFlight::modal_exp(double dt) const {
  Vec4c e;
  for (int j = 0; j < 4; ++j) e[j] = conjugate_of_[j] >= 0 ? std::conj(e[conjugate_of_[j]]) : exp_of(lambda_[j] * dt);
  return e;
}

State FreeFlight::propagate(double tau0, const State& u0, double tau1) const {
  return propagate(modes(tau0, u0), tau0, tau1);
}

FreeFlight::Modes FreeFlight::modes(double tau0, const State& u0) const {
  return V_inv_ * (u0 - particular(tau0)).cast<cd>();
}

State FreeFlight::propagate(const Modes& alpha, double tau0, double tau1) const {
  return state_at(alpha, modal_exp(tau1 - tau0), cis(sys_.omega * tau1 + sys_.phi0));
}

State FreeFlight::state_at(const Modes& alpha, const Modes& exponentials, std::complex<double> forcing) const {
  const Vec4c modal = exponentials.cwiseProduct(alpha);
  return (V_ * modal).real() + particular_at(forcing);
}

Eigen::Matrix4d FreeFlight::transition(double dt) const {
  return (V_ * modal_exp(dt).asDiagonal() * V_inv_).real();
}

bool FreeFlight::never_enters(double tau0, const State& u0) const {
  const Vec4c alpha = modes(tau0, u0);
  double bound = constant_[1] + std::abs(amp_[1]);
  double size = std::abs(constant_[1]) + std::abs(amp_[1]);
  for (int j = 0; j < 4; ++j) {
    const double a = std::abs(V_(1, j) * alpha[j]);
    bound += a;
    size += a;
  }
  // Below the entry tolerance by more than the rounding of the sum.
  return bound + sys_.z_tol + 1e-12 * size < 0.0;
}

std::optional<double> FreeFlight::find_entry(double tau0, const State& u0, double tau1) const {
  Search last;
  return search_entry(tau0, u0, tau1, last);
}

FreeFlight::Flight FreeFlight::fly(double tau0, const State& u0, double tau1) const {
  Search last;
  Flight f;
  f.entry = search_entry(tau0, u0, tau1, last);
  f.alpha = last.alpha;
  const double end = f.entry ? *f.entry : tau1;
  // propagate(f.alpha, tau0, end), taking what the search computed at the same arguments.
  f.u = state_at(f.alpha, end - tau0 == last.s ? last.modal : modal_exp(end - tau0),
                 tau0 + last.s == end ? last.forcing : cis(sys_.omega * end + sys_.phi0));
  return f;
}

std::optional<double> FreeFlight::search_entry(double tau0, const State& u0, double tau1, Search& last) const {
  last.alpha = modes(tau0, u0);
  const Vec4c& alpha = last.alpha;
  // z, w = z' and the bound M >= |z''| from the modal amplitudes (|e^{lambda s}| <= 1).
  Vec4c cz, cw;
  double M = forcing_z2_;
  for (int j = 0; j < 4; ++j) {
    cz[j] = V_(1, j) * alpha[j];
    cw[j] = cz[j] * lambda_[j];
    M += std::abs(cw[j] * lambda_[j]);
  }
  const cd amp_z = amp_[1];
  auto zw = [&](double s, double& z, double& w) {
    last.s = s;
    last.modal = modal_exp(s);
    last.forcing = cis(sys_.omega * (tau0 + s) + sys_.phi0);
    const Vec4c& e = last.modal;
    const cd zs = (cz.array() * e.array()).sum(), ws = (cw.array() * e.array()).sum();
    const cd ef = amp_z * last.forcing;
    z = zs.real() + ef.real() + constant_[1];
    w = ws.real() + (cd(0, sys_.omega) * ef).real();
  };
  const double s_end = tau1 - tau0;
  double s = 0.0, z = 0.0, w = 0.0;
  zw(s, z, w);
  for (;;) {
    if (z >= -sys_.z_tol && w > 0.0) {
      // At or within tolerance below a crossing: Newton on the closed form. Once a step does
      // not move s forward (z >= 0 already), the following ones would repeat it.
      for (int i = 0; i < kNewtonIterations && w > 0.0; ++i) {
        const double next = std::max(s, s - z / w);
        if (next == s) break;
        s = next;
        zw(s, z, w);
      }
      return s <= s_end ? std::optional<double>(tau0 + s) : std::nullopt;
    }
    // The largest step over which z + w h + M h^2 / 2 stays <= 0 (z < 0 here, or a graze
    // that is leaving: then the step only has to clear the tolerance band).
    const double zz = std::min(z, -sys_.z_tol);
    const double h = M > 0.0 ? (-w + std::sqrt(w * w - 2.0 * M * zz)) / M : (w > 0.0 ? -zz / w : s_end);
    if (s >= s_end) return std::nullopt;
    s = std::min(s_end, s + std::max(h, 1e-15 * (std::abs(tau0) + s_end)));
    zw(s, z, w);
    if (s >= s_end && !(z >= -sys_.z_tol && w > 0.0)) return std::nullopt;
  }
}

}  // namespace vibromap
