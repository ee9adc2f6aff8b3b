#pragma once
// The accuracy study (docs/guide-accuracy.md: numerical error against run time): one parameter
// point solved by several methods and tolerances, each compared with a reference solve of
// the same point, so that a user can choose a tolerance for a big sweep knowing what it
// costs (solve time, RHS evaluations, periods) and what it buys (relative error of T_con,
// F_max and k_con).
//
// Contract: run_accuracy() solves the reference first, then every case in order, one at a
// time (so each wall time is the solve time of that one point, undisturbed by the others).
// A case that fails or runs out of budget is a row with its status, never an exception.
// Relative errors are |x - x_ref| / |x_ref|; they are NaN when the reference or the case has
// no impact (T_con = 0), when either failed, or when the reference value is not finite or 0.
// A case whose regime differs from the reference's keeps its errors (they are what a sweep
// at that setting would report) and says so in `note`.
//
// Units: wall_s in s, T_con in s, F_max in N, k_con and the relative errors dimensionless.
// No I/O here: the command line (src/cli/accuracy_command.cpp) prints and writes the rows.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/model/parameters.hpp"

namespace vibromap {

// One way of solving the point: a label naming the method family (rows with the same label
// form one line of a work-precision plot) and the complete options.
struct AccuracyCase {
  std::string method_label;  // e.g. "rk4", "dopri5", "hybrid+shooting", "reference"
  PointOptions options;
};

// One solved case against the reference.
struct AccuracyRow {
  std::string label;        // AccuracyCase::method_label
  std::string setting;      // what was varied: "rtol 1e-8" or "2^11 steps/T" (setting_label())
  Method method = Method::hybrid;                     // integrator used
  SteadyMethod steady = SteadyMethod::integrate;      // steady-state method asked for
  double rtol = 0.0;        // hybrid, dopri5: relative tolerance (NaN for rk4), -
  double atol = 0.0;        // hybrid, dopri5: absolute tolerance (NaN for rk4), m
  int rk4_steps = 0;        // rk4: steps per forcing period (0 for the others), -
  SolveStatus status = SolveStatus::invalid_input;
  std::string regime;       // Regime::label(): "(1,1)", "chatter", ...
  bool regime_matches = false;                        // same regime as the reference
  SteadyMethod steady_used = SteadyMethod::integrate; // the method that produced the answer
  int newton_iterations = 0;
  double wall_s = 0.0;      // solve time of this one point, s
  long rhs_evals = 0;       // right-hand side evaluations, -
  long steps = 0;           // accepted steps, -
  long periods = 0;         // forcing periods integrated, -
  double T_con = 0.0;       // duration of the longest impact, s
  double F_max = 0.0;       // largest peak contact force, N
  double k_con = 0.0;       // T / T_con, -
  double rel_err_T_con = 0.0;  // |T_con - T_con_ref| / T_con_ref (NaN when undefined), -
  double rel_err_F_max = 0.0;  // likewise for F_max, -
  double rel_err_k_con = 0.0;  // likewise for k_con, -
  std::string note;         // why errors are NaN, or that the regime differs; empty otherwise
};

struct AccuracyReport {
  AccuracyRow reference;          // the reference against itself: errors 0 (or NaN without impact)
  std::vector<AccuracyRow> rows;  // the cases, in the order given
  // Why the cases were not solved (empty when they were): a reference without an impact, or
  // that did not settle, leaves no error to measure, and each case would only spend its budget.
  std::string unsolved;
};

// Relative error |value - reference| / |reference|; NaN when either is not finite or the
// reference is 0.
double relative_error(double value, double reference);

// "2^11 steps/T" (rk4; "3000 steps/T" when not a power of 2) or "rtol 1e-8" (hybrid, dopri5).
std::string setting_label(const IntegratorOptions& options);

// The row of a solved case against the reference's summary (also for the reference itself).
AccuracyRow accuracy_row(const AccuracyCase& c, const PointSummary& s, const PointSummary& reference);

// The default study, built on `base` (the scene's options: budgets, n_max, hertz_limit, ...
// are kept; trajectory and Lyapunov exponent are switched off, and steady_tol and newton_tol
// are set to auto so that each follows its own tolerance, as docs/numerics.md explains):
//   rk4 (the paper's method), steady = integrate, 2^11, 2^12, 2^13, 2^14, 2^15 steps per period;
//   dopri5 brute force, steady = integrate, rtol 1e-6, 1e-8, 1e-10, 1e-12;
//   hybrid with shooting, rtol 1e-6, 1e-8, 1e-10, 1e-12.
// atol is base.atol at rtol 1e-10 and scales with rtol (atol/rtol kept), so one knob sets both.
std::vector<AccuracyCase> default_accuracy_cases(const PointOptions& base);

// The default reference: dopri5 brute force (steady = integrate) at rtol 1e-13, the most
// conservative combination (no closed form, no Newton); label "reference".
AccuracyCase default_accuracy_reference(const PointOptions& base);

// Called after each solve (the reference first): the row, and how many of `total` are done.
using AccuracyProgress = std::function<void(const AccuracyRow& row, std::size_t done, std::size_t total)>;

AccuracyReport run_accuracy(const Parameters& p, const std::vector<AccuracyCase>& cases,
                            const AccuracyCase& reference, const AccuracyProgress& progress = {});

}  // namespace vibromap
