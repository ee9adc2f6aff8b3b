#include "progress.hpp"

#include <algorithm>
#include <cstdio>
#include <ostream>
#include <vector>

namespace vibromap::detail {

namespace {
std::string hms(double s) {
  if (!(s >= 0.0) || s > 1e8) return "--:--:--";
  const long t = static_cast<long>(s + 0.5);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  return buf;
}
}  // namespace

ProgressReporter::ProgressReporter(std::ostream& os, bool enabled, bool live, double interval_s, std::size_t total,
                                   std::size_t already_done)
    : os_(os), enabled_(enabled), live_(live), interval_s_(live ? 0.25 : interval_s), total_(total),
      start_done_(already_done), start_(std::chrono::steady_clock::now()), last_(start_) {}

std::string ProgressReporter::line(std::size_t done, const std::map<std::string, long>& regimes) const {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed > 0.0 ? static_cast<double>(done - start_done_) / elapsed : 0.0;
  const double eta = rate > 0.0 ? static_cast<double>(total_ - done) / rate : -1.0;
  char head[160];
  std::snprintf(head, sizeof head, "sweep: %zu/%zu cells (%.1f%%), %.1f cells/s, elapsed %s, ETA %s", done, total_,
                total_ ? 100.0 * static_cast<double>(done) / static_cast<double>(total_) : 100.0, rate,
                hms(elapsed).c_str(), hms(eta).c_str());
  std::vector<std::pair<long, std::string>> top;
  for (const auto& [label, count] : regimes) top.emplace_back(-count, label);
  std::sort(top.begin(), top.end());
  std::string out = head;
  if (!top.empty()) out += " |";
  for (std::size_t i = 0; i < top.size() && i < 5; ++i) out += " " + top[i].second + " " + std::to_string(-top[i].first);
  if (top.size() > 5) out += " ...";
  return out;
}

void ProgressReporter::update(std::size_t done, const std::map<std::string, long>& regimes, bool force) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && std::chrono::duration<double>(now - last_).count() < interval_s_) return;
  last_ = now;
  if (live_)
    os_ << '\r' << line(done, regimes) << "\033[K" << std::flush;
  else
    os_ << line(done, regimes) << '\n' << std::flush;
}

void ProgressReporter::finish(std::size_t done, const std::map<std::string, long>& regimes) {
  if (!enabled_) return;
  if (live_) os_ << '\r' << line(done, regimes) << "\033[K\n" << std::flush;
  else os_ << line(done, regimes) << '\n' << std::flush;
}

}  // namespace vibromap::detail
