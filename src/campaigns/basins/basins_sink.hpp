#pragma once
// Internal to the basins campaign: rank 0's sink of pixel results. Every label and the global
// attractor list stay in memory (4 bytes a pixel, a few records); each checkpoint rewrites the
// whole file atomically (io/basins_file.hpp), so a run killed at any instant leaves the file of
// its last checkpoint, which --resume continues (GNU parallel's joblog idea: what the file marks
// done is never redone).

#include <cstdint>
#include <string>
#include <vector>

#include "vibromap/campaigns/census/state_codec.hpp"
#include "vibromap/io/basins_file.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap::detail {

class BasinsSink : public ResultSink<PixelResult> {
 public:
  // A sink over `start` (a new run's empty content, or the content of the file resumed).
  // `census`: the followers' options (canonical records are found with them); `entropy`: the
  // basin entropy's options, applied to the labels at every write.
  BasinsSink(const PixelCodec& codec, const Scene& scene, CensusOptions census, BasinEntropyOptions entropy,
             std::string path, BasinsContent start);

  std::uint64_t items() const override { return content_.labels.size(); }
  std::uint64_t items_done() const override { return done_; }
  std::uint64_t pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) override;
  void store_results(const ItemRange& range, std::vector<PixelResult>& results) override;
  void checkpoint() override;
  void finish(bool complete) override;  // complete: canonical records, then the last write
  std::string note() const override;    // attractors found so far

  const BasinsContent& written() const { return written_; }

 private:
  int global_label(const Attractor& a, std::uint64_t pixel);
  void canonicalise();
  BasinsContent numbered(bool complete) const;  // attractors by pixel count, labels renumbered
  void write(bool complete);

  const Scene& scene_;
  CensusOptions census_;
  BasinEntropyOptions entropy_;
  std::string path_;
  BasinsContent content_;  // labels index into content_.attractors (discovery order here)
  BasinsContent written_;
  std::uint64_t done_ = 0;
  bool dirty_ = false;
};

}  // namespace vibromap::detail
