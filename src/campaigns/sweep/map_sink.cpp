#include "map_sink.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vibromap::detail {

std::string regime_label(const CellResult& c) { return Regime{static_cast<RegimeKind>(c.regime), c.n, c.k}.label(); }

void MapTally::add(const CellResult& c) {
  ++regimes[regime_label(c)];
  soft += c.soft == 1 ? 1 : 0;
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
  points_ = plan_.plan(phase);
  left_ = static_cast<std::uint64_t>(
      std::count_if(points_.begin(), points_.end(), [&](std::uint64_t p) { return !plan_.recorded(p); }));
  return left_;
}

std::uint64_t RefineSink::pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) {
  std::uint64_t taken = 0;
  auto it = std::lower_bound(points_.begin(), points_.end(), from);
  for (; it != points_.end() && taken < max; ++it) {
    if (plan_.recorded(*it)) continue;
    if (!out.empty() && out.back().end == *it) {
      ++out.back().end;
    } else {
      out.push_back({*it, *it + 1});
    }
    ++taken;
  }
  return it == points_.end() ? items() : *it;
}

void RefineSink::store_results(const ItemRange& range, std::vector<CellResult>& results) {
  for (std::uint64_t i = range.begin; i < range.end; ++i) {
    CellResult& c = results[static_cast<std::size_t>(i - range.begin)];
    plan_.stamp(phase_, i, c);
    plan_.record(i, c);
  }
  MapSink::store_results(range, results);
}

std::string RefineSink::note() const {  // the phase is the progress line's label
  return std::to_string(plan_.solved()) + " solved, " + std::to_string(plan_.inferred()) + " inferred of " +
         std::to_string(items()) + " points | " + MapSink::note();
}

void RefineSink::fill() {
  plan_.fill(writer_, [&](const CellResult& c) {
    tally_.add(c);
    ++filled_;
  });
}

void RefineSink::close() {
  figures_ = plan_.figures();
  writer_.finish(ranks_, &figures_);
}

}  // namespace vibromap::detail
