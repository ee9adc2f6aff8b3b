#pragma once
// Curves of codimension-one points in two parameters: a fold, period doubling,
// Neimark-Sacker, grazing or level point of a periodic orbit, located on a branch in P
// (continuation.hpp), followed in the plane (P, Q).
//
// The extended system. Unknowns z = (y, P, Q), scaled as the branch scales them (y by the
// motion's length and speed, StateScale; P and Q by the lengths of their intervals), and five
// equations in six unknowns:
//   G(y, P, Q) = (P^n(y; P, Q) - y) / unit = 0     (4: a period-n orbit; the shooting equations)
//   g(y, P, Q) = 0                                  (1: the defining condition of the kind)
// whose solutions form a curve, followed by pseudo-arclength continuation with the branch's own
// corrector and tangent (continuation_problem.hpp: arclength_correct, arclength_tangent) and its
// step control (halving on failure or a turn over kMaxTurn, growth after an easy correction).
// dG/dy is the monodromy (variational equations); dG/dP, dG/dQ and the whole row dg/dz are
// forward differences (step 1e-7 scaled). The defining conditions, chosen because each is a
// plain scalar of the orbit that crosses zero transversally at a generic point of its kind, so
// that the 5 x 6 Jacobian has full rank there and Newton converges quadratically up to the
// differences' error:
//   fold              det(M - I)  (M the monodromy: one multiplier at +1; the plain determinant,
//                     not a bordered test function: regular at a generic fold, where the
//                     multiplier crosses +1 with nonzero speed along the branch)
//   period-doubling   det(M + I)  (a multiplier at -1)
//   neimark-sacker    |mu|^2 - 1 of the complex pair nearest the unit circle (none: the curve stops)
//   grazing           the signed clearance of one tracked approach / length scale: a local
//                     minimum of x2 - x1 over the cycle (orbit_extent.hpp: OrbitExtent::approaches),
//                     the gap of a closest approach in free flight (> 0) or minus the peak
//                     penetration of a contact (< 0), located as a root of the relative velocity
//                     on the dense output. It crosses zero smoothly where that impact appears or
//                     vanishes, whatever the orbit's other contacts do, so every grazing is
//                     followed: a contact-free orbit touching, a further impact appearing on an
//                     orbit with impacts, one of several vanishing. (The global clearance_min,
//                     the condition before, is that only for a contact-free orbit; on one with
//                     another contact it is that contact's penetration, which does not vanish.)
//                     The tracked approach is the one touching at the start (least |clearance|),
//                     then at each point the one whose phase in the n-period cycle is nearest the
//                     previous point's (CurvePoint::phase). For a contact-free orbit that is the
//                     closest approach, i.e. clearance_min: the same curve as before.
//   level:NAME=VALUE  (quantity(orbit) - VALUE) / |VALUE|, the quantity (k_con, T_con, F_max,
//                     z_ratio) measured on the cycle as `run` measures it (measure_orbit)
// A point is accepted when the orbit's scaled residual is within options.tol and |g| within
// CurveOptions::condition_tol (g as scaled above; stored as the point's `residual`).
//
// Codimension-two points: along a curve the other kinds' test functions are watched, det(M - I),
// det(M + I) (sign changes), the number of complex multipliers outside the unit circle and the
// number of contacts per cycle (changes), and on a fold curve the tangent's (P, Q) projection
// reversing (a cusp); each change is located by bisection in arclength to locate_tol and named
// "<curve kind>+<other kind>" ("grazing+fold"), the level kind last ("fold+level:k_con=10").

#include <complex>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "vibromap/core/analysis/continuation/continuation.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"

namespace vibromap {

enum class CurveKind { fold, period_doubling, neimark_sacker, grazing, level };
enum class LevelQuantity { k_con, T_con, F_max, z_ratio };

struct CurveSpec {
  CurveKind kind = CurveKind::fold;
  LevelQuantity quantity = LevelQuantity::k_con;  // level only
  double value = 0.0;                             // level only
  std::string label;  // "fold", "period-doubling", "neimark-sacker", "grazing", "level:k_con=10" (as given)
};
// "fold", "period-doubling", "neimark-sacker", "grazing" or "level:NAME=VALUE" (NAME one of
// k_con, T_con, F_max, z_ratio, VALUE a finite number); the error names what is wrong.
std::optional<CurveSpec> parse_curve_spec(const std::string& text, std::string& error);
// A level quantity of a measured orbit.
double level_value(LevelQuantity q, const PointSummary& s);

// The point (parameters and options) at P = first, Q = second.
using PointAt2 = std::function<std::pair<Parameters, PointOptions>(double P, double Q)>;

struct CurveBox {
  double from = 0.0, to = 1.0;    // P: the branch's interval (either order), P scaled by to - from
  double from2 = 0.0, to2 = 1.0;  // Q: from2 < to2
  std::string key = "P", key2 = "Q";  // for the stop messages
  bool log = false, log2 = false;     // P (Q) is ln of the key's value: the messages print exp(P)
};

struct CurveOptions {
  ContinuationOptions base;       // steps, max_points, max_corrections, tol (the orbit), locate_tol
  double condition_tol = 1e-10;   // |g| of a point (g scaled as in the file comment)
};

struct CurvePoint {
  double param = 0.0, param2 = 0.0;
  Eigen::Vector4d y = Eigen::Vector4d::Zero();     // the orbit's state at a period start, physical
  std::vector<std::complex<double>> multipliers;  // largest |mu| first
  bool stable = false;
  double residual = 0.0;        // |g|, the defining condition
  double orbit_residual = 0.0;  // scaled |P^n(y) - y|
  int contacts = 0;             // per cycle (orbit_extent.hpp)
  double clearance_min = 0.0;   // m
  // Grazing curves: the tracked approach (orbit_extent.hpp), its phase in the cycle and signed
  // clearance (m, ~0 on the curve), and the contacts per cycle besides it.
  double phase = 0.0;
  double approach = 0.0;
  int other_contacts = 0;
};

struct Codim2Point {
  double param = 0.0, param2 = 0.0;
  std::string kind;  // "grazing+fold", "fold+level:k_con=10", "cusp", ...
};

struct Curve {
  CurveSpec spec;
  int n = 1;
  std::vector<CurvePoint> points;  // ordered along the curve
  int start = 0;                   // the index of the located point it was started from
  std::vector<Codim2Point> codim2;
  std::string stop;                // one sentence per direction, joined by "; "
  // Grazing: which kind, at the start: "an impact appears on an orbit with 1 contact per cycle:
  // 2 at higher KEY2, 1 at lower" (or "a contact-free orbit touches: ..."); empty otherwise.
  std::string grazing;
  IntegrationCounters counters;
};

// The period-n point of kind spec at (P = start_param, Q = q0) with orbit state y0 (physical; a
// point located on a branch) corrected on the extended system with Q fixed, then followed both
// ways in the box. Empty points, with `stop` saying why, when the start does not converge.
Curve continue_curve(const PointAt2& at, const CurveBox& box, const CurveSpec& spec, int n, double start_param,
                     double q0, const Eigen::Vector4d& y0, const CurveOptions& options);

// The level point of spec between two consecutive branch points a and b (period n, Q = q0)
// whose quantity values va, vb lie either side of spec.value: Newton on the extended system with
// Q fixed from their interpolation. None when it does not converge between them.
std::optional<CurvePoint> locate_level(const PointAt2& at, const CurveBox& box, const CurveSpec& spec, int n, double q0,
                                       const BranchPoint& a, double va, const BranchPoint& b, double vb,
                                       const CurveOptions& options);

}  // namespace vibromap
