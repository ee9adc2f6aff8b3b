#include "progress.hpp"

#include <cstdio>
#include <ostream>

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

ProgressReporter::ProgressReporter(std::ostream& os, bool enabled, bool live, double interval_s, std::string label,
                                   std::string noun, std::uint64_t total, std::uint64_t already_done)
    : os_(os), enabled_(enabled), live_(live), interval_s_(live ? 0.25 : interval_s), label_(std::move(label)),
      noun_(std::move(noun)), total_(total), start_done_(already_done), start_(std::chrono::steady_clock::now()),
      last_(start_) {}

std::string ProgressReporter::line(std::uint64_t done, const std::string& note) const {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double now_done = static_cast<double>(done > start_done_ ? done - start_done_ : 0);
  const double rate = elapsed > 0.0 ? now_done / elapsed : 0.0;
  const double eta = rate > 0.0 ? static_cast<double>(total_ - done) / rate : -1.0;
  char head[256];
  std::snprintf(head, sizeof head, "%s: %llu/%llu %s (%.1f%%), %.1f %s/s, elapsed %s, ETA %s", label_.c_str(),
                static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_), noun_.c_str(),
                total_ ? 100.0 * static_cast<double>(done) / static_cast<double>(total_) : 100.0, rate, noun_.c_str(),
                hms(elapsed).c_str(), hms(eta).c_str());
  return note.empty() ? std::string(head) : std::string(head) + " | " + note;
}

void ProgressReporter::update(std::uint64_t done, const std::string& note) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_).count() < interval_s_) return;
  last_ = now;
  if (live_)
    os_ << '\r' << line(done, note) << "\033[K" << std::flush;
  else
    os_ << line(done, note) << '\n' << std::flush;
}

void ProgressReporter::finish(std::uint64_t done, const std::string& note) {
  if (!enabled_) return;
  os_ << (live_ ? "\r" : "") << line(done, note) << (live_ ? "\033[K\n" : "\n") << std::flush;
}

}  // namespace vibromap::detail
