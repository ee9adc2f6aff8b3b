#pragma once
// Internal to the sweep campaign: rank 0's sink of cell results into the map file.

#include <map>
#include <string>

#include "cell_codec.hpp"
#include "vibromap/io/map_file.hpp"

namespace vibromap::detail {

class MapSink : public ResultSink<CellResult> {
 public:
  MapSink(const CellCodec& codec, std::string path, SweepMap map);

  std::uint64_t items() const override { return map_.grid.size(); }
  std::uint64_t items_done() const override { return done_; }
  std::uint64_t pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) override;
  void store_results(const ItemRange& range, std::vector<CellResult>& results) override;
  void checkpoint() override;
  void finish(bool complete) override;
  std::string note() const override;  // the five most frequent regimes

  const std::map<std::string, long>& regimes() const { return regimes_; }

 private:
  std::string path_;
  SweepMap map_;
  std::uint64_t done_ = 0;
  std::map<std::string, long> regimes_;
};

}  // namespace vibromap::detail
