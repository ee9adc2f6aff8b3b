#pragma once
// Internal to the farm: rank 0's progress report: items done/total, items per second over this
// run, ETA, and the campaign's note (a sweep's most frequent regimes). On a terminal a live
// line rewritten in place (at most 4 per second); otherwise a plain line every `interval_s`
// seconds, for batch logs.

#include <chrono>
#include <cstdint>
#include <iosfwd>
#include <string>

namespace vibromap::detail {

class ProgressReporter {
 public:
  // label: what runs ("sweep"); noun: what is counted ("cells"); total: items of the campaign;
  // already_done: items done before this run (not counted in the rate).
  ProgressReporter(std::ostream& os, bool enabled, bool live, double interval_s, std::string label, std::string noun,
                   std::uint64_t total, std::uint64_t already_done);
  void update(std::uint64_t done, const std::string& note);  // prints when the interval has passed
  void finish(std::uint64_t done, const std::string& note);  // prints the last line
  std::string line(std::uint64_t done, const std::string& note) const;

 private:
  std::ostream& os_;
  bool enabled_, live_;
  double interval_s_;
  std::string label_, noun_;
  std::uint64_t total_, start_done_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace vibromap::detail
