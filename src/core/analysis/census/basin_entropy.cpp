// Basin entropy and the uncertainty exponent of a plane of labels: see basin_entropy.hpp.

#include "vibromap/core/analysis/census/basin_entropy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap {
namespace {

constexpr int kExcluded = -1;  // the dense id of a pixel that is no outcome

bool is_outcome(std::int32_t label) { return label >= 0 || label == kUnresolvedLabel || label == kUnlistedLabel; }

// Each pixel's outcome as a dense id 0..m-1 (m = the distinct outcomes), kExcluded for the rest.
std::vector<int> dense_outcomes(std::span<const std::int32_t> labels, int& m) {
  std::vector<std::int32_t> distinct;
  for (const std::int32_t l : labels)
    if (is_outcome(l)) distinct.push_back(l);
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  m = static_cast<int>(distinct.size());
  std::vector<int> ids(labels.size(), kExcluded);
  for (std::size_t p = 0; p < labels.size(); ++p)
    if (is_outcome(labels[p]))
      ids[p] = static_cast<int>(std::lower_bound(distinct.begin(), distinct.end(), labels[p]) - distinct.begin());
  return ids;
}

// -sum p ln p over the counts of one box (total > 0); `kinds` gets the outcomes present.
double box_entropy(std::span<const long> counts, long total, int& kinds) {
  double s = 0.0;
  kinds = 0;
  for (const long c : counts) {
    if (c == 0) continue;
    ++kinds;
    const double p = static_cast<double>(c) / static_cast<double>(total);
    s -= p * std::log(p);
  }
  return s;
}

// S_b, S_bb and the box counts over the full boxes of the plane.
void box_entropies(const std::vector<int>& ids, int n0, int n1, int m, BasinEntropySummary& s) {
  const int box = s.box;
  std::vector<long> counts(static_cast<std::size_t>(m));
  double sum_all = 0.0, sum_boundary = 0.0;
  for (int by = 0; by + box <= n1; by += box)
    for (int bx = 0; bx + box <= n0; bx += box) {
      std::fill(counts.begin(), counts.end(), 0L);
      long total = 0;
      for (int j = by; j < by + box; ++j)
        for (int i = bx; i < bx + box; ++i) {
          const int id = ids[static_cast<std::size_t>(j) * static_cast<std::size_t>(n0) + static_cast<std::size_t>(i)];
          if (id == kExcluded) continue;
          ++counts[static_cast<std::size_t>(id)];
          ++total;
        }
      if (total == 0) continue;
      int kinds = 0;
      const double si = box_entropy(counts, total, kinds);
      ++s.boxes;
      sum_all += si;
      if (kinds > 1) {
        ++s.boundary_boxes;
        sum_boundary += si;
      }
    }
  if (s.boxes == 0) return;  // nothing counted: S_b and S_bb stay NaN
  s.S_b = sum_all / static_cast<double>(s.boxes);
  s.S_bb = s.boundary_boxes > 0 ? sum_boundary / static_cast<double>(s.boundary_boxes) : 0.0;
  s.verdict = s.boundary_boxes == 0       ? BoundaryVerdict::no_boundary
              : s.S_bb > std::log(2.0)    ? BoundaryVerdict::fractal
                                          : BoundaryVerdict::not_shown;
}

// One widening of the square windows held in lo and hi (radius r to r + shift, shift <= 2r + 1):
// each value becomes the min (max) of itself and its neighbours `shift` away along one axis,
// clipped to the plane. Separable, so that the square window costs two passes a step.
void widen(std::vector<int>& lo, std::vector<int>& hi, int n0, int n1, int shift, bool along_first) {
  const std::vector<int> lo0 = lo, hi0 = hi;
  for (int j = 0; j < n1; ++j)
    for (int i = 0; i < n0; ++i) {
      const auto at = [n0](int ii, int jj) { return static_cast<std::size_t>(jj) * static_cast<std::size_t>(n0) + static_cast<std::size_t>(ii); };
      const std::size_t p = at(i, j);
      const std::size_t a = along_first ? at(std::max(i - shift, 0), j) : at(i, std::max(j - shift, 0));
      const std::size_t b = along_first ? at(std::min(i + shift, n0 - 1), j) : at(i, std::min(j + shift, n1 - 1));
      lo[p] = std::min({lo0[a], lo0[p], lo0[b]});
      hi[p] = std::max({hi0[a], hi0[p], hi0[b]});
    }
}

// f(eps) at eps = 1, 2, 4, ... <= min(n0, n1) / 4: the share of outcome pixels whose square
// neighbourhood of half-width eps holds another outcome.
void uncertain_fractions(const std::vector<int>& ids, int n0, int n1, BasinEntropySummary& s) {
  std::vector<int> lo(ids.size()), hi(ids.size());
  long counted = 0;
  for (std::size_t p = 0; p < ids.size(); ++p) {
    const bool in = ids[p] != kExcluded;
    lo[p] = in ? ids[p] : std::numeric_limits<int>::max();
    hi[p] = in ? ids[p] : std::numeric_limits<int>::min();
    counted += in ? 1 : 0;
  }
  if (counted == 0) return;
  const int largest = std::min(n0, n1) / 4;
  int radius = 0;
  for (int eps = 1; eps <= largest; eps *= 2) {
    while (radius < eps) {
      const int shift = std::max(radius, 1);
      widen(lo, hi, n0, n1, shift, true);
      widen(lo, hi, n0, n1, shift, false);
      radius += shift;
    }
    long uncertain = 0;
    for (std::size_t p = 0; p < ids.size(); ++p)
      if (ids[p] != kExcluded && lo[p] != hi[p]) ++uncertain;
    s.eps.push_back(eps);
    s.uncertain.push_back(static_cast<double>(uncertain) / static_cast<double>(counted));
  }
}

// Least squares of ln f on ln eps over the unsaturated scales (0 < f < max_uncertain_fraction).
void fit_uncertainty(const BasinEntropyOptions& o, int outcomes, BasinEntropySummary& s) {
  std::vector<double> x, y;
  std::vector<int> used;
  for (std::size_t k = 0; k < s.eps.size(); ++k)
    if (s.uncertain[k] > 0.0 && s.uncertain[k] < o.max_uncertain_fraction) {
      x.push_back(std::log(static_cast<double>(s.eps[k])));
      y.push_back(std::log(s.uncertain[k]));
      used.push_back(s.eps[k]);
    }
  if (outcomes < 2) {
    s.alpha_note = "the plane holds one outcome: no boundary";
    return;
  }
  if (static_cast<int>(x.size()) < o.min_scales) {
    s.alpha_note = cat(std::to_string(x.size()), " of the ", std::to_string(s.eps.size()),
                       " scales eps = 1, 2, 4, ... <= min(N0, N1) / 4 have 0 < f(eps) < ",
                       number(o.max_uncertain_fraction), "; the fit needs ", std::to_string(o.min_scales));
    return;
  }
  const double n = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) mx += x[k] / n, my += y[k] / n;
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) sxx += (x[k] - mx) * (x[k] - mx), sxy += (x[k] - mx) * (y[k] - my);
  s.alpha = sxy / sxx;
  s.dimension = 2.0 - s.alpha;
  double ss = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double r = y[k] - (my + s.alpha * (x[k] - mx));
    ss += r * r;
  }
  s.fit_rms = std::sqrt(ss / n);
  s.fit_scales = static_cast<int>(x.size());
  s.eps_lo = used.front();
  s.eps_hi = used.back();
}

}  // namespace

