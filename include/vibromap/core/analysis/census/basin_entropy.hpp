#pragma once
// Basin entropy of a plane of labels, and of a set of basin fractions.
//
// After A. Daza, A. Wagemakers, B. Georgeot, D. Guery-Odelin, M. A. F. Sanjuan, "Basin entropy:
// a new tool to analyze uncertainty in dynamical systems", Sci. Rep. 6, 31416 (2016). The plane
// (N0 x N1 pixels, pixel p = j N0 + i, the first axis fastest: basins_plane.hpp) is cut into
// boxes of box x box pixels, from pixel (0, 0) on; the last N0 mod box columns and N1 mod box
// rows are in no box. In box i, p_ij is the share of its counted pixels with outcome j and
//   S_i = -sum_j p_ij ln p_ij   (natural logarithm: the maximum with m outcomes is ln m);
//   S_b  = the mean of S_i over the N boxes that hold a counted pixel;
//   S_bb = the mean of S_i over the N_b boundary boxes (those holding more than one outcome),
//          0 when there is none.
// Outcomes: every attractor label (>= 0), kUnresolvedLabel and kUnlistedLabel, each an outcome
// of its own (the unlisted attractors lumped into one). Every other label (kOverlapLabel, a pixel
// not computed) is excluded: it counts in no box's shares and in no neighbourhood below.
// The log 2 test: S_bb > ln 2 is a sufficient condition for a fractal boundary (Daza et al.'s
// criterion); S_bb <= ln 2 proves nothing. With two outcomes S_i <= ln 2, so the test can only
// pass where boundary boxes hold three or more outcomes.
//
// The uncertainty exponent (Grebogi, McDonald, Ott, Yorke, Phys. Lett. A 99, 415 (1983)):
// f(eps) is the share of counted pixels whose square neighbourhood of half-width eps pixels
// (clipped to the plane) holds another outcome, at eps = 1, 2, 4, ... up to min(N0, N1) / 4. The
// scales with 0 < f(eps) < max_uncertain_fraction (below saturation) are fitted by least squares,
// ln f = alpha ln eps + c; alpha is the slope, d = 2 - alpha the boundary's box dimension. The
// plane allows the fit when at least min_scales such scales exist; otherwise alpha is NaN and
// alpha_note says why. A straight boundary gives f = 2 eps / N: alpha = 1, d = 1.

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace vibromap {

struct BasinEntropyOptions {
  int box = 5;                          // side of the boxes, pixels (eps of Daza et al.), >= 1
  int min_scales = 3;                   // scales the uncertainty fit needs, >= 2
  double max_uncertain_fraction = 0.5;  // f(eps) at or above this is saturated and left out of the fit, (0, 1]
};

std::string validate(const BasinEntropyOptions& o);  // empty when valid

// The log 2 test's answer.
enum class BoundaryVerdict {
  no_boundary,  // no box holds two outcomes
  not_shown,    // S_bb <= ln 2: the test proves nothing
  fractal,      // S_bb > ln 2: the boundary is fractal
};
std::string to_string(BoundaryVerdict v);

struct BasinEntropySummary {
  bool ok = false;        // false: invalid options or a plane with no box (message says why)
  std::string message;
  int box = 0;            // the box side used, pixels
  long boxes = 0;         // N: boxes holding a counted pixel
  long boundary_boxes = 0;  // N_b: boxes holding more than one outcome
  int outcomes = 0;       // distinct outcomes in the plane
  double S_b = std::numeric_limits<double>::quiet_NaN();   // basin entropy, nats
  double S_bb = std::numeric_limits<double>::quiet_NaN();  // boundary basin entropy, nats
  BoundaryVerdict verdict = BoundaryVerdict::no_boundary;
  // The uncertainty exponent's fit.
  std::vector<int> eps;                  // the scales computed, pixels
  std::vector<double> uncertain;         // f(eps) at each
  double alpha = std::numeric_limits<double>::quiet_NaN();  // slope of ln f against ln eps
  double dimension = std::numeric_limits<double>::quiet_NaN();  // 2 - alpha
  int eps_lo = 0, eps_hi = 0;            // the fitted scales' range, pixels (0: no fit)
  int fit_scales = 0;                    // scales fitted
  double fit_rms = std::numeric_limits<double>::quiet_NaN();  // RMS residual of the fit in ln f
  std::string alpha_note;                // why alpha is NaN; empty when fitted
};

// The basin entropy of the n0 x n1 plane `labels` (pixel j n0 + i). Pure; never throws.
BasinEntropySummary basin_entropy(std::span<const std::int32_t> labels, int n0, int n1,
                                  const BasinEntropyOptions& options = {});

// -sum_j f_j ln f_j over the shares f_j > 0 of a census's outcomes (nats): Daza et al.'s S_b
// with the whole census box as its one box.
double fraction_entropy(std::span<const double> fractions);

}  // namespace vibromap
