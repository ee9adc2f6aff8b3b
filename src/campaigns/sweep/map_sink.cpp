#include "map_sink.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vibromap::detail {

std::string regime_label(const CellResult& c) { return Regime{static_cast<RegimeKind>(c.regime), c.n, c.k}.label(); }

void MapTally::add(const CellResult& c) {
  ++regimes[regime_label(c)];
  if (c.regime >= 0 && c.wall_s > 0.0) classes[to_string(static_cast<RegimeKind>(c.regime))].add(c.wall_s);
  soft += c.soft == 1 ? 1 : 0;
  fragile += c.fragile == 1 ? 1 : 0;
  fragility_assessed += c.fragile >= 0 ? 1 : 0;
  if (c.k > 0 || c.T_con > 0.0) {
    ++impacting;
    hertz_invalid += c.hertz_valid ? 0 : 1;
  }
  if (census_k > 0 && std::isfinite(c.budget_fraction)) census_budget_states += std::lround(c.budget_fraction * census_k);
}

MapSink::MapSink(const CellCodec& codec, MapWriter writer, MapTally tally, int ranks)
    : ResultSink<CellResult>(codec), writer_(std::move(writer)), tally_(std::move(tally)), ranks_(ranks) {}

std::uint64_t MapSink::pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) {
  spans_.clear();
  const std::uint64_t next = writer_.pending(from, max, spans_);
  for (const CellSpan& s : spans_) out.push_back({s.begin, s.end});
  return next;
}

void MapSink::store_results(const ItemRange& range, std::vector<CellResult>& results) {
  writer_.write(range.begin, results);
  for (const CellResult& c : results) tally_.add(c);
}

void MapSink::finish(bool) { writer_.finish(ranks_); }

std::string MapSink::note() const {
  std::vector<std::pair<long, std::string>> top;
  for (const auto& [label, count] : tally_.regimes) top.emplace_back(-count, label);
  std::sort(top.begin(), top.end());
  std::string out;
  for (std::size_t i = 0; i < top.size() && i < 5; ++i)
    out += (i ? " " : "") + top[i].second + " " + std::to_string(-top[i].first);
  if (top.size() > 5) out += " ...";
  return out;
}

RefineSink::RefineSink(const CellCodec& codec, MapWriter writer, MapTally tally, int ranks, RefinePlan plan)
    : MapSink(codec, std::move(writer), std::move(tally), ranks), plan_(std::move(plan)) {}

std::uint64_t RefineSink::begin_phase(int phase) {
  phase_ = phase;
  plan_.begin(phase, writer_);
  left_ = 0;
  std::vector<ItemRange> ranges;
  for (std::uint64_t from = 0; from < items();) {
    ranges.clear();
    from = pending(from, std::uint64_t{1} << 20, ranges);
    for (const ItemRange& r : ranges) left_ += r.end - r.begin;
  }
  phase_points_ = plan_.points_in(phase);
  solved_ += phase_points_ - left_;  // solved by an earlier run (a resumed map)
  // Decided now: every point but those a later level may still solve; of them, the solved ones
  // are those of the phases so far, this one's included.
  inferred_ = items() - plan_.open_after(phase) - (solved_ + left_);
  return left_;
}

// The points of the phase not done in the map: its not-done cells, asked of the plan one by one.
std::uint64_t RefineSink::pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) {
  spans_.clear();
  const std::uint64_t next = writer_.pending(from, std::max<std::uint64_t>(max, 1 << 16), spans_);
  std::uint64_t taken = 0;
  for (const CellSpan& s : spans_) {
    for (std::uint64_t p = s.begin; p < s.end; ++p) {
      if (!plan_.in_phase(phase_, p)) continue;
      if (taken == max) return p;  // the next call starts here
      if (!out.empty() && out.back().end == p) {
        ++out.back().end;
      } else {
        out.push_back({p, p + 1});
      }
      ++taken;
    }
  }
  return next;
}

void RefineSink::store_results(const ItemRange& range, std::vector<CellResult>& results) {
  for (std::uint64_t i = range.begin; i < range.end; ++i) plan_.stamp(phase_, i, results[static_cast<std::size_t>(i - range.begin)]);
  solved_ += range.end - range.begin;
  MapSink::store_results(range, results);
}

std::string RefineSink::note() const {  // the phase is the progress line's label
  return std::to_string(solved_) + " solved, " + std::to_string(inferred_) + " inferred of " +
         std::to_string(items()) + " points | " + MapSink::note();
}

void RefineSink::fill() {
  plan_.fill(writer_, [&](const CellResult& c) {
    tally_.add(c);
    ++filled_;
  });
  whole_ = true;
}

void RefineSink::close() {
  if (!whole_) {  // stopped: the map's figures stay "not finished" (zeros, bound 1)
    writer_.finish(ranks_);
    return;
  }
  figures_ = plan_.figures(writer_);
  writer_.finish(ranks_, &figures_);
}

}  // namespace vibromap::detail
