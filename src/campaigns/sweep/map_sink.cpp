#include "map_sink.hpp"

#include <algorithm>
#include <vector>

namespace vibromap::detail {
namespace {

std::string regime_label(const CellResult& c) { return Regime{static_cast<RegimeKind>(c.regime), c.n, c.k}.label(); }

}  // namespace

MapSink::MapSink(const CellCodec& codec, std::string path, SweepMap map)
    : ResultSink<CellResult>(codec), path_(std::move(path)), map_(std::move(map)) {
  for (std::size_t i = 0; i < map_.cells.size(); ++i) {
    if (!map_.done[i]) continue;
    ++done_;
    ++regimes_[regime_label(map_.cells[i])];
  }
}

std::uint64_t MapSink::pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) {
  std::uint64_t taken = 0, i = from;
  for (; i < items() && taken < max; ++i) {
    if (map_.done[i]) continue;
    if (!out.empty() && out.back().end == i) {
      ++out.back().end;
    } else {
      out.push_back({i, i + 1});
    }
    ++taken;
  }
  return i;
}

void MapSink::store_results(const ItemRange& range, std::vector<CellResult>& results) {
  for (std::uint64_t i = range.begin; i < range.end; ++i) {
    const CellResult& c = results[i - range.begin];
    map_.cells[i] = c;
    if (!map_.done[i]) ++done_;
    map_.done[i] = 1;
    ++regimes_[regime_label(c)];
  }
}

void MapSink::checkpoint() { write_map(path_, map_); }

void MapSink::finish(bool) { write_map(path_, map_); }

std::string MapSink::note() const {
  std::vector<std::pair<long, std::string>> top;
  for (const auto& [label, count] : regimes_) top.emplace_back(-count, label);
  std::sort(top.begin(), top.end());
  std::string out;
  for (std::size_t i = 0; i < top.size() && i < 5; ++i)
    out += (i ? " " : "") + top[i].second + " " + std::to_string(-top[i].first);
  if (top.size() > 5) out += " ...";
  return out;
}

}  // namespace vibromap::detail
