#pragma once
// Steady-state detection on the stroboscopic samples y_j = y(jT): an observer that asks the
// integrator to stop once the motion repeats.
//
// The motion is n-periodic when ||y_i - y_{i-n}|| <= tol for the last n samples i (so the
// whole cycle repeats, not one point of it); the least such n <= n_max is taken. The norm is a
// scaled max-norm (StateScale, shooting.hpp): positions over L + |x|, velocities over
// omega L + |v|, with L = max(D, lambda F0 / k1) the motion's natural length scale.
//
// When the budget runs out without a period, still_converging() tells a motion that is
// settling too slowly for the budget (unresolved) from one that does not settle at all
// (quasi-periodic or chaotic): it fits a line to log10 of the best residual over the last
// periods and calls the motion converging when the slope is negative beyond three standard
// errors.

#include <array>
#include <deque>
#include <vector>

#include "vibromap/core/analysis/point/shooting.hpp"
#include "vibromap/core/integrate/observer.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap {

class SteadyStateDetector final : public Observer {
 public:
  static constexpr int kMaxN = 64;  // the largest n_max (AnalysisOptions::n_max is validated against it)
  SteadyStateDetector(const Model& model, int n_max, double tol);

  bool on_period_end(long period, const State& u) override;

  int period_n() const { return n_found_; }         // the period found, 0 while none
  long detected_at() const { return detected_at_; } // the period (0-based) at whose end it was found
  double residual() const { return residual_; }     // best scaled residual at the last sample
  bool still_converging() const;
  // Up to `count` periods n <= n_max ordered by ||y_last - y_{last-n}||, smallest first: the
  // periods a shooting method should try.
  std::vector<int> candidate_periods(int count) const;

  double distance(const State& a, const State& b) const;
  // The samples kept (the last 2 n_max at most), oldest first.
  const std::deque<State>& samples() const { return samples_; }

 private:
  int n_max_;
  double tol_;
  StateScale scale_;
  std::deque<State> samples_;       // the last 2 n_max samples, newest at the back
  // gaps_[i][n] = ||y_i - y_{i-n}|| of samples_[i] (n = 1..n_max; infinite where y_{i-n} did
  // not exist), computed once when y_i came: the test over the last n samples of every n
  // reads them, instead of 1 + ... + n_max new distances every period.
  std::deque<std::array<double, kMaxN + 1>> gaps_;
  std::vector<double> worst_;       // per n: the largest gap over the last n samples
  std::vector<double> best_log10_;  // log10 of min over n of ||y_j - y_{j-n}||, per period
  int n_found_ = 0;
  long detected_at_ = -1;
  double residual_ = 0.0;
};

}  // namespace vibromap
