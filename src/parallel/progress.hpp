#pragma once
// Internal: rank 0's progress report of a sweep: cells done/total, cells per second, ETA and
// the most frequent regimes. On a terminal a live line (rewritten in place, at most 4 per
// second); otherwise one plain line every `interval` seconds, for batch logs.

#include <chrono>
#include <iosfwd>
#include <map>
#include <string>

namespace vibromap::detail {

class ProgressReporter {
 public:
  ProgressReporter(std::ostream& os, bool enabled, bool live, double interval_s, std::size_t total,
                   std::size_t already_done);
  // done: cells done in the map so far; regimes: label -> count over the map.
  void update(std::size_t done, const std::map<std::string, long>& regimes, bool force = false);
  void finish(std::size_t done, const std::map<std::string, long>& regimes);

 private:
  std::string line(std::size_t done, const std::map<std::string, long>& regimes) const;
  std::ostream& os_;
  bool enabled_, live_;
  double interval_s_;
  std::size_t total_, start_done_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace vibromap::detail
