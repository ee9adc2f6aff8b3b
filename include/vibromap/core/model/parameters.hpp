#pragma once
// Physical parameters of one point of the two-body vibro-impact system of docs/model.md.
//
// Parameters holds the values *as the user gave them*: a spring is given either by its
// stiffness k (N/m) or by its partial natural frequency omega = sqrt(k/m) (rad/s), a damper
// either by its coefficient c (N s/m) or by its ratio xi = c/(2 m omega). The form matters
// when another parameter changes (a sweep over m2 with xi2 given keeps xi2, not c2).
// The Model (system.hpp) turns these into the coefficients of the equations of motion.
//
// Defaults: Table 1 of the source paper with the calibration of docs/model.md (xi = 0.01,
// D = 0.05 m, nu = 0.3, lambda = 1, phi0 = 0).

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vibromap/core/model/contact_law.hpp"

namespace vibromap {

// A spring given by stiffness (N/m) or by partial natural frequency sqrt(k/m) (rad/s).
struct Spring {
  enum class Form { stiffness, frequency };
  Form form = Form::frequency;
  double value = 0.0;
  double stiffness(double mass) const { return form == Form::stiffness ? value : mass * value * value; }
};

// A damper given by coefficient c (N s/m) or by ratio xi = c / (2 m omega) (-).
struct Damper {
  enum class Form { coefficient, ratio };
  Form form = Form::ratio;
  double value = 0.0;
  double coefficient(double mass, double stiffness) const;
};

struct Parameters {
  // [system]
  double m1 = 1000.0;                               // main body mass, kg
  double m2 = 100.0;                                // attached body mass, kg
  Spring spring1{Spring::Form::frequency, 6.283};   // k1 (N/m) or omega1 (rad/s)
  Spring spring2{Spring::Form::frequency, 5.646};   // k2 (N/m) or omega2 (rad/s)
  Damper damper1{Damper::Form::ratio, 0.01};        // c1 (N s/m) or xi1 (-)
  Damper damper2{Damper::Form::ratio, 0.01};        // c2 (N s/m) or xi2 (-)
  double D = 0.05;                                  // clearance at rest, m
  // [contact]
  double E1 = 2.099e11;                             // Young's modulus of body 1, Pa
  double E2 = 2.099e11;                             // Young's modulus of body 2, Pa
  double nu1 = 0.3;                                 // Poisson ratio of body 1, -
  double nu2 = 0.3;                                 // Poisson ratio of body 2, -
  double R1 = 2.0;                                  // radius of curvature of body 1, m
  double R2 = 2.0;                                  // radius of curvature of body 2, m
  double q = 0.319;                                 // Hertz shape coefficient (circular contact), -
  ContactLawKind law = ContactLawKind::hertz;       // contact law (contact_law.hpp), elastic Hertz by default
  double restitution = 1.0;                         // restitution e the law's damping is calibrated for, (0, 1]
  std::optional<double> damping;                    // damping factor chi given directly (replaces the calibration), -
  // [forcing]
  double F0 = 500.0;                                // force amplitude, N
  double omega = 7.23;                              // forcing frequency, rad/s
  double lambda = 1.0;                              // amplitude factor, -
  double phi0 = 0.0;                                // phase, rad
  // [initial] x1, x2 (m), v1, v2 (m/s); unset = the rest state (0, D, 0, 0).
  std::optional<Eigen::Vector4d> initial;

  Eigen::Vector4d initial_state() const;
  double period() const;                            // forcing period T = 2 pi / omega, s
  double damping_factor() const;                    // chi: `damping` when given, else law's chi(restitution)
};

// The forcing frequency against the system's own: omega / omega_n, omega_n the fastest undamped
// natural frequency of the two bodies on their springs without contact (the larger root of
// det(K - omega^2 M) = 0, M = diag(m1, m2), K = [[k1 + k2, -k2], [-k2, k2]]), must lie in
// [kMinFrequencyRatio, kMaxFrequencyRatio]. Below, one forcing period holds more than 10^4
// oscillations of the fastest mode, and the closed-form free flight's search for contact
// steps through each (omega = 1e-9 rad/s on Table 1: 10^10 of them, a run that never ends);
// above, the forcing is 10^4 times faster than anything the springs can follow (omega = 1e308:
// a period of 6e-308 s). The paper's tables sit at 1.04 and 1.08, jobs/ spans 7.2e-4
// (jobs/study/extremes.toml) to 1.79; a ratio is the same whatever the units. Every one of m1,
// m2, k1 (omega1), k2 (omega2) and omega moves omega / omega_n one way only (omega_n^2 is the
// largest Rayleigh quotient of K against M), so over a grid or a box its extremes are at the
// corners.
inline constexpr double kMinFrequencyRatio = 1e-4;
inline constexpr double kMaxFrequencyRatio = 1e4;
// omega_n above, rad/s.
double fastest_natural_frequency(const Parameters& p);
// The same for the dampers: the fastest decay rate of the bodies on their dampers alone, the
// largest eigenvalue of M^-1 C, C = [[c1 + c2, -c2], [-c2, c2]], 1/s. It must be at most
// kMaxFrequencyRatio times omega: each decay time is a few steps of the explicit integrators, so
// above that a forcing period costs more than 10^4 steps (xi1 = 1e12 on Table 1: 10^13 a period,
// a run that spends its whole step budget in the first one). Table 1's is 0.02 omega.
double fastest_damping_rate(const Parameters& p);
// Empty when omega / omega_n lies in that range and the damping rate is within its bound, else
// the one-line reason with the range it allows.
std::string frequency_ratio_error(const Parameters& p);

// The motion's scales: the force amplitude lambda F0 (N); the length L = max(D, lambda F0 / k1,
// 1 nm) (m), the static deflection under that force or the clearance, whichever is larger; and
// the speed omega L (m/s). Every state scale is built from these (the steady-state and shooting
// norms, StateScale; the census box; the least entry speed of a damped law; free flight's
// contact tolerance).
double force_amplitude(const Parameters& p);
double motion_length(const Parameters& p);
double motion_speed(const Parameters& p);

// The scales the model derives from the keys must be finite at a valid point (the stiffness k1
// also > 0): k1, k2, c1, c2, T, lambda F0, L, omega L, omega_n, the fastest damping rate, the
// contact's K and its damping factor chi. Each is listed once in derived_scales.cpp with the
// keys it is derived from. Empty when every one is, else the refusal of the key that made the
// first one overflow, in the key table's form with the bound that key must keep
// ("[forcing] lambda = 1.7976931348623157e+308: makes the force amplitude lambda F0 (N) not
// finite; with the other keys as given it must be at most 3.59e+305").
std::string derived_scale_error(const Parameters& p);

// The point's checks: every key of [system], [contact], [forcing] and [initial] against the key
// table (keys.hpp), in its refusal's words ("[system] m2 = -5: must be > 0 (kg)"), then the
// rules that combine keys (a damping factor needs a damped law; derived_scale_error's, then
// frequency_ratio_error's, once the rest holds). Empty when the point is valid. Defined with the key table (keys.cpp).
std::vector<std::string> validate(const Parameters& p);

}  // namespace vibromap