std::string validate(const BasinEntropyOptions& o) {
  if (o.box < 1) return cat("box ", std::to_string(o.box), ": must be a whole number of pixels >= 1");
  if (o.min_scales < 2) return cat("min_scales ", std::to_string(o.min_scales), ": must be >= 2");
  if (!(o.max_uncertain_fraction > 0.0 && o.max_uncertain_fraction <= 1.0))
    return cat("max_uncertain_fraction ", number(o.max_uncertain_fraction), ": must be in (0, 1]");
  return {};
}

std::string to_string(BoundaryVerdict v) {
  switch (v) {
    case BoundaryVerdict::no_boundary: return "no_boundary";
    case BoundaryVerdict::not_shown: return "not_shown";
    case BoundaryVerdict::fractal: return "fractal";
  }
  return "?";
}

BasinEntropySummary basin_entropy(std::span<const std::int32_t> labels, int n0, int n1, const BasinEntropyOptions& o) {
  BasinEntropySummary s;
  s.box = o.box;
  if (s.message = validate(o); !s.message.empty()) return s;
  if (n0 < 1 || n1 < 1 || labels.size() != static_cast<std::size_t>(n0) * static_cast<std::size_t>(n1)) {
    s.message = cat("the labels (", std::to_string(labels.size()), ") do not fill a ", std::to_string(n0), " x ",
                    std::to_string(n1), " plane");
    return s;
  }
  if (o.box > n0 || o.box > n1) {
    s.message = cat("the box (", std::to_string(o.box), " pixels) exceeds the plane's side (", std::to_string(std::min(n0, n1)), ")");
    return s;
  }
  int m = 0;
  const std::vector<int> ids = dense_outcomes(labels, m);
  s.outcomes = m;
  box_entropies(ids, n0, n1, m, s);
  uncertain_fractions(ids, n0, n1, s);
  fit_uncertainty(o, m, s);
  s.ok = true;
  return s;
}

double fraction_entropy(std::span<const double> fractions) {
  double s = 0.0;
  for (const double f : fractions)
    if (f > 0.0) s -= f * std::log(f);
  return s;
}

}  // namespace vibromap
